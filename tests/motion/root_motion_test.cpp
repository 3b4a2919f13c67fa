#include "motiongraph/motion/root_motion.h"

#include <gtest/gtest.h>

#include "motion/static_root_bvh.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/synthesis/facing.h"
#include "test_data.h"

namespace mg {
namespace {

RootMotionClip added(const Clip& clip, double smoothing_s) {
  RootMotionSettings settings;
  settings.smoothing_s = smoothing_s;
  auto out = add_root_motion(clip.skeleton, clip.motion, learn_clip_forward_axis(clip.skeleton, clip.motion), settings);
  EXPECT_TRUE(out) << out.error().message;
  return std::move(*out);
}

// The new joint's floor position and +z axis per frame.
struct Track {
  std::vector<Vec3> at;
  std::vector<Vec3> facing;
};
Track root_track(const RootMotionClip& clip) {
  Track track;
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    track.at.push_back(clip.motion.translations(f)[0]);
    track.facing.push_back(clip.motion.rotations(f)[0] * Vec3::UnitZ());
  }
  return track;
}

// Sum of squared second differences: how much a track wobbles.
double wobble(const std::vector<Vec3>& track) {
  double sum = 0.0;
  for (size_t f = 1; f + 1 < track.size(); ++f) sum += (track[f + 1] - 2.0 * track[f] + track[f - 1]).squaredNorm();
  return sum;
}

TEST(RootMotion, NoJointMoves) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip run = test::load_data_clip("cmu/16/16_35.amc");
  const Clip six_channels = test::import_bvh(
      test::static_root_bvh(walk, Vec3(0.4, 0.0, -1.5), Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()))));
  for (const Clip* clip : {&walk, &run, &six_channels}) {
    for (double smoothing : {0.0, 0.5, 2.0}) {
      const RootMotionClip out = added(*clip, smoothing);
      ASSERT_EQ(out.skeleton.joint_count(), clip->skeleton.joint_count() + 1);
      const auto before = world_positions(clip->skeleton, clip->motion);
      const auto after = world_positions(out.skeleton, out.motion);
      const int joints = clip->skeleton.joint_count();
      double worst = 0.0;
      for (int f = 0; f < clip->motion.frame_count; ++f) {
        for (int j = 0; j < joints; ++j) {
          worst = std::max(worst, (after[f * (joints + 1) + j + 1] - before[f * joints + j]).norm());
        }
      }
      EXPECT_LT(worst, 1e-12) << clip->name << " smoothing " << smoothing;
    }
  }
}

TEST(RootMotion, UnsmoothedItStandsUnderTheHipsFacingTheirWay) {
  const Clip clip = test::load_data_clip("cmu/16/16_35.amc");
  const Vec3 axis = learn_clip_forward_axis(clip.skeleton, clip.motion);
  const RootMotionClip out = added(clip, 0.0);
  const Track track = root_track(out);
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    const Vec3 hips = clip.motion.translations(f)[0];
    EXPECT_EQ(track.at[f], Vec3(hips.x(), 0.0, hips.z())) << f;
    // A turn about the vertical alone, its +z where the hips face on the floor.
    const Quat turn = out.motion.rotations(f)[0];
    EXPECT_LT((turn * Vec3::UnitY() - Vec3::UnitY()).norm(), 1e-12);
    Vec3 facing = clip.motion.rotations(f)[0] * axis;
    facing.y() = 0.0;
    EXPECT_LT((track.facing[f] - facing.normalized()).norm(), 1e-9) << f;
  }
}

TEST(RootMotion, SmoothingTakesTheStepsSwayOutAndKeepsTheEnds) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const Track raw = root_track(added(clip, 0.0));
  const Track smooth = root_track(added(clip, 0.5));
  EXPECT_LT(wobble(smooth.at), 0.05 * wobble(raw.at));
  EXPECT_LT(wobble(smooth.facing), 0.05 * wobble(raw.facing));
  for (int f : {0, clip.motion.frame_count - 1}) {
    EXPECT_EQ(smooth.at[f], raw.at[f]);
    EXPECT_LT((smooth.facing[f] - raw.facing[f]).norm(), 1e-12);
  }
}

// Centred windows keep what is already straight: hips going along a line at a steady speed and
// facing one way give the same joint smoothed or not.
TEST(RootMotion, SmoothingKeepsASteadyStraightWalk) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const Quat facing_once = clip.motion.rotations(0)[0];
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    clip.motion.translations(f)[0] = Vec3(0.3 + 0.011 * f, 0.95, -2.0 - 0.004 * f);
    clip.motion.rotations(f)[0] = facing_once;
  }
  const Track raw = root_track(added(clip, 0.0));
  const Track smooth = root_track(added(clip, 1.0));
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    EXPECT_LT((smooth.at[f] - raw.at[f]).norm(), 1e-9) << f;
    EXPECT_LT((smooth.facing[f] - raw.facing[f]).norm(), 1e-9) << f;
  }
}

TEST(RootMotion, ItsNameIsFreeOrTheStaticRootsOwn) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  EXPECT_EQ(added(clip, 0.0).skeleton.joint(0).name, "root_motion");
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  joints[3].name = "root_motion";
  const Skeleton taken(joints);
  auto renamed = add_root_motion(taken, clip.motion, Vec3::UnitZ(), {});
  ASSERT_TRUE(renamed);
  EXPECT_EQ(renamed->skeleton.joint(0).name, "root_motion_2");
  const Clip bandai = test::import_bvh(test::static_root_bvh(clip));
  EXPECT_EQ(added(bandai, 0.5).skeleton.joint(0).name, test::kStaticRootName);
  EXPECT_TRUE(added(bandai, 0.5).skeleton.static_ancestors().empty());
}

// Written as BVH (the hips below the new root with position channels) and read back, every joint
// is where it was.
TEST(RootMotion, ABvhRoundTripKeepsEveryJoint) {
  const Clip clip = test::load_data_clip("cmu/16/16_35.amc");
  const RootMotionClip out = added(clip, 0.5);
  BvhImportSettings settings;
  settings.metres_per_unit = 1.0;
  settings.drop_rest_frames = false;
  const Clip back = test::import_bvh(write_bvh(out.skeleton, out.motion, {}), settings);
  EXPECT_EQ(back.skeleton.joint(0).name, "root_motion");
  EXPECT_LT(test::max_position_error_by_name(clip, back), 1e-5);
}

TEST(RootMotion, BadSettingsAreErrors) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  RootMotionSettings negative;
  negative.smoothing_s = -0.1;
  EXPECT_FALSE(add_root_motion(clip.skeleton, clip.motion, Vec3::UnitZ(), negative));
  RootMotionSettings unnamed;
  unnamed.joint_name.clear();
  EXPECT_FALSE(add_root_motion(clip.skeleton, clip.motion, Vec3::UnitZ(), unnamed));
}

}  // namespace
}  // namespace mg
