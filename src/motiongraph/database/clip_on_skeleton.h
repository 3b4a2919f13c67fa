// A database clip played on another of the database's skeletons, as synthesis plays every frame
// on its target skeleton (synthesis/assembler.h): the joint rotations kept, the translations (the
// root's and any translated joint's) scaled by the target's leg length over the clip's own, so
// that a shorter subject's stride fits a taller one's legs.
#pragma once

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"

namespace mg {

// leg_length(target) / leg_length(other); 1 when either has no legs found.
double leg_scale(const Skeleton& target, const Skeleton& other);

// Clip `clip` of db on skeleton `target`. Fails when target is not one of db's skeletons or
// differs from the clip's in joints or translated joints.
Result<Motion> clip_on_skeleton(const MotionDatabase& db, int clip, int target);

}  // namespace mg
