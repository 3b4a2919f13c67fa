// The type a steering session asked for none starts in: the one that travels, not the one most
// nodes carry.
#include "motiongraph/synthesis/travelling_type.h"

#include <algorithm>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/motion/resample.h"
#include "motiongraph/synthesis/controller.h"
#include "test_data.h"

namespace mg {
namespace {

constexpr int kWindow = 10;

// The pruned graph of `db` with transitions between these (from, to) frames, unaligned.
MotionGraph graph_of(const MotionDatabase& db, std::vector<std::pair<int, int>> pairs) {
  std::sort(pairs.begin(), pairs.end());  // by (from_frame, to_frame), as the graph wants them
  std::vector<Transition> transitions;
  for (const auto& [from, to] : pairs) {
    Transition t;
    t.from_frame = from;
    t.to_frame = to;
    transitions.push_back(t);
  }
  auto graph = build_motion_graph(db, transitions, kWindow);
  EXPECT_TRUE(graph) << graph.error().to_string();
  if (!graph) return {};
  EXPECT_TRUE(prune_motion_graph(*graph, {}));
  return std::move(*graph);
}

// A walk (16_15), looping back from near its end, and a pose held as long, "dance", looping on
// itself at six places (so most nodes are the pose's), the two joined each way.
TEST(TravellingType, TheTypeThatTravelsNotTheOneMostNodesCarry) {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip pose = test::held_pose(walk, 0, walk.motion.frame_count);  // 3.9 s: 118 frames at 30 fps
  DatabaseClip held;
  held.name = "pose";
  held.first_frame = db.frame_count();
  held.motion = *resample(pose.motion, db.fps);
  held.frame_count = held.motion.frame_count;
  db.clips.push_back(std::move(held));
  const int walk_frames = db.clips[0].frame_count;
  const int b = db.clips[1].first_frame;
  db.tag_names = {"walk", "dance"};
  db.tag_ranges = {TagRange{0, 0, walk_frames}, TagRange{1, b, db.clips[1].frame_count}};
  const int k = kWindow;
  std::vector<std::pair<int, int>> pairs = {
      {walk_frames - 2 * k, 2 * k - 1},  // the walk loops
      {40, b + 12},                      // walk -> pose
      {b + 100, 60},                     // pose -> walk
  };
  for (int i = 0; i < 6; ++i) pairs.emplace_back(b + 40 + 10 * i, b + 15 + 10 * i);  // the pose loops
  const MotionGraph graph = graph_of(db, pairs);
  ASSERT_GT(graph.node_count(), 0);
  auto context = make_synthesis_context(db, graph);
  ASSERT_TRUE(context) << context.error().to_string();
  ASSERT_EQ(most_played_type(*context), TagMask{0b10});  // the pose's nodes outnumber the walk's
  EXPECT_EQ(travelling_type(*context), TagMask{0b01});
  const int start = controller_start_node(*context, 0);
  EXPECT_LT(graph.nodes[static_cast<size_t>(start)].frame, b) << "starts in the walk";
  // Asked for a type, that type's.
  EXPECT_GE(graph.nodes[static_cast<size_t>(controller_start_node(*context, 0b10))].frame, b);
  // The walk held still too: no type travels.
  MotionDatabase still = db;
  still.clips[0].motion = *resample(test::held_pose(walk, 0, walk.motion.frame_count).motion, db.fps);
  auto still_context = make_synthesis_context(still, graph);
  ASSERT_TRUE(still_context) << still_context.error().to_string();
  EXPECT_EQ(travelling_type(*still_context), TagMask{0});
}

// Walks slowed to half their pace (0.6 m/s, as the 8-subject library's walks with their stops)
// beside a run of fewer frames: the walk, not the run, though the run is faster.
TEST(TravellingType, WalkingBeforeRunning) {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_35.amc"});
  const int slot = 0;
  for (int c = 0; c < 2; ++c) {
    Motion& walk = db.clips[static_cast<size_t>(c)].motion;
    const Vec3 first = walk.translations(0)[slot];
    for (int f = 0; f < walk.frame_count; ++f) {
      Vec3& root = walk.translations(f)[slot];
      root.x() = first.x() + 0.5 * (root.x() - first.x());
      root.z() = first.z() + 0.5 * (root.z() - first.z());
    }
  }
  const int run = db.clips[2].first_frame;
  db.tag_names = {"walk", "run"};
  db.tag_ranges = {TagRange{0, 0, run}, TagRange{1, run, db.frame_count() - run}};
  const int k = kWindow;
  const int second = db.clips[1].first_frame;
  const MotionGraph graph = graph_of(db, {{second - 2 * k, second + 2 * k},           // walk 1 -> walk 2
                                          {run - 2 * k, 2 * k - 1},                   // walk 2 -> walk 1
                                          {second + 40, run + k},                     // walk 2 -> run
                                          {db.frame_count() - 2 * k, second + 60}});  // run -> walk 2
  ASSERT_GT(graph.node_count(), 0);
  auto context = make_synthesis_context(db, graph);
  ASSERT_TRUE(context) << context.error().to_string();
  EXPECT_EQ(travelling_type(*context), TagMask{0b01});
}

}  // namespace
}  // namespace mg
