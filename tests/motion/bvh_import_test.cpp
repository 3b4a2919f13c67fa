#include "motiongraph/motion/bvh_import.h"

#include <numbers>
#include <utility>

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::Matrix3d rot(int axis, double degrees) {
  return Eigen::AngleAxisd(degrees * kDeg, Vec3::Unit(axis)).toRotationMatrix();
}

Clip import(const std::string& text, BvhImportSettings settings = {}) {
  if (!settings.metres_per_unit) settings.metres_per_unit = 1.0;
  auto doc = parse_bvh(text, "t.bvh");
  EXPECT_TRUE(doc) << doc.error().to_string();
  auto clip = clip_from_bvh(*doc, settings);
  EXPECT_TRUE(clip) << clip.error().to_string();
  return *clip;
}

std::string two_joint_bvh(const std::string& child_channels, const std::string& values) {
  return "HIERARCHY\nROOT r\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
         " JOINT c\n {\n  OFFSET 0 2 0\n  CHANNELS " + child_channels + "\n  End Site\n  {\n   OFFSET 1 0 0\n  }\n }\n}\n"
         "MOTION\nFrames: 1\nFrame Time: 0.04\n" + values + "\n";
}

TEST(BvhImport, EachJointUsesItsOwnRotationOrder) {
  // Root ZYX, child XYZ; the end site's world position from explicit matrix products.
  Clip clip = import(two_joint_bvh("3 Xrotation Yrotation Zrotation", "1 2 3 10 20 30 40 50 60"));
  const Eigen::Matrix3d root = rot(2, 10) * rot(1, 20) * rot(0, 30);
  const Eigen::Matrix3d child = rot(0, 40) * rot(1, 50) * rot(2, 60);
  const Vec3 expected_child = Vec3(1, 2, 3) + root * Vec3(0, 2, 0);
  const Vec3 expected_end = expected_child + root * child * Vec3(1, 0, 0);
  const auto p = world_positions(clip.skeleton, clip.motion);
  EXPECT_TRUE(p[1].isApprox(expected_child, 1e-12));
  EXPECT_TRUE(p[2].isApprox(expected_end, 1e-12));
  EXPECT_EQ(clip.skeleton.joint(1).euler_order, (ComposeOrder{Axis::kX, Axis::kY, Axis::kZ}));
  EXPECT_DOUBLE_EQ(clip.motion.fps, 25.0);
}

TEST(BvhImport, PositionChannelsReplaceTheOffset) {
  Clip clip = import(two_joint_bvh("6 Xposition Yposition Zposition Zrotation Xrotation Yrotation", "0 0 0 0 0 0 5 6 7 0 0 0"));
  const auto p = world_positions(clip.skeleton, clip.motion);
  EXPECT_TRUE(p[1].isApprox(Vec3(5, 6, 7), 1e-12)) << p[1].transpose();
}

TEST(BvhImport, ScaleAndFrameRateOverride) {
  BvhImportSettings settings;
  settings.metres_per_unit = 0.01;
  settings.fps_override = 120.0;
  Clip clip = import(two_joint_bvh("3 Zrotation Xrotation Yrotation", "100 200 300 0 0 0 0 0 0"), settings);
  const auto p = world_positions(clip.skeleton, clip.motion);
  EXPECT_TRUE(p[0].isApprox(Vec3(1, 2, 3), 1e-12));
  EXPECT_TRUE(p[2].isApprox(Vec3(1.01, 2.02, 3), 1e-12));
  EXPECT_EQ(clip.motion.fps, 120.0);
  settings.metres_per_unit = -1;
  auto doc = parse_bvh(two_joint_bvh("3 Zrotation Xrotation Yrotation", "0 0 0 0 0 0 0 0 0"), "t.bvh");
  EXPECT_FALSE(clip_from_bvh(*doc, settings));
}

// A Frame Time no capture has (milliseconds written for seconds) is refused naming its line,
// unless the rate is given; a file of one frame (a pose) has no rate to doubt.
TEST(BvhImport, AFrameTimeNoCaptureHasIsRefusedUnlessTheRateIsGiven) {
  auto with_time = [](int frames, const std::string& time) {
    std::string text = two_joint_bvh("3 Zrotation Xrotation Yrotation", "0 0 0 0 0 0 0 0 0");
    text.replace(text.find("Frames: 1\nFrame Time: 0.04"), 26, "Frames: " + std::to_string(frames) + "\nFrame Time: " + time);
    for (int f = 1; f < frames; ++f) text += "0 0 0 0 0 0 0 0 0\n";
    return *parse_bvh(text, "t.bvh");
  };
  BvhImportSettings settings;
  settings.metres_per_unit = 1.0;
  auto ms = clip_from_bvh(with_time(3, "8.3333"), settings);
  ASSERT_FALSE(ms);
  EXPECT_EQ(ms.error().to_string(),
            "t.bvh:18: Frame Time 8.3333 s is 0.12 frames a second, no capture's rate (read as milliseconds it would "
            "be 120 fps): give the rate with --input-fps");
  auto fast = clip_from_bvh(with_time(3, "1e-9"), settings);
  ASSERT_FALSE(fast);
  EXPECT_EQ(fast.error().to_string(),
            "t.bvh:18: Frame Time 1e-09 s is 1e+09 frames a second, no capture's rate: give the rate with --input-fps");
  EXPECT_TRUE(clip_from_bvh(with_time(1, "8.3333"), settings));  // a pose
  EXPECT_TRUE(clip_from_bvh(with_time(3, "1"), settings));        // 1 fps: slow, but a rate
  // Rates as their frame times are written rounded: whole numbers, and numbers of hundredths
  // within 1e-6 (7.5 fps as 9 digits, NTSC's 29.97 as 7), not NTSC film's 23.976.
  for (const auto& [time, fps] : {std::pair{"0.0083333", 120.0}, std::pair{"0.133333333", 7.5},
                                  std::pair{"0.0333667", 29.97}, std::pair{"0.0417083", 1.0 / 0.0417083}}) {
    auto clip = clip_from_bvh(with_time(3, time), settings);
    ASSERT_TRUE(clip) << time;
    EXPECT_EQ(clip->motion.fps, fps) << time;
  }
  settings.fps_override = 120.0;
  auto given = clip_from_bvh(with_time(3, "8.3333"), settings);
  ASSERT_TRUE(given) << given.error().to_string();
  EXPECT_EQ(given->motion.fps, 120.0);
}

TEST(BvhImport, EndSitesFollowTheJoints) {
  Clip clip = test::load_data_clip("bvh/131_01.bvh");
  bool seen_end = false;
  for (const JointDef& joint : clip.skeleton.joints()) {
    if (joint.end_site) seen_end = true;
    EXPECT_EQ(joint.end_site, seen_end) << joint.name;
  }
  EXPECT_EQ(clip.skeleton.joint(0).name, "Hips");
  EXPECT_TRUE(clip.skeleton.find("LeftToe_end"));
}

TEST(BvhImport, DropsTheFramesConvertersAdded) {
  EXPECT_EQ(test::load_data_clip("bvh/07_01.bvh").dropped_leading_frames, 1);
  EXPECT_EQ(test::load_data_clip("bvh/07_12.bvh").dropped_leading_frames, 2);
  EXPECT_EQ(test::load_data_clip("bvh/111_36.bvh").dropped_leading_frames, 1);
  EXPECT_EQ(test::load_data_clip("bvh/131_01.bvh").dropped_leading_frames, 0);
  EXPECT_EQ(test::load_data_clip("bvh/16_01.bvh").dropped_leading_frames, 0);
  Clip clip = test::load_data_clip("bvh/111_36.bvh");
  EXPECT_EQ(clip.motion.frame_count, 1465);
}

}  // namespace
}  // namespace mg
