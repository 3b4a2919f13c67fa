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

// Sets db.frame_contacts from db.foot_names, or, when the feet cannot be found, clears them and
// sets db.contacts_error. Fails only when a joint the user named is missing: that is the user's
// mistake to fix, not a rig without feet.
Status find_database_contacts(MotionDatabase& db, const FootContactSettings& settings = {});

// The database's own contacts when it holds them for every frame, else found now (databases
// made in memory); fails with db.contacts_error or the reason the feet are not found.
Result<std::vector<ContactMask>> contacts_of(const MotionDatabase& db);

}  // namespace mg
