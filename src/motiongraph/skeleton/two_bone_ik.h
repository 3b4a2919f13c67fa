// Analytic two-bone IK (hip, knee, ankle), the leg solver of footskate clean-up (Kovar,
// Schreiner & Gleicher, SCA 2002; DESIGN.md 5b): put the ankle on a target while both bones
// keep their lengths and the knee bends in the plane it bent in.
//
// In world space, with a the hip, b the knee, c the ankle and t the target:
//  1. the distance the leg must span, |t - a|, is clamped to what it can: at most
//     max_extension of the full length l1 + l2 (a straight knee snaps and looks locked), at
//     least a little over |l1 - l2|;
//  2. the knee opens or closes about its bend axis n = (b - a) x (c - b) until the ankle is that
//     far from the hip (law of cosines). `bend_hint` is the knee's hinge axis (the direction
//     n has when the knee bends the usual way, e.g. learnt from the motion; zero: none): a
//     knee bent against it (hyperextended) or straight is straightened and bent about it
//     instead, so the knee never bends backwards;
//  3. the whole leg turns about the hip by the shortest arc that points it at the target.
// So a reachable target is met exactly, a far one is met in direction with the leg at
// max_extension, and the knee never flips to the other side of its plane (step 3 turns the
// plane with the leg by the least rotation).
//
// The result is two world-space rotations: `lower` about the knee (applied to the shank first),
// `upper` about the hip (applied to the whole leg then). apply_two_bone() turns them into the
// local rotations of the upper and lower joints of a pose (forward_kinematics.h's convention:
// world[j] = world[parent] * local[j]).
#pragma once

#include <span>

#include "motiongraph/skeleton/skeleton.h"

namespace mg {

struct TwoBoneSolution {
  Quat upper = Quat::Identity();  // world rotation about the hip, applied to the whole leg
  Quat lower = Quat::Identity();  // world rotation about the knee, applied to the shank first
  Vec3 knee = Vec3::Zero();       // where the knee and ankle end up
  Vec3 ankle = Vec3::Zero();
  bool reached = false;           // the ankle is on the target (within 1e-6 m)
};

TwoBoneSolution solve_two_bone(const Vec3& hip, const Vec3& knee, const Vec3& ankle, const Vec3& target,
                               const Vec3& bend_hint, double max_extension = 0.999);

// Applies a solution to one frame's local rotations: `upper_joint` is the joint whose world
// rotation turns the thigh (at the hip; the knee joint is its child), `lower_joint` the one
// turning the shank (at the knee). world_rotations are the frame's before the change
// (forward_kinematics()); only the two joints' local rotations change.
void apply_two_bone(const Skeleton& skeleton, std::span<const Quat> world_rotations, int upper_joint, int lower_joint,
                    const TwoBoneSolution& solution, std::span<Quat> local_rotations);

}  // namespace mg
