// Forward kinematics: local rotations and translations -> world positions (metres) and world
// rotations of every joint, one pass over joints stored parent-before-child.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/motion/motion.h"

namespace mg {

// World positions (metres) and world rotations of frame `frame`; both spans hold
// skeleton.joint_count() entries, owned by the caller.
void forward_kinematics(const Skeleton& skeleton, const Motion& motion, int frame,
                        std::span<Vec3> world_positions_m, std::span<Quat> world_rotations);

// All frames: frame_count x joint_count world positions, frame-major.
std::vector<Vec3> world_positions(const Skeleton& skeleton, const Motion& motion);

}  // namespace mg
