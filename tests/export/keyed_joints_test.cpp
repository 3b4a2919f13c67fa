#include "motiongraph/export/keyed_joints.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "motion/static_root_bvh.h"
#include "test_data.h"

namespace mg {
namespace {

bool has(const std::vector<int>& joints, int j) { return std::find(joints.begin(), joints.end(), j) != joints.end(); }

TEST(KeyedJoints, ATravellingRootRestsOverTheOriginAtItsFirstFramesHeight) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const Vec3 first = clip.motion.translations(0)[clip.skeleton.translation_slot(0)];
  ASSERT_GT(Vec3(first.x(), 0.0, first.z()).norm(), 0.01);  // the test means something
  EXPECT_EQ(rest_node_translation(clip.skeleton, &clip.motion, 0), Vec3(0.0, first.y(), 0.0));
  // Without a motion, the rest offset's height; other joints their offsets.
  EXPECT_EQ(rest_node_translation(clip.skeleton, nullptr, 0), Vec3(0.0, clip.skeleton.joint(0).rest_offset_m.y(), 0.0));
  EXPECT_EQ(rest_node_translation(clip.skeleton, &clip.motion, 3), clip.skeleton.joint(3).rest_offset_m);
}

TEST(KeyedJoints, BelowStaticAncestorsComposesBackToTheJointsTransform) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Vec3 at(1.0, 0.2, -3.0);
  const Quat turn(Eigen::AngleAxisd(1.1, Vec3(0.3, 1.0, -0.2).normalized()));
  const Clip clip = test::import_bvh(test::static_root_bvh(plain, at, turn));
  ASSERT_EQ(clip.skeleton.static_ancestors().size(), 1u);
  const Vec3 t = clip.motion.translations(5)[clip.skeleton.translation_slot(0)];
  const Quat q = clip.motion.rotations(5)[0];
  // The ancestors' transform (the file's, to its digits) times joint 0's below them is joint 0's here.
  const Quat ancestor_turn = clip.skeleton.static_ancestor_rotation();
  const Vec3 ancestor_at = clip.skeleton.static_ancestor_translation_m();
  ASSERT_LT(ancestor_turn.angularDistance(turn), 1e-6);
  ASSERT_LT((ancestor_at - at).norm(), 1e-6);
  EXPECT_LT((ancestor_turn * below_static_ancestors(clip.skeleton, t) + ancestor_at - t).norm(), 1e-12);
  EXPECT_LT((ancestor_turn * below_static_ancestors(clip.skeleton, q)).angularDistance(q), 1e-12);
}

// At rest every node stands unturned below its parent: the static root where the file puts it,
// the hips over the origin at their first frame's height below it, each other joint at its
// first-frame translation from its parent.
TEST(KeyedJoints, RestTransformsComposeTheNodesDownTheHierarchy) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Clip clip =
      test::import_bvh(test::static_root_bvh(plain, Vec3(1.0, 0.2, -3.0), Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()))));
  ASSERT_EQ(clip.skeleton.static_ancestors().size(), 1u);
  const auto rest = rest_transforms(clip.skeleton, &clip.motion);
  ASSERT_EQ(rest.size(), static_cast<size_t>(clip.skeleton.joint_count()) + 1);
  const Quat ancestor_turn = clip.skeleton.static_ancestor_rotation();
  EXPECT_LT((rest[0].translation() - clip.skeleton.static_ancestor_translation_m()).norm(), 1e-12);
  EXPECT_LT(Quat(rest[0].rotation()).angularDistance(ancestor_turn), 1e-12);
  const Vec3 hips = clip.motion.translations(0)[clip.skeleton.translation_slot(0)];
  EXPECT_LT(std::abs(rest[1].translation().y() - hips.y()), 1e-9);
  EXPECT_LT(Vec3(rest[1].translation().x(), 0.0, rest[1].translation().z()).norm(), 1e-9);
  for (int j = 1; j < clip.skeleton.joint_count(); ++j) {
    const Eigen::Affine3d& parent = rest[1 + static_cast<size_t>(clip.skeleton.parent(j))];
    const int slot = clip.skeleton.translation_slot(j);
    const Vec3 t = slot >= 0 ? clip.motion.translations(0)[slot] : clip.skeleton.joint(j).rest_offset_m;
    EXPECT_LT((rest[1 + static_cast<size_t>(j)].translation() - (parent.translation() + parent.rotation() * t)).norm(),
              1e-12);
    EXPECT_LT(Quat(rest[1 + static_cast<size_t>(j)].rotation()).angularDistance(ancestor_turn), 1e-12);
  }
}

TEST(KeyedJoints, JointsAnyMotionTurnsOrMovesAreKeyedAndEndSitesNever) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Clip clip = test::import_bvh(test::static_root_bvh(plain));
  Motion still(clip.skeleton, 3, 30.0);  // identity rotations, rest translations
  for (int f = 0; f < 3; ++f) {
    for (int j : clip.skeleton.translated_joints())
      still.translations(f)[clip.skeleton.translation_slot(j)] = clip.skeleton.joint(j).rest_offset_m;
  }
  Motion bent = still;
  const int knee = *clip.skeleton.find("ltibia");
  bent.rotations(2)[knee] = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitX()));
  bent.translations(1)[clip.skeleton.translation_slot(knee)] += Vec3(0.0, 0.01, 0.0);
  const std::vector<const Motion*> one{&still}, both{&still, &bent};
  const KeyedJoints alone = keyed_joints(clip.skeleton, one);
  // Joint 0 below the static root always: its rotation and its travel.
  EXPECT_EQ(alone.turned, std::vector<int>{0});
  EXPECT_EQ(alone.moved, std::vector<int>{0});
  const KeyedJoints set = keyed_joints(clip.skeleton, both);
  EXPECT_TRUE(has(set.turned, knee) && has(set.moved, knee));
  for (int j = 0; j < clip.skeleton.joint_count(); ++j) {
    if (clip.skeleton.joint(j).end_site) {
      EXPECT_FALSE(has(set.turned, j)) << j;
    }
  }
}

}  // namespace
}  // namespace mg
