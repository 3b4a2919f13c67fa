// Foot contacts of every frame of a motion database (motion/foot_contacts.h), found clip by
// clip on each clip's own skeleton: what synthesis carries into the frames it plays
// (MotionAssembler::append_edge_contacts) for the foot clean-up (synthesis/foot_cleanup.h).
#pragma once

#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/motion/foot_contacts.h"

namespace mg {

// Per global frame, the contact bits of its clip's feet. Fails, naming the skeleton, when a
// skeleton's feet cannot be found (skeleton/foot_joints.h).
Result<std::vector<ContactMask>> database_contacts(const MotionDatabase& db, const FootContactSettings& settings = {},
                                                   const FootJointNames& names = {});

}  // namespace mg
