// Analytic two-bone IK: law of cosines at the knee, shortest arc at the hip.
#include "motiongraph/skeleton/two_bone_ik.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mg {

namespace {

// A unit axis perpendicular to `v`, as close to `hint` as can be.
Vec3 perpendicular_axis(const Vec3& v, const Vec3& hint) {
  const Vec3 u = v.normalized();
  Vec3 axis = hint - hint.dot(u) * u;
  if (axis.norm() < 1e-9) axis = u.unitOrthogonal();
  return axis.normalized();
}

}  // namespace

TwoBoneSolution solve_two_bone(const Vec3& hip, const Vec3& knee, const Vec3& ankle, const Vec3& target,
                               const Vec3& bend_hint, double max_extension) {
  TwoBoneSolution out;
  const Vec3 thigh = knee - hip, shank = ankle - knee;
  const double l1 = thigh.norm(), l2 = shank.norm();
  out.knee = knee;
  out.ankle = ankle;
  if (!(l1 > 0.0) || !(l2 > 0.0)) return out;

  // 1. The span the leg can make.
  const double wanted = (target - hip).norm();
  const double longest = max_extension * (l1 + l2), shortest = std::abs(l1 - l2) * 1.001 + 1e-9;
  const double span = std::clamp(wanted, shortest, std::max(shortest, longest));

  // 2. The knee about its bend axis until the ankle is `span` from the hip. A knee bent against
  // the hint (hyperextended) or straight is first straightened, then bent about the hint.
  Vec3 axis = thigh.cross(shank);
  const double cos_want = std::clamp((l1 * l1 + l2 * l2 - span * span) / (2.0 * l1 * l2), -1.0, 1.0);
  const bool has_hint = bend_hint.norm() > 1e-12;
  if (axis.norm() <= 1e-6 * l1 * l2 || (has_hint && axis.dot(bend_hint) < 0.0)) {
    const Vec3 hinge = perpendicular_axis(thigh, has_hint ? bend_hint : axis);
    const double bend = std::numbers::pi - std::acos(cos_want);  // 0 for a straight leg
    out.lower = Quat(Eigen::AngleAxisd(bend, hinge)) * Quat::FromTwoVectors(shank, thigh);
  } else {
    axis.normalize();
    const double cos_now = std::clamp((-thigh).dot(shank) / (l1 * l2), -1.0, 1.0);  // interior angle at the knee
    const double change = std::acos(cos_want) - std::acos(cos_now);
    // Opening the knee turns the shank one way about the axis; try both and keep the one that
    // gives the span (they differ unless change is 0).
    const Quat open(Eigen::AngleAxisd(change, axis)), close(Eigen::AngleAxisd(-change, axis));
    const double open_error = std::abs((thigh + open * shank).norm() - span);
    const double close_error = std::abs((thigh + close * shank).norm() - span);
    out.lower = open_error <= close_error ? open : close;
  }
  const Vec3 leg = thigh + out.lower * shank;  // hip to ankle after the knee moved

  // 3. The whole leg towards the target by the shortest arc.
  const Vec3 to_target = target - hip;
  if (to_target.norm() > 1e-12 && leg.norm() > 1e-12) out.upper = Quat::FromTwoVectors(leg, to_target);
  out.knee = hip + out.upper * thigh;
  out.ankle = hip + out.upper * leg;
  out.reached = (out.ankle - target).norm() <= 1e-6;
  return out;
}

void apply_two_bone(const Skeleton& skeleton, std::span<const Quat> world_rotations, int upper_joint, int lower_joint,
                    const TwoBoneSolution& solution, std::span<Quat> local_rotations) {
  // New world rotations: upper * W[upper], upper * lower * W[lower]. Locals follow from
  // world[j] = world[parent] * local[j]; the lower joint's parent chain from the upper joint
  // turns by `upper` as a whole, so its local rotation only takes `lower`, seen from there.
  const int upper_parent = skeleton.joint(upper_joint).parent;
  const Quat parent = upper_parent >= 0 ? world_rotations[upper_parent] : Quat::Identity();
  local_rotations[upper_joint] = (parent.conjugate() * solution.upper * world_rotations[upper_joint]).normalized();
  const int lower_parent = skeleton.joint(lower_joint).parent;
  const Quat& lower_parent_world = world_rotations[lower_parent];
  local_rotations[lower_joint] =
      (lower_parent_world.conjugate() * solution.lower * world_rotations[lower_joint]).normalized();
}

}  // namespace mg
