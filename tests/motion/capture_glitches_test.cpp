// Capture glitches anywhere in a clip and the parts kept between them: clean captures are one
// part, a limb put elsewhere for a few frames is cut out, one put elsewhere for longer is a part
// of its own, parts under a quarter second go, the longest stays when none is that long, and a
// turn too small to jump 0.2 m in a frame is no glitch.
#include "motiongraph/motion/capture_glitches.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "motion/glitched.h"
#include "motiongraph/motion/glitched_ends.h"
#include "test_data.h"

namespace mg {
namespace {

using Parts = std::vector<std::pair<int, int>>;
using test::largest_step;
using test::with_turn;

TEST(CaptureGlitches, CleanCapturesAreOnePart) {
  // (Read whole: 111_36.bvh's converter rest frame would be a glitch; the reader drops it first.)
  for (const char* file : {"cmu/16/16_16.amc", "cmu/16/16_35.amc", "cmu/16/16_57.amc", "bvh/131_01.bvh"}) {
    const Clip clip = test::load_whole_data_clip(file);
    const GlitchFreeParts found = glitch_free_parts(clip.skeleton, clip.motion);
    EXPECT_TRUE(found.glitches.empty()) << file;
    EXPECT_EQ(found.parts, (Parts{{0, clip.motion.frame_count}})) << file;
    EXPECT_EQ(found.dropped_frames(clip.motion.frame_count), 0) << file;
  }
}

TEST(CaptureGlitches, SixteenFifteensOpeningGlitchLeavesTheGlitchedEndsPart) {
  // Read whole, 16_15 opens on two frames of its left arm elsewhere: the part before the glitch
  // is under a quarter second, so the parts keep what glitched_ends.h keeps.
  const Clip whole = test::load_whole_data_clip("cmu/16/16_15.amc");
  const int n = whole.motion.frame_count;
  const GlitchFreeParts found = glitch_free_parts(whole.skeleton, whole.motion);
  ASSERT_EQ(found.glitches.size(), 1u);
  EXPECT_EQ(found.glitches[0].frame, 1);
  EXPECT_EQ(found.glitches[0].jump_m, largest_step(whole.skeleton, whole.motion, 1));
  const GlitchedEnds ends = find_glitched_ends(whole.skeleton, whole.motion);
  EXPECT_EQ(found.parts, (Parts{{ends.leading, n - ends.leading}}));
  EXPECT_EQ(found.dropped_frames(n), 2);
}

TEST(CaptureGlitches, ALimbElsewhereForAFewFramesIsCutOut) {
  // 16_16's right upper arm turned by 100 degrees for frames 200..209 (a twelfth of a second at
  // 120 fps): glitches before and after them, the frames between dropped.
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  const int n = clean.motion.frame_count;
  ASSERT_EQ(clean.motion.fps, 120.0);
  const Clip glitched = with_turn(clean, "rhumerus", 200, 209, 1.745);
  const GlitchFreeParts found = glitch_free_parts(glitched.skeleton, glitched.motion);
  ASSERT_EQ(found.glitches.size(), 2u);
  EXPECT_EQ(found.glitches[0].frame, 199);
  EXPECT_EQ(found.glitches[1].frame, 209);
  for (const CaptureGlitch& g : found.glitches) {
    EXPECT_EQ(g.jump_m, largest_step(glitched.skeleton, glitched.motion, g.frame));
    EXPECT_GE(g.jump_m, kGlitchJumpM);
    EXPECT_EQ(g.joint.front(), 'r') << g.joint;  // the right arm's
  }
  EXPECT_EQ(found.parts, (Parts{{0, 200}, {210, n - 210}}));
  EXPECT_EQ(found.dropped_frames(n), 10);
  // Half a second elsewhere is a part of its own (the capture's limb may be right there).
  const Clip longer = with_turn(clean, "rhumerus", 200, 259, 1.745);
  EXPECT_EQ(glitch_free_parts(longer.skeleton, longer.motion).parts, (Parts{{0, 200}, {200, 60}, {260, n - 260}}));
  // A part of 29 frames goes, one of 30 (a quarter second) stays.
  const Clip twenty_nine = with_turn(clean, "rhumerus", 200, 228, 1.745);
  EXPECT_EQ(glitch_free_parts(twenty_nine.skeleton, twenty_nine.motion).parts, (Parts{{0, 200}, {229, n - 229}}));
  const Clip thirty = with_turn(clean, "rhumerus", 200, 229, 1.745);
  EXPECT_EQ(glitch_free_parts(thirty.skeleton, thirty.motion).parts, (Parts{{0, 200}, {200, 30}, {230, n - 230}}));
}

TEST(CaptureGlitches, ATurnThatJumpsLessThanTheRuleIsNoGlitch) {
  // 20 degrees moves the hand under 0.2 m in a frame: no glitch, whatever the steps around it.
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  const Clip turned = with_turn(clean, "rhumerus", 200, 209, 0.35);
  ASSERT_LT(largest_step(turned.skeleton, turned.motion, 199), kGlitchJumpM);
  EXPECT_TRUE(glitch_free_parts(turned.skeleton, turned.motion).glitches.empty());
}

TEST(CaptureGlitches, WhenNoPartLastsAQuarterSecondTheLongestStays) {
  const Clip short_clip = test::first_frames(test::load_whole_data_clip("cmu/16/16_16.amc"), 50);
  // Glitches after frames 15 and 32: parts of 16, 17 and 17 frames; the longer of the clip's
  // ends stays, not the arm elsewhere between the glitches.
  const Clip glitched = with_turn(short_clip, "rhumerus", 16, 32, 1.745);
  const GlitchFreeParts found = glitch_free_parts(glitched.skeleton, glitched.motion);
  ASSERT_EQ(found.glitches.size(), 2u);
  EXPECT_EQ(found.parts, (Parts{{33, 17}}));
  EXPECT_EQ(found.dropped_frames(50), 33);
  // Glitches after frames 16 and 32: the ends are 17 frames each, the first stays.
  const Clip even = with_turn(short_clip, "rhumerus", 17, 32, 1.745);
  EXPECT_EQ(glitch_free_parts(even.skeleton, even.motion).parts, (Parts{{0, 17}}));
}

TEST(CaptureGlitches, ALimbElsewhereForOneFrameStepsOutAndBack) {
  // Frame 200 alone turned: two glitch-sized steps in a row, out and back, the frame between them
  // dropped. The rule for one step alone would see neither (each has a large neighbour).
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  const int n = clean.motion.frame_count;
  const Clip glitched = with_turn(clean, "rhumerus", 200, 200, 1.745);
  const GlitchFreeParts found = glitch_free_parts(glitched.skeleton, glitched.motion);
  ASSERT_EQ(found.glitches.size(), 2u);
  EXPECT_EQ(found.glitches[0].frame, 199);
  EXPECT_EQ(found.glitches[1].frame, 200);
  EXPECT_EQ(found.glitches[1].jump_m, largest_step(glitched.skeleton, glitched.motion, 200));
  EXPECT_EQ(found.parts, (Parts{{0, 200}, {201, n - 201}}));
  // At 30 fps (every 4th frame) the same arm out for one frame steps under 20 m/s: out and back,
  // it is found at any rate.
  Clip slow = clean;
  slow.motion = test::every_nth_frame(clean, 4, 30.0);
  const Clip slow_glitched = with_turn(slow, "rhumerus", 50, 50, 1.745);
  ASSERT_LT(largest_step(slow_glitched.skeleton, slow_glitched.motion, 49) * 30.0, kGlitchSpeedMps);
  EXPECT_TRUE(glitch_free_parts(slow.skeleton, slow.motion).glitches.empty());
  const GlitchFreeParts slow_found = glitch_free_parts(slow_glitched.skeleton, slow_glitched.motion);
  ASSERT_EQ(slow_found.glitches.size(), 2u);
  EXPECT_EQ(slow_found.glitches[0].frame, 49);
  // A limb that steps out twice and stays (frames 200 on turned by 100 degrees, 201 on by 100
  // more) is no out and back: the second step has a large neighbour, the first too.
  const Clip twice = with_turn(with_turn(clean, "rhumerus", 200, n - 1, 1.745), "rhumerus", 201, n - 1, 1.745);
  EXPECT_TRUE(glitch_free_parts(twice.skeleton, twice.motion).glitches.empty());
}

TEST(CaptureGlitches, PartsOfARangeCountOnlyTheGlitchesWithinIt) {
  // Glitches after frames 199 and 209 of the clip. Frames 100..299 hold both: cut there,
  // numbered from frame 100. Frames 205..404 hold the second only; frames 0..199 and 210..409
  // neither (a glitch's step must lie within the frames).
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  const Clip glitched = with_turn(clean, "rhumerus", 200, 209, 1.745);
  const std::vector<CaptureGlitch> glitches = find_capture_glitches(glitched.skeleton, glitched.motion);
  ASSERT_EQ(glitches.size(), 2u);
  const GlitchFreeParts both = glitch_free_parts(glitches, 100, 200, 120.0);
  ASSERT_EQ(both.glitches.size(), 2u);
  EXPECT_EQ(both.glitches[0].frame, 99);
  EXPECT_EQ(both.parts, (Parts{{0, 100}, {110, 90}}));
  const GlitchFreeParts second = glitch_free_parts(glitches, 205, 200, 120.0);
  ASSERT_EQ(second.glitches.size(), 1u);
  EXPECT_EQ(second.parts, (Parts{{5, 195}}));  // frames 205..209 (5) under a quarter second
  EXPECT_EQ(glitch_free_parts(glitches, 0, 200, 120.0).parts, (Parts{{0, 200}}));
  EXPECT_EQ(glitch_free_parts(glitches, 210, 200, 120.0).parts, (Parts{{0, 200}}));
  // Frames 205..215: 205..209 (the arm elsewhere, a glitch before them) and 210..215, neither a
  // quarter second long: the end with no glitch beyond it stays (6 frames).
  EXPECT_EQ(glitch_free_parts(glitches, 205, 11, 120.0).parts, (Parts{{5, 6}}));
  // Frames 195..204: 195..199 and 200..204 (the arm elsewhere, a glitch after them): the first.
  EXPECT_EQ(glitch_free_parts(glitches, 195, 10, 120.0).parts, (Parts{{0, 5}}));
  // Placed in the file: the frame after which the arm jumps, and when it lands.
  const std::vector<FileGlitch> placed = in_file_frames(both.glitches, 101, 120.0);
  EXPECT_EQ(placed[0].frame, 200);  // the file's frame 200 (1-based) is the clip's 199
  EXPECT_DOUBLE_EQ(placed[0].seconds, 200.0 / 120.0);
  EXPECT_EQ(placed[1].frame, 210);
  EXPECT_EQ(placed[1].joint, glitches[1].joint);
}

TEST(CaptureGlitches, MotionsTooShortToJudgeAreOnePart) {
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  const Clip glitched = with_turn(clean, "rhumerus", 2, 2, 1.745);
  const Motion three = glitched.motion.slice(0, 3);
  const GlitchFreeParts found = glitch_free_parts(glitched.skeleton, three);
  EXPECT_TRUE(found.glitches.empty());
  EXPECT_EQ(found.parts, (Parts{{0, 3}}));
}

}  // namespace
}  // namespace mg
