#include "motiongraph/graph/bridges.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

// Frames 0..99 walk (tag 0), 100..199 run (tag 1); window 4.
struct WalkRun {
  std::vector<TagMask> tags = std::vector<TagMask>(200, 0);
  std::vector<std::vector<char>> cores = {std::vector<char>(200, 0), std::vector<char>(200, 0)};
  WalkRun() {
    for (int f = 0; f < 200; ++f) tags[f] = f < 100 ? 1 : 2;
    for (int f = 20; f < 80; ++f) cores[0][f] = 1;
    for (int f = 120; f < 180; ++f) cores[1][f] = 1;
  }
};

Transition t(int from, int to, float d) { return Transition{from, to, d, 0, 0, 0}; }

TEST(Bridges, BestCandidatesBetweenCoresInEachDirection) {
  WalkRun s;
  BridgeSettings settings;
  settings.per_tag_pair = 2;
  settings.locality_radius = 3;
  const std::vector<Transition> candidates = {
      t(30, 150, 9.0f), t(31, 151, 5.0f),   // walk -> run, near each other: only the better one
      t(50, 170, 7.0f),                      // walk -> run, the second bridge
      t(60, 160, 7.5f),                      // walk -> run, third best: over the limit of 2
      t(10, 150, 1.0f),                      // leaves outside the walk core
      t(40, 190, 1.0f),                      // lands outside the run core
      t(140, 40, 8.0f),                      // run -> walk
      t(98, 104, 0.5f),                      // windows mixing walk and run frames: no bridge
      t(30, 60, 0.1f),                       // walk -> walk: no bridge
  };
  auto bridges = select_bridges(candidates, {}, s.tags, s.cores, 4, settings);
  ASSERT_EQ(bridges.size(), 3u);
  EXPECT_EQ(bridges[0].from_frame, 31);
  EXPECT_EQ(bridges[1].from_frame, 50);
  EXPECT_EQ(bridges[2].from_frame, 140);
}

TEST(Bridges, NoneWhereSelectedTransitionsAlreadyJoinTheCores) {
  WalkRun s;
  const std::vector<Transition> candidates = {t(31, 151, 5.0f), t(140, 40, 8.0f)};
  const std::vector<Transition> selected = {t(45, 165, 2.0f)};  // walk core -> run core
  auto bridges = select_bridges(candidates, selected, s.tags, s.cores, 4, {});
  ASSERT_EQ(bridges.size(), 1u);
  EXPECT_EQ(bridges[0].from_frame, 140);
  // A tag without a core gets none; nor do bridges when switched off.
  s.cores[1].clear();
  EXPECT_TRUE(select_bridges(candidates, {}, s.tags, s.cores, 4, {}).empty());
  BridgeSettings off;
  off.per_tag_pair = 0;
  EXPECT_TRUE(select_bridges(candidates, {}, WalkRun().tags, WalkRun().cores, 4, off).empty());
}

}  // namespace
}  // namespace mg
