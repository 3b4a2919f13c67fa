#include "motiongraph/motion/clip_doubts.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

bool has(const ClipDoubts& doubts, const std::string& words) {
  for (const std::string& d : doubts.phrases()) {
    if (d.find(words) != std::string::npos) return true;
  }
  return false;
}

// Two joints per frame: one at `low + wobble`, one 1.5 m above it.
std::vector<Vec3> figure(int frames, double low, double wobble) {
  std::vector<Vec3> p;
  for (int f = 0; f < frames; ++f) {
    const double y = low + wobble * ((f % 10) / 9.0);
    p.emplace_back(0.1 * f, y, 0.0);
    p.emplace_back(0.1 * f, y + 1.5, 0.0);
  }
  return p;
}

TEST(ClipDoubts, AFigureOffTheFloorIsNamedWithItsLowestJointsHeights) {
  const std::vector<ContactMask> planted(100, contact_bit(FootSide::kLeft, FootPart::kToe));
  EXPECT_TRUE(clip_doubts(figure(100, 0.0, 0.1), 2, 30.0, planted).empty());
  EXPECT_TRUE(clip_doubts(figure(100, -0.2, 0.1), 2, 30.0, planted).empty());  // within 0.25 m
  // Lowest joint from -0.80 to -0.70 m: the 2 % and 98 % quantiles of each frame's lowest.
  const auto below = clip_doubts(figure(100, -0.8, 0.1), 2, 30.0, planted);
  ASSERT_EQ(below.floor.size(), 1u);
  EXPECT_EQ(below.floor[0], "its lowest joint is 0.70-0.80 m below the floor (y = 0)");
  const auto above = clip_doubts(figure(100, 0.5, 0.1), 2, 30.0, planted);
  ASSERT_EQ(above.floor.size(), 1u);
  EXPECT_EQ(above.floor[0], "its lowest joint stays 0.50-0.60 m above the floor (y = 0)");
}

TEST(ClipDoubts, FeetThatNeverRestAreNamedInClipsOfASecondOrMore) {
  const std::vector<Vec3> p = figure(60, 0.0, 0.05);
  const std::vector<ContactMask> never(60, 0);
  EXPECT_TRUE(has(clip_doubts(p, 2, 30.0, never), "no foot rests on the floor in any frame"));
  EXPECT_TRUE(clip_doubts(p, 2, 90.0, never).empty());  // 0.67 s: too short to judge
  EXPECT_TRUE(clip_doubts(p, 2, 30.0, {}).empty());     // feet unknown: not judged
  std::vector<ContactMask> once = never;
  once[30] = contact_bit(FootSide::kRight, FootPart::kAnkle);
  EXPECT_TRUE(clip_doubts(p, 2, 30.0, once).empty());
  const auto both = clip_doubts(figure(60, -0.8, 0.1), 2, 30.0, never);
  EXPECT_EQ(both.floor.size(), 2u);
  EXPECT_EQ(clip_doubt_line("07_12", both),
            "07_12: " + both.floor[0] + ", and " + both.floor[1] +
                "; its root translation may be wrong (the distances compare clips as read, so the graph may join "
                "it to nothing)");
}

// A captured walk is on the floor with its feet planted; the same walk with its root's
// translation lowered by 0.8 m (a converter's offset) sinks below the floor by that much.
TEST(ClipDoubts, ACapturedWalkHasNoneAndItsRootLoweredSinks) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  EXPECT_TRUE(clip_doubts(clip.skeleton, clip.motion).empty());
  ASSERT_GE(clip.motion.translated_count, 1);
  for (int f = 0; f < clip.motion.frame_count; ++f) clip.motion.translations(f)[0].y() -= 0.8;
  const auto doubts = clip_doubts(clip.skeleton, clip.motion);
  ASSERT_EQ(doubts.floor.size(), 1u) << clip_doubts_text(doubts);
  EXPECT_TRUE(has(doubts, "m below the floor (y = 0)")) << doubts.floor[0];
  // Planted feet are found on the clip's own floor, so they still rest: only the height is wrong.
  EXPECT_FALSE(has(doubts, "no foot rests"));
}

// A figure read in the wrong unit (a walk in metres read as centimetres, or as millimetres taken
// for metres) is named by its size alone: its floor and feet are a person's limits, not judged.
TEST(ClipDoubts, AFigureOfNoPersonsSizeIsNamedAloneByItsSize) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const std::vector<Vec3> positions = world_positions(clip.skeleton, clip.motion);
  const int joints = clip.skeleton.joint_count();
  const auto scaled = [&](double factor) {
    std::vector<Vec3> p = positions;
    for (Vec3& v : p) v *= static_cast<float>(factor);
    return clip_doubts(p, joints, clip.motion.fps, {});
  };
  EXPECT_TRUE(scaled(1.0).empty());
  EXPECT_TRUE(scaled(1.5).empty());  // a tall person's arms swung wide
  for (const double factor : {0.01, 0.1, 4.0, 100.0, 1e30}) {
    const ClipDoubts doubts = scaled(factor);
    EXPECT_FALSE(doubts.size.empty()) << factor;
    EXPECT_TRUE(doubts.floor.empty()) << factor;  // 100 m tall: its lowest joint off the floor, unsaid
    EXPECT_NE(clip_doubts_text(doubts).find("no person's size (0.4-4 m)"), std::string::npos) << factor;
  }
  // The figure's size is its largest extent, the median over the frames: a walk of 1.7 m by 1.7.
  const ClipDoubts tall = scaled(100.0);
  EXPECT_NE(tall.size.find("its figure is 1"), std::string::npos) << tall.size;
  EXPECT_EQ(tall.phrases(), std::vector<std::string>{tall.size});
  EXPECT_EQ(scaled(0.0).size, "its joints all lie at one point (its bones have no length)");
  ClipDoubtSettings upside_down;
  upside_down.min_figure_m = 3.0;
  upside_down.max_figure_m = 2.0;
  EXPECT_FALSE(upside_down.validate());
}

}  // namespace
}  // namespace mg
