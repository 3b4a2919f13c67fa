// How long walking strides take for their length: exact on a walker made here, at the capture's
// clock and at wrong ones; runs, short steps, limps and too few strides are not judged; CMU's
// walks at their clock lie near the walk ratio, and read 4x slow (as amc2bvh writes them) at 4x.
#include "motiongraph/motion/walk_pace.h"

#include <cmath>

#include <gtest/gtest.h>

#include "motiongraph/motion/clip_doubts.h"
#include "motiongraph/motion/length_unit.h"
#include "motion/walker.h"
#include "test_data.h"

namespace mg {
namespace {

WalkPace pace_of(const test::Walker& w, double fps) {
  return measure_walk_pace(w.positions, test::kWalkerJoints, fps, w.contacts, w.feet);
}

TEST(WalkPace, AWalkersStridesGiveItsWalkRatioAndAWrongClockScalesIt) {
  const test::Walker w = test::walker({});  // 1.3 m strides of 1 s at 30 fps
  const WalkPace right = pace_of(w, 30.0);
  // Each ankle's plants cut off by the clip's ends are left out: 6 s of walking give 5 plants of
  // the left ankle inside the clip (at 1-5 s; the one at 0 s is cut), 5 of the right (at 0.5-4.5
  // s; the one at 5.5 s is cut), so 4 + 4 strides.
  EXPECT_EQ(right.strides, 8);
  EXPECT_NEAR(right.stride_m, 1.3, 1e-9);
  EXPECT_NEAR(right.stride_s, 1.0, 1e-9);
  const double figure = figure_size(w.positions, test::kWalkerJoints);
  EXPECT_NEAR(figure, 1.6, 0.03);
  EXPECT_DOUBLE_EQ(right.figure_m, figure);
  EXPECT_NEAR(right.walk_ratio, 1.3 / figure * 1.0 * std::sqrt(kGravityMps2 / figure), 1e-9);
  EXPECT_NEAR(right.slowdown(), right.walk_ratio / kWalkRatio, 1e-12);
  // The same frames said to be 4x longer (120 fps frames read at 30), or half as long.
  const WalkPace slow = pace_of(w, 7.5);
  EXPECT_EQ(slow.strides, right.strides);
  EXPECT_NEAR(slow.stride_s, 4.0, 1e-9);
  EXPECT_NEAR(slow.slowdown(), 4.0 * right.slowdown(), 1e-9);
  EXPECT_NEAR(pace_of(w, 60.0).slowdown(), 0.5 * right.slowdown(), 1e-9);
  // Unknown feet or contacts: nothing measured.
  EXPECT_FALSE(measure_walk_pace(w.positions, test::kWalkerJoints, 30.0, {}, w.feet).measured());
  EXPECT_FALSE(measure_walk_pace(w.positions, test::kWalkerJoints, 30.0, w.contacts, FootJoints{}).measured());
  EXPECT_EQ(WalkPace{}.slowdown(), 0.0);
}

TEST(WalkPace, OnlyAWalksStridesAreJudged) {
  // A run sinks where the feet pass: no stride of it counts.
  EXPECT_EQ(pace_of(test::walker({.vault = -1.0}), 30.0).strides, 0);
  // Steps of 0.4 m (a quarter of the figure; shuffling on the spot) are no walk's.
  EXPECT_EQ(pace_of(test::walker({.stride_m = 0.4}), 30.0).strides, 0);
  // The right foot coming down 0.3 of a stride after the left (a limp, a gallop): not a walk's
  // alternation; 0.6 of it is within 0.15 of halfway.
  EXPECT_EQ(pace_of(test::walker({.right_phase = 0.3}), 30.0).strides, 0);
  EXPECT_EQ(pace_of(test::walker({.right_phase = 0.6}), 30.0).strides, 8);
  // A body surging 15 cm forward and back twice a stride stops in it: not steady. Surging 2 cm is.
  EXPECT_EQ(pace_of(test::walker({.surge_m = 0.15}), 30.0).strides, 0);
  EXPECT_EQ(pace_of(test::walker({.surge_m = 0.02}), 30.0).strides, 8);
  // A body swaying 0.4 m side to side each stride goes under 0.8 of its path in a straight line;
  // swaying 5 cm, it goes straight enough.
  EXPECT_EQ(pace_of(test::walker({.sway_m = 0.4}), 30.0).strides, 0);
  EXPECT_EQ(pace_of(test::walker({.sway_m = 0.05}), 30.0).strides, 8);
  // Three seconds of walking leave two plants of each ankle inside the clip, one stride each: too
  // few to judge.
  const WalkPace brief = pace_of(test::walker({.strides = 3}), 30.0);
  EXPECT_EQ(brief.strides, 2);
  EXPECT_FALSE(brief.measured());
  EXPECT_EQ(brief.walk_ratio, 0.0);
}

TEST(WalkPace, AStrideUnlikeTheStridesEitherSideIsLeftOut) {
  // The left ankle's plant at 3 s 0.4 m further ahead: its stride from 2 s is 1.7 m long and the
  // one from 3 s 0.9 m, each over 20 % off the right ankle's either side (1.3 m); the right's
  // from 2.5 s lies between the two and agrees with neither. 5 of the 8 are left.
  const WalkPace long_step = pace_of(test::walker({.long_plant_m = 0.4}), 30.0);
  EXPECT_EQ(long_step.strides, 5);
  EXPECT_NEAR(long_step.stride_m, 1.3, 1e-9);
  EXPECT_EQ(pace_of(test::walker({.long_plant_m = 0.1}), 30.0).strides, 8);  // within 20 %: kept
  // The walker's fourth second (the left ankle's stride from 3 s to 4 s) played 1.6x slower: that
  // stride takes 1.6 s, the right ankle's either side of it 1.3 s (the left ankle coming down 0.38
  // and 0.62 of the way through them), the rest 1 s. In the order they start (right 0.5 s, left
  // 1 s, right 1.5 s, left 2 s, right 2.5 s, left 3 s, right 3.5 s, left 4 s), each from 2.5 s on
  // takes over 1.2x as long as its neighbours or under 1/1.2 (the last has none after it, the
  // right's next plant cut off by the clip's end): 4 strides are left.
  const WalkPace slowing = pace_of(test::walker({.slow_from_s = 3.0, .slow_to_s = 4.0, .slowdown = 1.6}), 30.0);
  EXPECT_EQ(slowing.strides, 4);
  EXPECT_NEAR(slowing.stride_s, 1.0, 1e-9);  // the strides kept are the walk's
  // 1.1x slower: the neighbours agree, and all 8 are kept.
  EXPECT_EQ(pace_of(test::walker({.slow_from_s = 3.0, .slow_to_s = 4.0, .slowdown = 1.1}), 30.0).strides, 8);
}

// The clip's own joints and contacts, at the rate it is read at: what info judges its clock on.
WalkPace walk_of(const Clip& clip) { return clip_doubts(clip.skeleton, clip.motion).walk_pace; }

TEST(WalkPace, CapturedWalksLieNearTheWalkRatioAndReadFourTimesSlowAtFourTimesIt) {
  for (const char* file : {"cmu/16/16_13.amc", "cmu/16/16_15.amc"}) {
    const WalkPace right = walk_of(test::load_data_clip(file));
    ASSERT_TRUE(right.measured()) << file;
    EXPECT_GT(right.slowdown(), 1.0 / 1.3) << file;
    EXPECT_LT(right.slowdown(), 1.3) << file;
    // Read 4x slow, as amc2bvh labels CMU's 120 fps frames: the contacts, found at the wrong
    // speeds, still find the strides.
    const WalkPace slow = walk_of(test::load_data_clip(file, std::nullopt, 30.0));
    ASSERT_TRUE(slow.measured()) << file;
    EXPECT_NEAR(slow.slowdown(), 4.0 * right.slowdown(), 0.1 * 4.0 * right.slowdown()) << file;
  }
  // Runs and jumps have no walk to judge.
  for (const char* file : {"cmu/16/16_35.amc", "cmu/16/16_01.amc", "cmu/16/16_57.amc"}) {
    EXPECT_EQ(walk_of(test::load_data_clip(file)).strides, 0) << file;
  }
}

}  // namespace
}  // namespace mg
