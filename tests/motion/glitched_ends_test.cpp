// Frames cut off by a capture glitch at a clip's ends: 16_15's first two (measured by hand: its
// left hand 0.92 m from the third frame's), a glitch put at a clean clip's end, none where the
// motion is fast but smooth, none in the middle, and the loader's numbering of what is left.
#include "motiongraph/motion/glitched_ends.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "motion/glitched.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/motion/capture_glitches.h"
#include "motiongraph/motion/clip_loader.h"
#include "temp_folder.h"
#include "test_data.h"

namespace mg {
namespace {

using test::largest_step;
using test::with_turn;

TEST(GlitchedEnds, SixteenFifteenOpensOnTwoFramesOfALeftArmElsewhere) {
  const Clip whole = test::load_whole_data_clip("cmu/16/16_15.amc");
  const GlitchedEnds found = find_glitched_ends(whole.skeleton, whole.motion);
  EXPECT_EQ(found.leading, 2);
  EXPECT_EQ(found.trailing, 0);
  EXPECT_NEAR(found.leading_jump_m, 0.92, 0.01);
  EXPECT_EQ(found.leading_jump_m, largest_step(whole.skeleton, whole.motion, 1));
  EXPECT_EQ(found.leading_joint.front(), 'l') << found.leading_joint;  // the left arm's
  // The steps either side are a fraction of it; the motion after it is smooth.
  EXPECT_LT(largest_step(whole.skeleton, whole.motion, 0), 0.05);
  EXPECT_LT(largest_step(whole.skeleton, whole.motion, 2), 0.05);
  // The loader drops them: the clip is the file from its third frame on.
  const Clip loaded = test::load_data_clip("cmu/16/16_15.amc");
  EXPECT_EQ(loaded.glitched_leading_frames, 2);
  EXPECT_EQ(loaded.glitched_trailing_frames, 0);
  ASSERT_EQ(loaded.motion.frame_count, whole.motion.frame_count - 2);
  for (int f : {0, 100, loaded.motion.frame_count - 1}) {
    for (int j = 0; j < loaded.motion.joint_count; ++j) {
      EXPECT_EQ(loaded.motion.rotations(f)[j].coeffs(), whole.motion.rotations(f + 2)[j].coeffs());
    }
  }
  EXPECT_EQ(whole.glitched_leading_frames, 0);  // kept
}

TEST(GlitchedEnds, CleanClipsKeepEveryFrame) {
  for (const char* file : {"cmu/16/16_16.amc", "cmu/16/16_35.amc", "cmu/16/16_57.amc", "bvh/131_01.bvh"}) {
    const Clip clip = test::load_whole_data_clip(file);
    const GlitchedEnds found = find_glitched_ends(clip.skeleton, clip.motion);
    EXPECT_EQ(found.leading, 0) << file;
    EXPECT_EQ(found.trailing, 0) << file;
  }
}

TEST(GlitchedEnds, AGlitchAtTheEndIsCutOffOneInTheMiddleIsNot) {
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  const int n = clean.motion.frame_count;
  // The last three frames' right upper arm turned by 100 degrees: a glitch before them.
  const Clip tail = with_turn(clean, "rhumerus", n - 3, n - 1, 1.745);
  const GlitchedEnds found = find_glitched_ends(tail.skeleton, tail.motion);
  EXPECT_EQ(found.leading, 0);
  EXPECT_EQ(found.trailing, 3);
  EXPECT_GE(found.trailing_jump_m, kGlitchJumpM);
  EXPECT_EQ(found.trailing_jump_m, largest_step(tail.skeleton, tail.motion, n - 4));
  Clip dropped = tail;
  const GlitchedEnds again = drop_glitched_ends(dropped);
  EXPECT_EQ(again.trailing, 3);
  EXPECT_EQ(dropped.motion.frame_count, n - 3);
  EXPECT_EQ(dropped.glitched_trailing_frames, 3);
  EXPECT_EQ(find_glitched_ends(dropped.skeleton, dropped.motion).trailing, 0);
  // The same frames a second in: the capture's, left.
  const Clip middle = with_turn(clean, "rhumerus", 120, 122, 1.745);
  const GlitchedEnds none = find_glitched_ends(middle.skeleton, middle.motion);
  EXPECT_EQ(none.leading + none.trailing, 0);
  // A quarter second in, at most: frames 40 in (a third of a second at 120 fps) are left.
  const Clip later = with_turn(clean, "rhumerus", 0, 39, 1.745);
  EXPECT_EQ(find_glitched_ends(later.skeleton, later.motion).leading, 0);
  const Clip within = with_turn(clean, "rhumerus", 0, 19, 1.745);
  EXPECT_EQ(find_glitched_ends(within.skeleton, within.motion).leading, 20);
}

TEST(GlitchedEnds, AShortClipsEndsAreMeasuredWhereTheyMeet) {
  // 50 frames at 120 fps: the windows of a quarter second (30 steps) at either end overlap. A
  // glitch before the last 18 frames (step 31, just past the first window) is found.
  const Clip short_clip = test::first_frames(test::load_whole_data_clip("cmu/16/16_16.amc"), 50);
  const Clip glitched = with_turn(short_clip, "rhumerus", 32, 49, 1.745);
  const GlitchedEnds found = find_glitched_ends(glitched.skeleton, glitched.motion);
  EXPECT_EQ(found.leading, 0);
  EXPECT_EQ(found.trailing, 18);
  EXPECT_EQ(found.trailing_jump_m, largest_step(glitched.skeleton, glitched.motion, 31));
  const GlitchedEnds none = find_glitched_ends(short_clip.skeleton, short_clip.motion);
  EXPECT_EQ(none.leading + none.trailing, 0);
}

TEST(GlitchedEnds, TheEndsAreTheGlitchesOfTheWholeClipThere) {
  // Every length from 4 frames to past two windows (30 fps: 7 frames a window), a limb out and
  // back (a glitch) or the root moved on twice (15 m/s each: none) at each frame: the ends found
  // from the windows alone are those the glitches of the whole clip give (the last among the
  // first window's steps, two frames left; the first among the last window's after it).
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  Clip slow = clean;
  slow.motion = test::every_nth_frame(clean, 4, 30.0);
  const int window = 7;
  const int root = slow.skeleton.translation_slot(0);
  ASSERT_GE(root, 0);
  for (int frames = 4; frames <= 2 * window + 8; ++frames) {
    for (int at = 1; at + 1 < frames; ++at) {
      for (const bool out_and_back : {true, false}) {
        Clip clip = test::first_frames(slow, frames);
        if (out_and_back) {
          clip = with_turn(clip, "rhumerus", at, at, 1.745);
        } else {
          for (int f = at; f < frames; ++f) clip.motion.translations(f)[root].x() += f == at ? 0.5 : 1.0;
        }
        const std::vector<CaptureGlitch> all = find_capture_glitches(clip.skeleton, clip.motion);
        int leading = 0, trailing = 0;
        for (const CaptureGlitch& g : all) {
          if (g.frame < std::min(window, frames - 3)) leading = g.frame + 1;
        }
        for (const CaptureGlitch& g : all) {
          if (g.frame >= std::max(leading + 1, frames - 1 - window) && g.frame < frames - 1) {
            trailing = frames - 1 - g.frame;
            break;
          }
        }
        const GlitchedEnds found = find_glitched_ends(clip.skeleton, clip.motion);
        EXPECT_EQ(found.leading, leading) << frames << " frames, at " << at << (out_and_back ? " out and back" : "");
        EXPECT_EQ(found.trailing, trailing) << frames << " frames, at " << at << (out_and_back ? " out and back" : "");
      }
    }
  }
}

TEST(GlitchedEnds, FastSmoothMotionIsNoGlitch) {
  // The clip played 12 times as fast (every 12th frame at 120 fps): its hands move over 20 m/s
  // and 0.2 m a frame, but no faster in one frame than in the next.
  const Clip clean = test::load_whole_data_clip("cmu/16/16_35.amc");  // a run
  const Motion fast = test::every_nth_frame(clean, 12, 120.0);
  double fastest = 0.0;
  for (int f = 0; f + 1 < fast.frame_count; ++f) fastest = std::max(fastest, largest_step(clean.skeleton, fast, f));
  ASSERT_GT(fastest, kGlitchJumpM);
  ASSERT_GT(fastest * fast.fps, kGlitchSpeedMps);
  const GlitchedEnds found = find_glitched_ends(clean.skeleton, fast);
  EXPECT_EQ(found.leading + found.trailing, 0);
  EXPECT_TRUE(glitch_free_parts(clean.skeleton, fast).glitches.empty());  // nor within it
}

TEST(GlitchedEnds, ASecondGlitchTheFirstCutBringsToTheStartIsCutToo) {
  // The right arm elsewhere for frames 0-19 and the left for 20-39 (120 fps): glitches at steps
  // 19 and 39. Step 39 lies past the file's first quarter second (30 steps) but 19 steps into
  // what the first cut leaves. A clip read, written and read again used to lose those 20 frames
  // then (CMU 03_02: 341 frames read, 315 read back).
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  const int n = clean.motion.frame_count;
  const Clip glitched = with_turn(with_turn(clean, "rhumerus", 0, 19, 1.745), "lhumerus", 20, 39, 1.745);
  EXPECT_EQ(find_glitched_ends(glitched.skeleton, glitched.motion).leading, 20);  // one look: the first
  Clip dropped = glitched;
  const GlitchedEnds found = drop_glitched_ends(dropped);
  EXPECT_EQ(found.leading, 40);
  EXPECT_EQ(found.trailing, 0);
  EXPECT_EQ(found.leading_jump_m, std::max(largest_step(glitched.skeleton, glitched.motion, 19),
                                           largest_step(glitched.skeleton, glitched.motion, 39)));
  EXPECT_EQ(dropped.glitched_leading_frames, 40);
  ASSERT_EQ(dropped.motion.frame_count, n - 40);
  EXPECT_EQ(dropped.motion.rotations(0)[1].coeffs(), clean.motion.rotations(40)[1].coeffs());
  const GlitchedEnds again = drop_glitched_ends(dropped);
  EXPECT_EQ(again.leading + again.trailing, 0);
  EXPECT_EQ(dropped.motion.frame_count, n - 40);

  // Through the reader: the file, then what the reader made of it written and read again.
  test::TempFolder folder("glitched-ends");
  const std::string first = folder.write("glitched.bvh", write_bvh(glitched.skeleton, glitched.motion, {}));
  ClipLoader loader{ClipLoadSettings{}};
  auto read = loader.load(first);
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_EQ(read->clip.motion.frame_count, n - 40);
  EXPECT_EQ(read->clip.glitched_leading_frames, 40);
  const std::string second = folder.write("again.bvh", write_bvh(read->clip.skeleton, read->clip.motion, {}));
  auto back = loader.load(second);
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back->clip.motion.frame_count, n - 40);
  EXPECT_EQ(back->clip.glitched_leading_frames, 0);
}

}  // namespace
}  // namespace mg
