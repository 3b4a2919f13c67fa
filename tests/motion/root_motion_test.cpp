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
    EXPECT_EQ(track.at[f].x(), hips.x()) << f;
    EXPECT_EQ(track.at[f].z(), hips.z()) << f;
    EXPECT_EQ(track.at[f].y(), track.at[0].y()) << f;  // one floor
    // A turn about the vertical alone, its +z where the hips face on the floor.
    const Quat turn = out.motion.rotations(f)[0];
    EXPECT_LT((turn * Vec3::UnitY() - Vec3::UnitY()).norm(), 1e-12);
    Vec3 facing = clip.motion.rotations(f)[0] * axis;
    facing.y() = 0.0;
    EXPECT_LT((track.facing[f] - facing.normalized()).norm(), 1e-9) << f;
  }
  EXPECT_LT(std::abs(track.at[0].y()), 0.05);  // the CMU clips stand on y = 0
}

// The joint stands on the clip's floor wherever the file puts it.
TEST(RootMotion, ItStandsOnTheClipsFloor) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  Clip lower = clip;
  for (int f = 0; f < lower.motion.frame_count; ++f) lower.motion.translations(f)[0].y() -= 0.75;
  const Track track = root_track(added(clip, 0.5)), low = root_track(added(lower, 0.5));
  for (int f = 0; f < clip.motion.frame_count; ++f) EXPECT_NEAR(low.at[f].y(), track.at[f].y() - 0.75, 1e-9) << f;
}

// The joint's +z points the way the feet do (ankle to toe), walking forwards or backwards: a clip
// alone says which way its skeleton faces by its toes, not by where it travels.
TEST(RootMotion, ItFacesTheWayTheToesPointWalkingForwardsOrBackwards) {
  for (const char* file : {"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_01.amc"}) {
    const Clip forwards = test::load_data_clip(file);
    Clip backwards = forwards;
    const int n = forwards.motion.frame_count;
    for (int f = 0; f < n; ++f) {
      std::copy(forwards.motion.rotations(n - 1 - f).begin(), forwards.motion.rotations(n - 1 - f).end(),
                backwards.motion.rotations(f).begin());
      std::copy(forwards.motion.translations(n - 1 - f).begin(), forwards.motion.translations(n - 1 - f).end(),
                backwards.motion.translations(f).begin());
    }
    for (const Clip* clip : {&forwards, static_cast<const Clip*>(&backwards)}) {
      const RootMotionClip out = added(*clip, 0.5);
      const auto ltoes = *out.skeleton.find("ltoes"), lfoot = *out.skeleton.find("lfoot");
      const auto world = world_positions(out.skeleton, out.motion);
      const int joints = out.skeleton.joint_count();
      double along = 0.0;
      for (int f = 0; f < n; ++f) {
        Vec3 foot = world[f * joints + ltoes] - world[f * joints + lfoot];
        foot.y() = 0.0;
        along += (out.motion.rotations(f)[0] * Vec3::UnitZ()).dot(foot.normalized());
      }
      // Positive, the front: 0.95 walking, 0.38 running (a running foot swings back toes down),
      // the same negated were the joint turned about.
      EXPECT_GT(along / n, 0.25) << file << (clip == &backwards ? " backwards" : "");
    }
  }
}

// Smoothed, each frame is the least-squares line through the frames within half the window either
// side, evaluated at it (checked against Eigen's least squares), and the sway of the steps is
// mostly gone.
TEST(RootMotion, SmoothingIsALocalLineAndTakesTheStepsSwayOut) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");  // 120 fps
  const Track raw = root_track(added(clip, 0.0));
  const Track smooth = root_track(added(clip, 0.5));
  EXPECT_LT(wobble(smooth.at), 0.05 * wobble(raw.at));
  EXPECT_LT(wobble(smooth.facing), 0.05 * wobble(raw.facing));
  const int n = clip.motion.frame_count, half = 30;  // 0.25 s at 120 fps
  std::vector<double> yaw(n);
  for (int f = 0; f < n; ++f) {
    yaw[f] = std::atan2(raw.facing[f].x(), raw.facing[f].z());
    if (f > 0) yaw[f] = yaw[f - 1] + std::remainder(yaw[f] - yaw[f - 1], 2.0 * M_PI);
  }
  for (int f = 0; f < n; ++f) {
    const int first = std::max(0, f - half), last = std::min(n - 1, f + half);
    Eigen::MatrixXd a(last - first + 1, 2);
    Eigen::MatrixXd b(last - first + 1, 3);
    for (int i = first; i <= last; ++i) {
      a.row(i - first) << 1.0, i - f;
      b.row(i - first) << raw.at[i].x(), raw.at[i].z(), yaw[i];
    }
    const Eigen::MatrixXd line = a.colPivHouseholderQr().solve(b);
    EXPECT_NEAR(smooth.at[f].x(), line(0, 0), 1e-9) << f;
    EXPECT_NEAR(smooth.at[f].z(), line(0, 1), 1e-9) << f;
    EXPECT_LT((smooth.facing[f] - Vec3(std::sin(line(0, 2)), 0.0, std::cos(line(0, 2)))).norm(), 1e-9) << f;
  }
}

// Lines stay lines: hips going straight at a steady speed, and turning at a steady rate (up to a
// spin of two turns a second), give the same track smoothed or not.
TEST(RootMotion, SmoothingKeepsSteadyMotion) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const Quat facing_once = clip.motion.rotations(0)[0];
  const double fps = clip.motion.fps;
  for (double turns_per_second : {0.0, 0.3, 2.0}) {
    for (int f = 0; f < clip.motion.frame_count; ++f) {
      clip.motion.translations(f)[0] = Vec3(0.3 + 0.011 * f, 0.95, -2.0 - 0.004 * f);
      clip.motion.rotations(f)[0] = Quat(Eigen::AngleAxisd(2.0 * M_PI * turns_per_second * f / fps, Vec3::UnitY())) * facing_once;
    }
    const Track raw = root_track(added(clip, 0.0));
    const Track smooth = root_track(added(clip, 1.0));
    for (int f = 0; f < clip.motion.frame_count; ++f) {
      EXPECT_LT((smooth.at[f] - raw.at[f]).norm(), 1e-9) << f;
      EXPECT_LT((smooth.facing[f] - raw.facing[f]).norm(), 1e-9) << turns_per_second << " " << f;
    }
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
  // Two fixed joints above the hips: the one right above them carries the root motion, the other
  // stays above it, and no joint moves.
  StaticAncestor armature{"Armature", Vec3(1.0, 0.0, 2.0), Quat(Eigen::AngleAxisd(0.4, Vec3::UnitY()))};
  StaticAncestor root{"joint_Root", Vec3(0.0, 0.1, 0.0), Quat::Identity()};
  Clip two;
  two.skeleton = Skeleton(joints, {armature, root});
  two.motion = clip.motion;
  Clip moved;
  auto out = add_root_motion(two.skeleton, two.motion, Vec3::UnitZ(), {});
  ASSERT_TRUE(out);
  EXPECT_EQ(out->skeleton.joint(0).name, "joint_Root");
  ASSERT_EQ(out->skeleton.static_ancestors().size(), 1u);
  EXPECT_EQ(out->skeleton.static_ancestors()[0].name, "Armature");
  moved.skeleton = out->skeleton;
  moved.motion = out->motion;
  EXPECT_LT(test::max_position_error_by_name(two, moved), 1e-12);
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
  // A huge window is the whole clip, not an overflow.
  RootMotionSettings huge;
  huge.smoothing_s = 1e300;
  auto whole = add_root_motion(clip.skeleton, clip.motion, Vec3::UnitZ(), huge);
  ASSERT_TRUE(whole);
  EXPECT_LT(wobble(root_track(*whole).at), 1e-20);  // one line through every frame
}

// A root without position channels has no travel to carry: an error, not a crash, also where the
// facing is learnt first.
TEST(RootMotion, ARootWithoutPositionChannelsIsAnError) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  joints[0].animated_translation = false;
  const Skeleton fixed(joints);
  Motion motion(fixed, clip.motion.frame_count, clip.motion.fps);
  motion.local_rotations = clip.motion.local_rotations;
  EXPECT_EQ(learn_clip_forward_axis(fixed, motion), Vec3::UnitZ());
  auto out = add_root_motion(fixed, motion, Vec3::UnitZ(), {});
  ASSERT_FALSE(out);
  EXPECT_NE(out.error().message.find("no position channels"), std::string::npos) << out.error().message;
}

// A root that stands while the joints below it travel (a fixed root not folded away): an error
// naming both, rather than a root-motion joint that never moves.
TEST(RootMotion, AStandingRootAboveTravellingJointsIsAnError) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  // The same motion with its root held at its first place and the joints right below it given
  // position channels that carry the travel instead.
  std::vector<JointDef> joints(plain.skeleton.joints().begin(), plain.skeleton.joints().end());
  for (JointDef& joint : joints) joint.animated_translation = joint.animated_translation || joint.parent == 0;
  Clip clip;
  clip.skeleton = Skeleton(joints);
  clip.motion = Motion(clip.skeleton, plain.motion.frame_count, plain.motion.fps);
  clip.motion.local_rotations = plain.motion.local_rotations;
  const Vec3 start = plain.motion.translations(0)[0];
  for (int f = 0; f < plain.motion.frame_count; ++f) {
    const Vec3 travel = plain.motion.translations(f)[0] - start;
    const Quat root = plain.motion.rotations(f)[0];
    clip.motion.translations(f)[0] = start;
    for (int j = 1; j < clip.skeleton.joint_count(); ++j) {
      if (joints[j].parent == 0) {
        clip.motion.translations(f)[clip.skeleton.translation_slot(j)] = joints[j].rest_offset_m + root.conjugate() * travel;
      }
    }
  }
  // Every joint but the root where it was.
  const auto before = world_positions(plain.skeleton, plain.motion), after = world_positions(clip.skeleton, clip.motion);
  for (size_t i = 0; i < before.size(); ++i) {
    if (i % joints.size() != 0) {
      ASSERT_LT((before[i] - after[i]).norm(), 1e-9) << i;
    }
  }
  auto out = add_root_motion(clip.skeleton, clip.motion, Vec3::UnitZ(), {});
  ASSERT_FALSE(out);
  EXPECT_NE(out.error().message.find("does not travel"), std::string::npos) << out.error().message;
}

}  // namespace
}  // namespace mg
