// Detects rest or T-pose frames that a converter put in front of the captured motion (CMU
// BVH conversions do: a zero pose, a T-pose, or two such frames). Such frames are not motion:
// played, they pop; in a motion graph, they are frames no transition should reach.
//
// The test: the first frames have a root rotation of exactly zero, which captured data never
// has, the frames after them do not, and the pose or the root jumps where they end (more than
// 3 times the median frame-to-frame change of the next 120 frames). At most 5 frames.
#pragma once

#include "motiongraph/motion/motion.h"

namespace mg {

// Largest angle (radians) by which any joint's local rotation differs between two frames.
double pose_change_rad(const Motion& motion, int frame_a, int frame_b);

// How many leading frames were added by a converter (0 when none).
int leading_added_frames(const Motion& motion);

}  // namespace mg
