#include "motiongraph/motion/rest_frame.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

// A two-joint skeleton turning smoothly. Frames before `added` have a zero root rotation;
// with `jump` they are a zero pose somewhere else, as a converter's added rest frame.
Motion smooth_motion(int frames, int added, bool jump) {
  JointDef root;
  root.name = "root";
  root.animated_translation = true;
  JointDef child;
  child.name = "child";
  child.parent = 0;
  Skeleton skeleton({root, child});
  Motion motion(skeleton, frames, 120.0);
  for (int f = 0; f < frames; ++f) {
    auto r = motion.rotations(f);
    if (f < added && jump) {
      r[0] = Quat::Identity();
      r[1] = Quat::Identity();
      motion.translations(f)[0] = Vec3(0, 1, 0);
    } else {
      // Without a jump the root starts at exactly zero rotation (Ry(0)) and turns on smoothly.
      r[0] = f < added ? Quat::Identity() : axis_rotation(Axis::kY, 0.01 * f);
      r[1] = axis_rotation(Axis::kX, 0.5 + 0.01 * f);
      motion.translations(f)[0] = Vec3(0.01 * f, 1, jump ? 5.0 : 0.0);
    }
  }
  return motion;
}

TEST(RestFrame, FindsAddedFramesFollowedByAJump) {
  EXPECT_EQ(leading_added_frames(smooth_motion(100, 1, true)), 1);
  EXPECT_EQ(leading_added_frames(smooth_motion(100, 2, true)), 2);
}

TEST(RestFrame, KeepsCapturedMotion) {
  EXPECT_EQ(leading_added_frames(smooth_motion(100, 0, true)), 0);
  // A root that starts at exactly zero rotation but moves on smoothly is not a rest frame.
  EXPECT_EQ(leading_added_frames(smooth_motion(100, 1, false)), 0);
  // Never more than five, never the whole clip.
  EXPECT_EQ(leading_added_frames(smooth_motion(100, 6, true)), 0);
  EXPECT_EQ(leading_added_frames(smooth_motion(3, 1, true)), 0);
}

}  // namespace
}  // namespace mg
