// The Euler order a figure's root rotation (joint 0: the joint that carries its heading) is
// written in, by the writers of Euler curves (BVH, FBX).
#pragma once

#include "motiongraph/skeleton/rotation.h"
#include "motiongraph/skeleton/skeleton.h"

namespace mg {

// The axis nearest the vertical (y, in the frame of the static ancestors above joint 0)
// outermost, so that the middle angle, where Euler angles lock, is a lean rather than the
// heading a travelling figure turns through freely (CMU's root, in Acclaim's XYZ, has the
// heading in the middle: its curves jumped by tens of degrees at every quarter turn).
ComposeOrder root_rotation_order(const Skeleton& skeleton);

}  // namespace mg
