#include "motiongraph/motion/common_joints.h"

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/root_motion.h"
#include "motiongraph/synthesis/facing.h"
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

// The walk with a root-motion joint ("root_motion") above its root, as a game engine takes it.
Clip with_root_motion(const Clip& walk) {
  auto added = add_root_motion(walk.skeleton, walk.motion, learn_clip_forward_axis(walk.skeleton, walk.motion),
                               RootMotionSettings{});
  EXPECT_TRUE(added) << added.error().to_string();
  Clip out;
  out.name = walk.name;
  out.skeleton = added->skeleton;
  out.motion = added->motion;
  return out;
}

TEST(CommonJoints, TheSharedRootIsTheRootEverySkeletonHas) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip engine = with_root_motion(walk);
  ASSERT_EQ(engine.skeleton.joint(0).name, "root_motion");
  EXPECT_EQ(shared_root(std::vector<Skeleton>{walk.skeleton, engine.skeleton}), "root");
  EXPECT_EQ(shared_root(std::vector<Skeleton>{engine.skeleton, walk.skeleton, engine.skeleton}), "root");
  // One root everywhere, or roots that are nowhere else: none to share.
  EXPECT_EQ(shared_root(std::vector<Skeleton>{walk.skeleton, walk.skeleton}), "");
  std::vector<JointDef> renamed(walk.skeleton.joints().begin(), walk.skeleton.joints().end());
  renamed[0].name = "Hips";
  EXPECT_EQ(shared_root(std::vector<Skeleton>{engine.skeleton, Skeleton(renamed)}), "");
  // Of two roots every skeleton has, the deeper.
  const Clip twice = with_root_motion(engine);  // root_motion_2 -> root_motion -> root
  EXPECT_EQ(shared_root(std::vector<Skeleton>{twice.skeleton, engine.skeleton, walk.skeleton}), "root");
  EXPECT_EQ(shared_root(std::vector<Skeleton>{twice.skeleton, engine.skeleton}), "root_motion");
}

TEST(CommonJoints, RerootingComposesTheJointsAboveAndKeepsEveryKeptJointInTheWorld) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip engine = with_root_motion(walk);
  auto rerooted = reroot_at(engine, "root");
  ASSERT_TRUE(rerooted) << rerooted.error().to_string();
  EXPECT_EQ(names_of(rerooted->skeleton), names_of(walk.skeleton));
  EXPECT_TRUE(rerooted->skeleton.static_ancestors().empty());  // the root-motion joint moved: not written back
  const std::vector<Vec3> want = world_positions(walk.skeleton, walk.motion);
  const std::vector<Vec3> got = world_positions(rerooted->skeleton, rerooted->motion);
  ASSERT_EQ(got.size(), want.size());
  double worst = 0.0;
  for (size_t i = 0; i < want.size(); ++i) worst = std::max(worst, (got[i] - want[i]).norm());
  EXPECT_LT(worst, 1e-9);

  // From a joint deeper down: the chain above it composed in, the joints off the chain dropped,
  // every kept joint where it was in the world.
  const int lfemur = *walk.skeleton.find("lfemur");
  auto leg = reroot_at(walk, "lfemur");
  ASSERT_TRUE(leg) << leg.error().to_string();
  EXPECT_EQ(leg->skeleton.joint(0).name, "lfemur");
  EXPECT_TRUE(leg->skeleton.joint(0).animated_translation);
  std::vector<int> below;  // lfemur and the joints under it, in order
  for (int j = 0; j < walk.skeleton.joint_count(); ++j) {
    int up = j;
    while (up >= 0 && up != lfemur) up = walk.skeleton.parent(up);
    if (up == lfemur) below.push_back(j);
  }
  ASSERT_EQ(static_cast<size_t>(leg->skeleton.joint_count()), below.size());
  const std::vector<Vec3> leg_world = world_positions(leg->skeleton, leg->motion);
  const size_t all = static_cast<size_t>(walk.skeleton.joint_count()), kept = below.size();
  for (int f = 0; f < walk.motion.frame_count; f += 7) {
    for (size_t k = 0; k < kept; ++k) {
      EXPECT_EQ(leg->skeleton.joint(static_cast<int>(k)).name, walk.skeleton.joint(below[k]).name);
      ASSERT_LT((leg_world[f * kept + k] - want[f * all + static_cast<size_t>(below[k])]).norm(), 1e-9) << k << " at " << f;
    }
  }
  EXPECT_FALSE(reroot_at(walk, "nosuchjoint"));
  auto same = reroot_at(walk, "root");
  ASSERT_TRUE(same);
  EXPECT_EQ(world_positions(same->skeleton, same->motion), want);
}

}  // namespace
}  // namespace mg
