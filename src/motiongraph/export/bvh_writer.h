// Motion -> BVH text. Lengths in metres by default (units_per_metre scales them), angles in
// degrees, each joint's rotation in the Euler order its skeleton prefers (the order it was read
// with, ZYX for ASF bones), unwrapped from frame to frame so curves stay continuous.
//
// Position channels go on the root only (DESIGN.md section 6: readers disagree about them
// elsewhere). A non-root joint whose translation is animated but constant is written as an
// OFFSET; one that really moves keeps its position channels (Blender's reading). End joints
// become End Sites; a leaf joint that is not an end joint gets a zero End Site.
//
// A skeleton whose joint 0 was a trajectory joint below static joints (motion/trajectory_joint.h)
// is written with those joints back above it, as the file had them: the root with constant
// position and rotation channels, joint 0 below with position and rotation channels.
#pragma once

#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct BvhWriteSettings {
  double units_per_metre = 1.0;
  int decimals = 6;  // fixed decimals for lengths and angles (6: 1 micrometre at 1 unit = 1 m)
  // The heading's joint (joint 0; the hips below a static root) in the file's own rotation
  // order (a clip written back as it was read) rather than with the vertical outermost
  // (root_rotation_order.h: a figure turning through east or west made spikes in curve editors).
  bool keep_root_order = false;

  Status validate() const;
};

std::string write_bvh(const Skeleton& skeleton, const Motion& motion, const BvhWriteSettings& settings);

}  // namespace mg
