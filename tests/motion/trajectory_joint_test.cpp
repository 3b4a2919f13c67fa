#include "motiongraph/motion/trajectory_joint.h"

#include <numbers>

#include <gtest/gtest.h>

#include "motion/static_root_bvh.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/metric/point_cloud.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

using test::import_bvh;

std::vector<std::pair<std::string, std::string>> hierarchy(const std::string& bvh_text) {
  auto doc = parse_bvh(bvh_text, "h.bvh");
  EXPECT_TRUE(doc) << doc.error().to_string();
  std::vector<std::pair<std::string, std::string>> out;
  for (const BvhJoint& joint : doc->joints) {
    out.emplace_back(joint.name, joint.parent < 0 ? "" : doc->joints[joint.parent].name);
  }
  return out;
}

// The static roots the tests use: at the origin (as Bandai's), and moved and turned.
struct StaticRoot {
  Vec3 translation_m;
  Quat rotation;
};
const StaticRoot kRoots[] = {{Vec3::Zero(), Quat::Identity()},
                             {Vec3(0.4, 0.0, -1.5), Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()))},
                             {Vec3(-2.0, 0.1, 3.0), Quat(Eigen::AngleAxisd(-2.5, Vec3(0.1, 1.0, 0.2).normalized()))}};

TEST(TrajectoryJoint, TheHipsBelowAStaticRootBecomeJointZeroWithTheSameWorldPositions) {
  for (const char* file : {"cmu/16/16_15.amc", "cmu/16/16_35.amc"}) {
    const Clip plain = test::load_data_clip(file);
    for (const StaticRoot& root : kRoots) {
      const Clip clip = import_bvh(test::static_root_bvh(plain, root.translation_m, root.rotation));
      EXPECT_EQ(clip.skeleton.joint(0).name, plain.skeleton.joint(0).name) << file;
      ASSERT_EQ(clip.skeleton.static_ancestors().size(), 1u) << file;
      EXPECT_EQ(clip.skeleton.static_ancestors()[0].name, test::kStaticRootName);
      EXPECT_FALSE(clip.skeleton.find(test::kStaticRootName));
      ASSERT_TRUE(clip.detected_unit);
      EXPECT_EQ(clip.detected_unit->unit.name, "cm");
      // Written with 6 decimals of cm and degrees: a micrometre or so.
      EXPECT_LT(test::max_position_error_by_name(plain, clip), 1e-5) << file;
    }
  }
}

TEST(TrajectoryJoint, FrameDistancesAreThoseOfThePlainClip) {
  // Same clouds up to joint order, so D(a, b) agrees: compare the rings' sums of squared
  // distances between frames, which do not depend on the order of the points.
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Clip clip = import_bvh(test::static_root_bvh(plain, kRoots[1].translation_m, kRoots[1].rotation));
  PointCloudSettings settings;
  auto plain_layout = make_cloud_layout(plain.skeleton, settings);
  auto layout = make_cloud_layout(clip.skeleton, settings);
  ASSERT_TRUE(plain_layout && layout);
  const auto a = compute_clouds(plain.skeleton, plain.motion, *plain_layout);
  const auto b = compute_clouds(clip.skeleton, clip.motion, *layout);
  const size_t pa = static_cast<size_t>(plain_layout->point_count());
  const size_t pb = static_cast<size_t>(layout->point_count());
  // The imported skeleton has an End Site per leaf joint the plain one ends with: same bones.
  ASSERT_EQ(pa, pb);
  const auto frame_distance = [](const std::vector<float>& clouds, size_t points, int f, int g) {
    double sum = 0.0;
    for (size_t i = 0; i < points * 3; ++i) {
      const double d = clouds[f * points * 3 + i] - clouds[g * points * 3 + i];
      sum += d * d;
    }
    return sum;
  };
  double spread = 0.0;
  for (int f = 0; f + 37 < plain.motion.frame_count; f += 23) {
    const double expected = frame_distance(a, pa, f, f + 37);
    spread = std::max(spread, expected);
    EXPECT_NEAR(frame_distance(b, pb, f, f + 37), expected, 1e-6 * expected + 1e-9) << f;
  }
  EXPECT_GT(spread, 1.0);  // the frames compared do differ
}

TEST(TrajectoryJoint, AWrittenFileKeepsItsHierarchyAndReadsBackToTheSameWorld) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  for (const StaticRoot& root : kRoots) {
    const std::string original = test::static_root_bvh(plain, root.translation_m, root.rotation);
    const Clip clip = import_bvh(original);
    const std::string written = write_bvh(clip.skeleton, clip.motion, {});
    EXPECT_EQ(hierarchy(written), hierarchy(original));
    BvhImportSettings metres;
    metres.metres_per_unit = 1.0;
    const Clip back = import_bvh(written, metres);
    EXPECT_EQ(back.skeleton.static_ancestors().size(), 1u);
    EXPECT_LT(test::max_position_error_by_name(clip, back), 1e-5);
    // The static root stays where it was in the file.
    const Clip unfolded = unfold_static_root(back);
    const auto positions = world_positions(unfolded.skeleton, unfolded.motion);
    const size_t joints = static_cast<size_t>(unfolded.skeleton.joint_count());
    for (int f = 0; f < unfolded.motion.frame_count; f += 50) {
      EXPECT_LT((positions[f * joints] - root.translation_m).norm(), 1e-6);
    }
  }
}

TEST(TrajectoryJoint, UnfoldThenFoldIsTheIdentity) {
  const Clip plain = test::load_data_clip("cmu/16/16_35.amc");
  const Clip clip = import_bvh(test::static_root_bvh(plain, kRoots[2].translation_m, kRoots[2].rotation));
  const Clip unfolded = unfold_static_root(clip);
  EXPECT_EQ(unfolded.skeleton.joint_count(), clip.skeleton.joint_count() + 1);
  EXPECT_EQ(unfolded.skeleton.joint(0).name, test::kStaticRootName);
  EXPECT_LT(test::max_position_error_by_name(clip, unfolded), 1e-9);
  const auto joint = find_trajectory_joint(unfolded.skeleton, unfolded.motion, 0.003);
  ASSERT_TRUE(joint);
  EXPECT_EQ(*joint, 1);
  const Clip folded = fold_static_root(unfolded, *joint);
  EXPECT_LT(test::max_position_error_by_name(folded, unfolded), 1e-9);
  EXPECT_EQ(folded.skeleton.joint_count(), clip.skeleton.joint_count());
}

// A held pose of the rig stays unfolded (its hips never travel); folded as a clip of the rig
// that travels is, the two share a skeleton and the pose keeps every joint where it was. A clip
// of another rig, or one already folded, is left as it is.
TEST(TrajectoryJoint, AHeldPoseFoldsAsItsRigsTravellingClips) {
  const Clip plain = test::load_data_clip("cmu/16/16_35.amc");
  const Clip walk = import_bvh(test::static_root_bvh(plain, kRoots[1].translation_m, kRoots[1].rotation));
  ASSERT_EQ(walk.skeleton.static_ancestors().size(), 1u);
  const Clip pose = test::held_pose(plain, 40, 5);
  const Clip held = import_bvh(test::static_root_bvh(pose, kRoots[1].translation_m, kRoots[1].rotation));
  ASSERT_TRUE(held.skeleton.static_ancestors().empty());
  ASSERT_EQ(held.skeleton.joint_count(), walk.skeleton.joint_count() + 1);
  const Clip refolded = fold_as(held, walk.skeleton);
  EXPECT_EQ(refolded.skeleton.joint_count(), walk.skeleton.joint_count());
  EXPECT_EQ(refolded.skeleton.joint(0).name, walk.skeleton.joint(0).name);
  EXPECT_EQ(refolded.skeleton.static_ancestors().size(), 1u);
  EXPECT_LT(test::max_position_error_by_name(refolded, held), 1e-9);
  // Already folded, or not the rig: as it is.
  EXPECT_EQ(fold_as(walk, walk.skeleton).skeleton.joint_count(), walk.skeleton.joint_count());
  EXPECT_EQ(fold_as(plain, walk.skeleton).skeleton.joint_count(), plain.skeleton.joint_count());
}

TEST(TrajectoryJoint, ARootThatTravelsWithoutTurningGivesItsTravelToTheBody) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  // Turned as a z-up export's root is, once for all frames.
  const Quat turn(Eigen::AngleAxisd(-0.5 * std::numbers::pi, Vec3::UnitX()));
  const Clip engine = test::translation_root_clip(walk, turn, 0.0, true);
  EXPECT_LT(test::max_position_error_by_name(walk, engine), 1e-9);
  const auto joint = find_trajectory_joint(engine.skeleton, engine.motion, 0.003);
  ASSERT_TRUE(joint);
  EXPECT_EQ(engine.skeleton.joint(*joint).name, "root");  // CMU's root, where the legs part
  const Clip folded = fold_static_root(engine, *joint);
  ASSERT_EQ(folded.skeleton.joint_count(), walk.skeleton.joint_count());
  for (int j = 0; j < walk.skeleton.joint_count(); ++j) EXPECT_EQ(folded.skeleton.joint(j).name, walk.skeleton.joint(j).name);
  EXPECT_LT(test::max_position_error_by_name(walk, folded), 1e-9);
  EXPECT_EQ(folded.dropped_at_fold, std::vector<std::string>{"ik_foot_l"});
  ASSERT_EQ(folded.skeleton.static_ancestors().size(), 1u);
  EXPECT_EQ(folded.skeleton.static_ancestors()[0].name, "root_motion");
  // The body's joint turns as the walk's root does: the facing is the walk's.
  for (int f = 0; f < walk.motion.frame_count; f += 40) {
    EXPECT_LT(folded.motion.rotations(f)[0].angularDistance(walk.motion.rotations(f)[0]), 1e-9) << f;
  }
  // Read from a BVH file: folded at import, the helper named.
  const Clip read = import_bvh(write_bvh(engine.skeleton, engine.motion, BvhWriteSettings{}));
  EXPECT_EQ(read.skeleton.joint(0).name, "root");
  EXPECT_EQ(read.dropped_at_fold, std::vector<std::string>{"ik_foot_l"});
  EXPECT_LT(test::max_position_error_by_name(walk, read), 1e-4);

  // A root that turns says where the body faces (an engine's full root motion): no fold; nor
  // where the legs part at the root that travels without turning (a CMU root held level).
  const Clip turning = test::translation_root_clip(walk, turn, 0.01, true);
  EXPECT_FALSE(find_trajectory_joint(turning.skeleton, turning.motion, 0.003));
  Clip level = walk;
  for (int f = 0; f < level.motion.frame_count; ++f) level.motion.rotations(f)[0] = Quat::Identity();
  EXPECT_FALSE(find_trajectory_joint(level.skeleton, level.motion, 0.003));
}

// The clip with its last joint (a leaf hanging off the root) moved to index 1, before the body,
// as an engine may list its IK targets.
Clip last_joint_first(const Clip& clip) {
  const int n = clip.skeleton.joint_count();
  std::vector<int> old_of = {0, n - 1};  // new index -> old
  for (int j = 1; j < n - 1; ++j) old_of.push_back(j);
  std::vector<int> new_of(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) new_of[static_cast<size_t>(old_of[static_cast<size_t>(k)])] = k;
  std::vector<JointDef> joints;
  for (int k = 0; k < n; ++k) {
    JointDef joint = clip.skeleton.joint(old_of[static_cast<size_t>(k)]);
    if (joint.parent >= 0) joint.parent = new_of[static_cast<size_t>(joint.parent)];
    joints.push_back(joint);
  }
  Clip out = clip;
  out.skeleton = Skeleton(std::move(joints));
  out.motion = Motion(out.skeleton, clip.motion.frame_count, clip.motion.fps);
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    for (int k = 0; k < n; ++k) {
      const int j = old_of[static_cast<size_t>(k)];
      out.motion.rotations(f)[k] = clip.motion.rotations(f)[j];
      const int slot = out.skeleton.translation_slot(k);
      if (slot >= 0) out.motion.translations(f)[slot] = clip.motion.translations(f)[clip.skeleton.translation_slot(j)];
    }
  }
  return out;
}

// A held pose of a rig whose root travels without turning (not folded: it does not travel) is
// folded as its walks are, whatever the order of the joints beside the body, with their
// ancestors: the two share one skeleton to write (a .glb of both).
TEST(TrajectoryJoint, AHeldPoseFoldsAsItsRigsWalksWhateverItsJointsOrder) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip pose = test::held_pose(walk, 40, 5);
  const Clip engine = test::translation_root_clip(walk, Quat::Identity(), 0.0, true);
  const Clip folded = fold_static_root(engine, *find_trajectory_joint(engine.skeleton, engine.motion, 0.003));
  // The travelling root is written back at the origin: every walk of the rig has one hierarchy.
  ASSERT_EQ(folded.skeleton.static_ancestors().size(), 1u);
  EXPECT_EQ(folded.skeleton.static_ancestors()[0].translation_m, Vec3::Zero());
  for (const bool helper_first : {false, true}) {
    Clip held = test::translation_root_clip(pose, Quat::Identity(), 0.0, true);
    if (helper_first) held = last_joint_first(held);
    ASSERT_FALSE(find_trajectory_joint(held.skeleton, held.motion, 0.003));
    const Clip refolded = fold_as(held, folded.skeleton);
    ASSERT_EQ(refolded.skeleton.joint_count(), folded.skeleton.joint_count()) << helper_first;
    for (int j = 0; j < folded.skeleton.joint_count(); ++j) {
      EXPECT_EQ(refolded.skeleton.joint(j).name, folded.skeleton.joint(j).name);
    }
    ASSERT_EQ(refolded.skeleton.static_ancestors().size(), 1u);
    EXPECT_EQ(refolded.skeleton.static_ancestors()[0].translation_m, Vec3::Zero());
    EXPECT_LT(test::max_position_error_by_name(refolded, held), 1e-9);
  }
}

TEST(TrajectoryJoint, NoFoldWhenTheRootTravelsOrTheStaticRootHasNoTravellingChild) {
  // CMU data: the root is the hips and travels.
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  EXPECT_FALSE(find_trajectory_joint(plain.skeleton, plain.motion, 0.003));
  const Clip read = test::load_data_clip("bvh/131_01.bvh");
  EXPECT_TRUE(read.skeleton.static_ancestors().empty());
  // A static root above hips that stay in place (the first frame, held): nothing travels.
  Clip held = plain;
  held.motion = plain.motion.slice(0, 1);
  const Clip one = import_bvh(test::static_root_bvh(held));
  EXPECT_TRUE(one.skeleton.static_ancestors().empty());
  EXPECT_EQ(one.skeleton.joint(0).name, test::kStaticRootName);
  // A root that moves a little more than the tolerance is not static.
  Clip unfolded = unfold_static_root(import_bvh(test::static_root_bvh(plain)));
  for (int f = 0; f < unfolded.motion.frame_count; ++f) unfolded.motion.translations(f)[0].x() = 0.01 * (f % 2);
  EXPECT_FALSE(find_trajectory_joint(unfolded.skeleton, unfolded.motion, 0.003));
  // Folding can be turned off.
  BvhImportSettings off;
  off.fold_static_root = false;
  EXPECT_EQ(import_bvh(test::static_root_bvh(plain), off).skeleton.joint(0).name, test::kStaticRootName);
}

}  // namespace
}  // namespace mg
