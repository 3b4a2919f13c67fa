// Two-bone IK: reachable targets are met exactly with both bone lengths kept; far ones are met
// in direction with the leg at its limit; the knee stays on its side; a target at the ankle
// changes nothing; applied to a real CMU pose through forward kinematics, the ankle lands on
// the target and nothing outside the leg moves.
#include "motiongraph/skeleton/two_bone_ik.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

struct Leg {
  Vec3 hip, knee, ankle;
};

// A leg with a thigh of 0.35-0.5 m and a shank of 0.35-0.5 m, the knee bent 10-120 degrees
// forward, in a random orientation and place.
Leg random_leg(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double l1 = 0.35 + 0.15 * u(rng), l2 = 0.35 + 0.15 * u(rng);
  const double bend = (10.0 + 110.0 * u(rng)) * 3.14159265358979 / 180.0;
  const Quat turn = Quat::UnitRandom();
  Leg leg;
  leg.hip = Vec3(u(rng), 0.9 + 0.2 * u(rng), u(rng));
  leg.knee = leg.hip + turn * Vec3(0.0, -l1, 0.0);
  leg.ankle = leg.knee + turn * (Eigen::AngleAxisd(bend, Vec3::UnitX()) * Vec3(0.0, -l2, 0.0));
  return leg;
}

TEST(TwoBoneIk, ReachableTargetsAreMetWithBoneLengthsKept) {
  std::mt19937 rng(11);
  for (int i = 0; i < 2000; ++i) {
    const Leg leg = random_leg(rng);
    const double l1 = (leg.knee - leg.hip).norm(), l2 = (leg.ankle - leg.knee).norm();
    // A target strictly inside what the leg can span, in any direction from the hip.
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double reach = std::abs(l1 - l2) * 1.01 + 0.02 + u(rng) * (0.99 * (l1 + l2) - std::abs(l1 - l2) * 1.01 - 0.04);
    const Vec3 target = leg.hip + reach * Vec3::Random().normalized();
    const TwoBoneSolution s = solve_two_bone(leg.hip, leg.knee, leg.ankle, target, Vec3::UnitX());
    ASSERT_TRUE(s.reached) << i;
    EXPECT_NEAR((s.ankle - target).norm(), 0.0, 1e-9) << i;
    EXPECT_NEAR((s.knee - leg.hip).norm(), l1, 1e-9) << i;
    EXPECT_NEAR((s.ankle - s.knee).norm(), l2, 1e-9) << i;
    // The rotations say the same as the positions.
    EXPECT_NEAR((leg.hip + s.upper * (leg.knee - leg.hip) - s.knee).norm(), 0.0, 1e-9);
    EXPECT_NEAR((s.knee + s.upper * (s.lower * (leg.ankle - leg.knee)) - s.ankle).norm(), 0.0, 1e-9);
  }
}

TEST(TwoBoneIk, FarTargetsAreMetInDirectionAtTheExtensionLimit) {
  std::mt19937 rng(12);
  for (int i = 0; i < 500; ++i) {
    const Leg leg = random_leg(rng);
    const double l1 = (leg.knee - leg.hip).norm(), l2 = (leg.ankle - leg.knee).norm();
    const Vec3 direction = Vec3::Random().normalized();
    const Vec3 target = leg.hip + (l1 + l2) * 1.3 * direction;
    const TwoBoneSolution s = solve_two_bone(leg.hip, leg.knee, leg.ankle, target, Vec3::UnitX(), 0.98);
    EXPECT_FALSE(s.reached);
    EXPECT_NEAR((s.ankle - leg.hip).norm(), 0.98 * (l1 + l2), 1e-9);
    EXPECT_NEAR((s.ankle - leg.hip).normalized().dot(direction), 1.0, 1e-9);
    EXPECT_NEAR((s.knee - leg.hip).norm(), l1, 1e-9);
  }
}

TEST(TwoBoneIk, TheKneeKeepsItsSideAndATargetAtTheAnkleChangesNothing) {
  std::mt19937 rng(13);
  for (int i = 0; i < 1000; ++i) {
    const Leg leg = random_leg(rng);
    const Vec3 bend = (leg.knee - leg.hip).cross(leg.ankle - leg.knee).normalized();
    // A plant a few centimetres away, as the clean-up asks.
    const Vec3 target = leg.ankle + 0.05 * Vec3::Random();
    const TwoBoneSolution s = solve_two_bone(leg.hip, leg.knee, leg.ankle, target, bend);
    const Vec3 after = (s.knee - leg.hip).cross(s.ankle - s.knee);
    if (after.norm() > 1e-6) {
      EXPECT_GT(after.normalized().dot(bend), 0.5) << i;  // no flip
    }
    const TwoBoneSolution same = solve_two_bone(leg.hip, leg.knee, leg.ankle, leg.ankle, bend);
    EXPECT_LT(same.upper.angularDistance(Quat::Identity()), 1e-7);
    EXPECT_LT(same.lower.angularDistance(Quat::Identity()), 1e-7);
  }
  // A straight leg bends about the hint: the knee goes forward of the hip-ankle line.
  const Vec3 hip(0, 1, 0), knee(0, 0.55, 0), ankle(0, 0.1, 0);
  const TwoBoneSolution s = solve_two_bone(hip, knee, ankle, Vec3(0, 0.3, 0), Vec3::UnitX());
  EXPECT_TRUE(s.reached);
  EXPECT_GT(std::abs(s.knee.z()), 0.1);
  EXPECT_NEAR(s.knee.x(), 0.0, 1e-9);  // bent in the plane normal to the hint
}

TEST(TwoBoneIk, AKneeBentAgainstItsHingeIsBentTheUsualWay) {
  // Hyperextended by a few degrees (the shank behind the thigh's line the wrong way): the
  // solution bends the knee about the hinge, forwards, and still reaches the target.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> back(0.01, 0.08);
  for (int i = 0; i < 200; ++i) {
    const Vec3 hinge = Vec3::UnitX();
    const Vec3 hip(0, 1, 0), knee(0, 0.55, 0);
    const Vec3 ankle = knee + 0.45 * Vec3(0, -1, back(rng)).normalized();  // bent the wrong way about +x
    ASSERT_LT((knee - hip).cross(ankle - knee).dot(hinge), 0.0);
    const Vec3 target = ankle + Vec3(0, 0.02 + 0.05 * back(rng), 0.01);
    const TwoBoneSolution s = solve_two_bone(hip, knee, ankle, target, hinge);
    EXPECT_TRUE(s.reached) << i;
    EXPECT_GT((s.knee - hip).cross(s.ankle - s.knee).dot(hinge), 0.0) << i;  // bent forwards now
    EXPECT_NEAR((s.knee - hip).norm(), 0.45, 1e-9);
    EXPECT_NEAR((s.ankle - s.knee).norm(), 0.45, 1e-9);
  }
}

TEST(TwoBoneIk, AppliedToACmuPoseMovesOnlyTheLegAndPutsTheAnkleOnTheTarget) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const Skeleton& skeleton = clip.skeleton;
  const int n = skeleton.joint_count();
  const int femur = *skeleton.find("lfemur"), tibia = *skeleton.find("ltibia"), foot = *skeleton.find("lfoot");
  for (int frame : {0, 17, 40}) {
    std::vector<Vec3> positions(n);
    std::vector<Quat> rotations(n);
    forward_kinematics(skeleton, clip.motion, frame, positions, rotations);
    const Vec3 target = positions[foot] + Vec3(0.03, 0.03, 0.02);  // up: a straight leg reaches it
    const TwoBoneSolution s =
        solve_two_bone(positions[femur], positions[tibia], positions[foot], target, rotations[tibia] * Vec3::UnitX());
    ASSERT_TRUE(s.reached);
    Motion changed = clip.motion;
    auto locals = changed.rotations(frame);
    apply_two_bone(skeleton, rotations, femur, tibia, s, locals);
    std::vector<Vec3> after(n);
    std::vector<Quat> after_rotations(n);
    forward_kinematics(skeleton, changed, frame, after, after_rotations);
    EXPECT_NEAR((after[foot] - target).norm(), 0.0, 1e-9);
    EXPECT_NEAR((after[tibia] - s.knee).norm(), 0.0, 1e-9);
    for (int j = 0; j < n; ++j) {
      // Bone lengths everywhere; positions outside the left leg's subtree unchanged.
      const int parent = skeleton.joint(j).parent;
      if (parent >= 0) {
        EXPECT_NEAR((after[j] - after[parent]).norm(), (positions[j] - positions[parent]).norm(), 1e-9);
      }
      bool in_leg = false;
      for (int a = j; a >= 0; a = skeleton.joint(a).parent) in_leg = in_leg || a == tibia;
      if (!in_leg) {
        EXPECT_NEAR((after[j] - positions[j]).norm(), 0.0, 1e-12) << skeleton.joint(j).name;
      }
    }
  }
}

}  // namespace
}  // namespace mg
