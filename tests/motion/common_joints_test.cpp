#include "motiongraph/motion/common_joints.h"

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

std::vector<std::string> names_of(const Skeleton& skeleton) {
  std::vector<std::string> names;
  for (const JointDef& joint : skeleton.joints()) names.push_back(joint.name);
  return names;
}

TEST(CommonJoints, TheJointsEverySkeletonHasInTheFirstsOrder) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip fingers = test::with_fingers(walk);
  const std::vector<std::string> plain = names_of(walk.skeleton);
  EXPECT_EQ(common_joints(std::vector<Skeleton>{walk.skeleton}), plain);
  EXPECT_EQ(common_joints(std::vector<Skeleton>{walk.skeleton, fingers.skeleton}), plain);
  EXPECT_EQ(common_joints(std::vector<Skeleton>{fingers.skeleton, walk.skeleton, fingers.skeleton}), plain);
  EXPECT_TRUE(common_joints(std::vector<Skeleton>{}).empty());

  // A joint under another parent in one skeleton is dropped there and everywhere, with all below it.
  std::vector<JointDef> moved(walk.skeleton.joints().begin(), walk.skeleton.joints().end());
  const int lclavicle = *walk.skeleton.find("lclavicle");
  moved[static_cast<size_t>(lclavicle)].parent = *walk.skeleton.find("upperback");
  const std::vector<std::string> common = common_joints(std::vector<Skeleton>{walk.skeleton, Skeleton(moved)});
  std::vector<std::string> outside;  // the joints not at or below lclavicle, in order
  for (int j = 0; j < walk.skeleton.joint_count(); ++j) {
    int up = j;
    while (up >= 0 && up != lclavicle) up = walk.skeleton.parent(up);
    if (up < 0) outside.push_back(plain[static_cast<size_t>(j)]);
  }
  EXPECT_EQ(common, outside);
  EXPECT_GE(plain.size() - outside.size(), 7u);  // lclavicle, lhumerus, lradius, lwrist, lhand, ... and their ends

  // Roots of other names share nothing.
  std::vector<JointDef> renamed(walk.skeleton.joints().begin(), walk.skeleton.joints().end());
  renamed[0].name = "Hips";
  EXPECT_TRUE(common_joints(std::vector<Skeleton>{walk.skeleton, Skeleton(renamed)}).empty());
}

TEST(CommonJoints, KeptJointsMoveAsBeforeInTheWorld) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip fingers = test::with_fingers(walk);
  const std::vector<std::string> plain = names_of(walk.skeleton);
  auto kept = keep_joints(fingers, plain);
  ASSERT_TRUE(kept) << kept.error().to_string();
  EXPECT_EQ(names_of(kept->skeleton), plain);
  for (int j = 0; j < walk.skeleton.joint_count(); ++j) EXPECT_EQ(kept->skeleton.parent(j), walk.skeleton.parent(j));
  EXPECT_EQ(world_positions(kept->skeleton, kept->motion), world_positions(walk.skeleton, walk.motion));

  // Another order, parents first: each joint where it was in the world.
  std::vector<std::string> reordered = {plain[0]};
  for (int j = walk.skeleton.joint_count() - 1; j > 0; --j) {
    if (walk.skeleton.parent(j) == 0) reordered.push_back(plain[static_cast<size_t>(j)]);
  }
  for (int j = 1; j < walk.skeleton.joint_count(); ++j) {
    if (walk.skeleton.parent(j) != 0) reordered.push_back(plain[static_cast<size_t>(j)]);
  }
  auto turned = keep_joints(fingers, reordered);
  ASSERT_TRUE(turned) << turned.error().to_string();
  const std::vector<Vec3> before = world_positions(walk.skeleton, walk.motion);
  const std::vector<Vec3> after = world_positions(turned->skeleton, turned->motion);
  const size_t joints = plain.size();
  for (int f = 0; f < walk.motion.frame_count; ++f) {
    for (size_t k = 0; k < joints; ++k) {
      const size_t j = static_cast<size_t>(*walk.skeleton.find(reordered[k]));
      ASSERT_LT((after[f * joints + k] - before[f * joints + j]).norm(), 1e-12) << reordered[k] << " at " << f;
    }
  }
}

TEST(CommonJoints, KeepingFailsOnAMissingJointAnotherRootOrAnOrphan) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const std::vector<std::string> missing = {"root", "lhipjoint", "nosuchjoint"};
  auto a = keep_joints(walk, missing);
  ASSERT_FALSE(a);
  EXPECT_NE(a.error().message.find("no joint 'nosuchjoint'"), std::string::npos) << a.error().message;
  const std::vector<std::string> not_root = {"lhipjoint", "lfemur"};
  auto b = keep_joints(walk, not_root);
  ASSERT_FALSE(b);
  EXPECT_NE(b.error().message.find("not the skeleton's root"), std::string::npos) << b.error().message;
  const std::vector<std::string> orphan = {"root", "lfemur"};  // its parent lhipjoint is not kept
  auto c = keep_joints(walk, orphan);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().message.find("parent of 'lfemur'"), std::string::npos) << c.error().message;
}

}  // namespace
}  // namespace mg
