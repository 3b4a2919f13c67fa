#include "motiongraph/motion/rig_matching.h"

#include <random>

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "motion/static_root_bvh.h"
#include "test_data.h"

namespace mg {
namespace {

// The clip's skeleton with joint j renamed.
Clip with_joint_names(const Clip& clip, const std::vector<std::pair<int, std::string>>& names) {
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  for (const auto& [j, name] : names) joints[static_cast<size_t>(j)].name = name;
  Clip out = clip;
  out.skeleton = Skeleton(std::move(joints));
  return out;
}

// A skeleton of the same joints whose bones rest in other directions (same lengths): each
// bone's offset turned by a random rotation of up to `max_angle` radians.
Skeleton turned_rest_pose(const Skeleton& skeleton, double max_angle, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<JointDef> joints(skeleton.joints().begin(), skeleton.joints().end());
  for (size_t j = 1; j < joints.size(); ++j) {
    const Vec3 axis = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    joints[j].rest_offset_m = Quat(Eigen::AngleAxisd(max_angle * unit(rng), axis)) * joints[j].rest_offset_m;
  }
  return Skeleton(std::move(joints));
}

double max_bone_length_change(const Skeleton& a, const Skeleton& b) {
  double worst = 0.0;
  for (int j = 0; j < a.joint_count(); ++j) {
    worst = std::max(worst, std::abs(a.joint(j).rest_offset_m.norm() - b.joint(j).rest_offset_m.norm()));
  }
  return worst;
}

TEST(RigMatching, SidesFromNames) {
  const std::vector<std::pair<const char*, JointSide>> cases = {
      {"LeftUpLeg", JointSide::kLeft},   {"mixamorig:RightHand", JointSide::kRight}, {"lfemur", JointSide::kLeft},
      {"rhumerus", JointSide::kRight},   {"LHipJoint", JointSide::kLeft},           {"rCollar", JointSide::kRight},
      {"hand_l", JointSide::kLeft},      {"foot.R", JointSide::kRight},            {"l_hip", JointSide::kLeft},
      {"lowerback", JointSide::kNone},   {"LowerBack", JointSide::kNone},          {"root", JointSide::kNone},
      {"radius", JointSide::kNone},      {"Hips", JointSide::kNone},               {"rtoes", JointSide::kRight},
      {"lthumb", JointSide::kLeft},      {"lpes", JointSide::kNone},               {"LeftRight", JointSide::kNone},
      {"Bip01 L Thigh", JointSide::kLeft}, {"Bip001_R_Calf", JointSide::kRight},   {"hand.L.001", JointSide::kLeft},
      {"thigh.L", JointSide::kLeft},     {"ROOT", JointSide::kNone},               {"RIBS", JointSide::kNone},
      {"lShldr", JointSide::kLeft},      {"lowerJaw", JointSide::kNone},           {"L R", JointSide::kNone}};
  for (const auto& [name, side] : cases) EXPECT_EQ(joint_side(name), side) << name;
}

TEST(RigMatching, TheConvertersOfCmuShareOneHierarchyUnderTheirOwnNames) {
  // Three conversions of CMU's capture (amc2bvh's CMU names, MotionBuilder's, 3ds Max's): the
  // same joints in the same order, named three ways.
  const Clip cmu = test::load_data_clip("bvh/16_01.bvh");
  const Clip builder = test::load_data_clip("bvh/111_36.bvh");
  const Clip max = test::load_data_clip("bvh/131_01.bvh");
  EXPECT_EQ(hierarchy_mismatch(cmu.skeleton, builder.skeleton), std::nullopt);
  EXPECT_EQ(hierarchy_mismatch(cmu.skeleton, max.skeleton), std::nullopt);
  EXPECT_EQ(hierarchy_mismatch(builder.skeleton, max.skeleton), std::nullopt);
  // Daz's names on another hierarchy (eyes, fingers, no hip joints).
  const auto daz = hierarchy_mismatch(cmu.skeleton, test::load_data_clip("bvh/07_01.bvh").skeleton);
  ASSERT_TRUE(daz.has_value());
  EXPECT_NE(daz->find("joints there"), std::string::npos) << *daz;

  const Clip renamed = renamed_as(builder, cmu.skeleton);
  for (int j = 0; j < cmu.skeleton.joint_count(); ++j) {
    EXPECT_EQ(renamed.skeleton.joint(j).name, cmu.skeleton.joint(j).name);
  }
  EXPECT_EQ(world_positions(renamed.skeleton, renamed.motion), world_positions(builder.skeleton, builder.motion));
}

// The same rig: one subject's clips (one ASF), whatever their motion; not: other names, a bone
// 1 mm longer, position channels on another joint, a static root above the hips.
TEST(RigMatching, TheSameRigOnlyWithTheSameNamesChannelsAndBones) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip jog = test::load_data_clip("cmu/16/16_35.amc");
  EXPECT_EQ(rig_difference(walk.skeleton, jog.skeleton), std::nullopt);
  EXPECT_EQ(rig_difference(walk.skeleton, walk.skeleton), std::nullopt);
  const auto renamed = rig_difference(walk.skeleton, with_joint_names(walk, {{2, "LeftUpLeg"}}).skeleton);
  ASSERT_TRUE(renamed);
  EXPECT_NE(renamed->find("'LeftUpLeg' here"), std::string::npos) << *renamed;
  std::vector<JointDef> joints(walk.skeleton.joints().begin(), walk.skeleton.joints().end());
  const int femur = *walk.skeleton.find("lfemur");
  std::vector<JointDef> longer = joints;
  longer[static_cast<size_t>(femur)].rest_offset_m *= 1.0 + 0.001 / longer[static_cast<size_t>(femur)].rest_offset_m.norm();
  const auto bone = rig_difference(walk.skeleton, Skeleton(longer));
  ASSERT_TRUE(bone);
  EXPECT_NE(bone->find("the bone to 'lfemur' is 0.10 cm"), std::string::npos) << *bone;
  // Within 0.1 mm is the same bone (rounding in a file's text).
  std::vector<JointDef> rounded = joints;
  rounded[static_cast<size_t>(femur)].rest_offset_m += Vec3(5e-5, 0.0, 0.0);
  EXPECT_EQ(rig_difference(walk.skeleton, Skeleton(rounded)), std::nullopt);
  std::vector<JointDef> channels = joints;
  channels[static_cast<size_t>(femur)].animated_translation = true;
  const auto moved = rig_difference(walk.skeleton, Skeleton(channels));
  ASSERT_TRUE(moved);
  EXPECT_NE(moved->find("'lfemur' has position channels here only"), std::string::npos) << *moved;
  // A rig whose every joint has position channels: its offsets are its channels', not compared.
  const Clip six = test::import_bvh(test::static_root_bvh(walk));
  ASSERT_FALSE(six.skeleton.static_ancestors().empty());
  EXPECT_EQ(rig_difference(six.skeleton, six.skeleton), std::nullopt);
  const auto above = rig_difference(
      six.skeleton, Skeleton(std::vector<JointDef>(six.skeleton.joints().begin(), six.skeleton.joints().end())));
  ASSERT_TRUE(above);
  EXPECT_NE(above->find("static joint(s) above the root"), std::string::npos) << *above;
}

TEST(RigMatching, LegsNamedTheOtherWayRoundDoNotMatch) {
  const Clip cmu = test::load_data_clip("bvh/16_01.bvh");
  const int left = *cmu.skeleton.find("lfemur");
  const int right = *cmu.skeleton.find("rfemur");
  const Clip swapped = with_joint_names(cmu, {{left, "RightUpLeg"}, {right, "LeftUpLeg"}});
  const auto mismatch = hierarchy_mismatch(cmu.skeleton, swapped.skeleton);
  ASSERT_TRUE(mismatch.has_value());
  EXPECT_NE(mismatch->find("'lfemur' (left) there and 'RightUpLeg' (right) here"), std::string::npos) << *mismatch;
  // A name without a side matches anything.
  EXPECT_EQ(hierarchy_mismatch(cmu.skeleton, with_joint_names(cmu, {{left, "thigh_a"}}).skeleton), std::nullopt);
}

TEST(RigMatching, RestPoseOfTheArmsDownConverter) {
  const Clip builder = test::load_data_clip("bvh/111_36.bvh");
  const Clip max = test::load_data_clip("bvh/131_01.bvh");
  const RestPoseDifference difference = rest_pose_difference(builder.skeleton, max.skeleton);
  EXPECT_NEAR(difference.angle_deg, 90.0, 1.0);  // the forearms hang down instead of out
  EXPECT_NE(difference.bone.find("ForeArm"), std::string::npos) << difference.bone;
  EXPECT_GT(difference.angle_deg, kRestPoseRetargetDeg);
  EXPECT_LT(rest_pose_difference(max.skeleton, max.skeleton).angle_deg, 1e-5);  // acos near 1 rounds

  // Re-expressed on the arms-out rest pose: every joint where it was, the bones as long, and
  // every bone of a joint with one bone resting as the reference's.
  const Clip out = on_rest_pose_of(max, builder.skeleton);
  const std::vector<Vec3> before = world_positions(max.skeleton, max.motion);
  const std::vector<Vec3> after = world_positions(out.skeleton, out.motion);
  EXPECT_LT(test::max_position_error(before, after), 1e-9);
  EXPECT_LT(max_bone_length_change(max.skeleton, out.skeleton), 1e-12);
  EXPECT_LT(rest_pose_difference(builder.skeleton, out.skeleton).angle_deg, kRestPoseRetargetDeg);
  const int forearm = *max.skeleton.find("LeftWrist");  // the bone from LeftElbow to LeftWrist
  const Vec3 want = builder.skeleton.joint(forearm).rest_offset_m.normalized();
  EXPECT_LT((out.skeleton.joint(forearm).rest_offset_m.normalized() - want).norm(), 1e-9);
  for (int j = 0; j < out.skeleton.joint_count(); ++j) {
    if (!out.skeleton.joint(j).end_site) continue;
    for (int f = 0; f < out.motion.frame_count; f += 50) {
      EXPECT_LT(out.motion.rotations(f)[static_cast<size_t>(j)].angularDistance(Quat::Identity()), 1e-9);
    }
  }
}

TEST(RigMatching, AnyRestPoseKeepsEveryJointWhereItWas) {
  // Property: onto skeletons whose bones rest turned at random (up to 170 degrees), and back,
  // the positions are the clip's in every frame; joints with translation channels included.
  const Clip amc = test::load_data_clip("cmu/16/16_15.amc");
  const Clip walk = test::import_bvh(test::static_root_bvh(amc));  // every joint translated per frame
  ASSERT_GT(walk.skeleton.translated_joints().size(), 10u);
  const std::vector<Vec3> positions = world_positions(walk.skeleton, walk.motion);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Skeleton other = turned_rest_pose(walk.skeleton, 170.0 * 3.14159265 / 180.0, seed);
    const Clip there = on_rest_pose_of(walk, other);
    EXPECT_LT(test::max_position_error(positions, world_positions(there.skeleton, there.motion)), 1e-9) << seed;
    EXPECT_LT(max_bone_length_change(walk.skeleton, there.skeleton), 1e-12);
    const Clip back = on_rest_pose_of(there, walk.skeleton);
    EXPECT_LT(test::max_position_error(positions, world_positions(back.skeleton, back.motion)), 1e-9) << seed;
    for (int f = 0; f < back.motion.frame_count; ++f) {
      for (const Quat& q : back.motion.rotations(f)) ASSERT_NEAR(q.norm(), 1.0, 1e-12);
    }
  }
}

}  // namespace
}  // namespace mg
