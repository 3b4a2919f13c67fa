// ASF/AMC -> Skeleton + Motion, with Acclaim semantics (DESIGN.md section 2).
//
// Each bone has a fixed axis frame C (its 'axis' angles, composed in the order of its axis
// string, e.g. "XYZ" = Rz * Ry * Rx). An AMC frame gives a rotation M from the bone's dofs,
// applied in the order listed ("dof rx ry rz" = Rz * Ry * Rx). The bone's local rotation,
// relative to its parent in the global-aligned rest frame, is L = C * M * C^-1. A bone starts
// at its parent's end: the joint for a bone sits where the bone starts, its rest offset is the
// parent bone's vector (direction * length). Lengths become metres: 1 unit = 0.0254 / length
// metres (":units length 0.45" -> 0.05644 m).
//
// Joints: "root" (index 0), then one per bone named after it (depth first along
// :hierarchy), then for each leaf bone an end joint "<bone>_end" where the bone ends.
#pragma once

#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/io/amc_parser.h"
#include "motiongraph/io/asf_parser.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct AcclaimChannels {
  int joint = 0;
  std::vector<AcclaimDof> dofs;
  Quat axis = Quat::Identity();  // C
};

struct AcclaimRig {
  Skeleton skeleton;
  AmcLayout amc_layout;                  // the AMC lines, parallel to `channels`
  std::vector<AcclaimChannels> channels;
  double metres_per_unit = 1.0;
  bool angles_in_degrees = true;         // the ASF's unit, the AMC default
};

// Checks names and hierarchy (duplicates, unknown bones, a bone with two parents, cycles,
// bones unreachable from the root, unsupported dofs) and builds the rig.
Result<AcclaimRig> build_acclaim_rig(const AsfDocument& asf);

// The AMC's frames on the rig; fps is the capture rate (AMC files do not store it).
Motion motion_from_amc(const AcclaimRig& rig, const AmcDocument& amc, double fps);

}  // namespace mg
