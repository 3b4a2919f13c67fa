#include "motiongraph/motion/resample.h"

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(Resample, QuarterRateKeepsEveryFourthFrameExactly) {
  Clip clip = test::load_data_clip("cmu/16/16_35.amc");
  auto out = resample(clip.motion, 30.0);
  ASSERT_TRUE(out);
  EXPECT_EQ(out->frame_count, (clip.motion.frame_count - 1) / 4 + 1);
  EXPECT_EQ(out->fps, 30.0);
  for (int i = 0; i < out->frame_count; ++i) {
    for (int j = 0; j < clip.motion.joint_count; ++j) {
      EXPECT_LT(out->rotations(i)[j].angularDistance(clip.motion.rotations(4 * i)[j]), 1e-9);
    }
    EXPECT_EQ(out->translations(i)[0], clip.motion.translations(4 * i)[0]);
  }
}

TEST(Resample, InBetweenFramesInterpolate) {
  Clip clip = test::load_data_clip("cmu/16/16_35.amc");
  auto out = resample(clip.motion, 80.0);  // source time 1.5 frames per output frame
  ASSERT_TRUE(out);
  EXPECT_NEAR(out->duration_s(), clip.motion.duration_s(), 1.0 / 80.0);
  const int i = 7;  // source time 10.5: halfway between frames 10 and 11
  const Vec3 expected = 0.5 * (clip.motion.translations(10)[0] + clip.motion.translations(11)[0]);
  EXPECT_TRUE(out->translations(i)[0].isApprox(expected, 1e-12));
  for (int j = 0; j < clip.motion.joint_count; ++j) {
    const Quat& a = clip.motion.rotations(10)[j];
    const Quat& b = clip.motion.rotations(11)[j];
    const Quat& m = out->rotations(i)[j];
    // Slerp's midpoint is equally far from both ends, at half their distance.
    EXPECT_NEAR(m.angularDistance(a), m.angularDistance(b), 1e-9);
    EXPECT_NEAR(m.angularDistance(a), 0.5 * a.angularDistance(b), 1e-9);
  }
}

TEST(Resample, RejectsBadRates) {
  Clip clip = test::load_data_clip("cmu/16/16_35.amc");
  EXPECT_FALSE(resample(clip.motion, 0.0));
  EXPECT_FALSE(resample(clip.motion, -30.0));
  EXPECT_FALSE(resample(clip.motion, std::numeric_limits<double>::quiet_NaN()));
  // A rate that would make more joint poses than a clip may hold: an error, not gigabytes.
  const double poses = clip.motion.duration_s() * 1e6 * clip.motion.joint_count;
  ASSERT_GT(poses, 5e7);
  auto huge = resample(clip.motion, 1e6);
  ASSERT_FALSE(huge);
  EXPECT_NE(huge.error().message.find("over the 50 million joint poses a clip may hold"), std::string::npos)
      << huge.error().message;
}

}  // namespace
}  // namespace mg
