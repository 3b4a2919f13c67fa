// World positions as JSON for other tools and the studio:
//   {"fps": F, "joints": [{"name": ..., "parent": index}, ...],
//    "positions": [frame][joint][x, y, z]}   (metres, rounded to the micrometre)
// and, when given, the feet's contacts (motion/foot_contacts.h) per frame:
//    "contacts": {"joints": [left ankle, left toe, right ankle, right toe: the names of those
//                 the skeleton has], "joint_indices": [their indices in "joints"],
//                 "planted": [frame][each of those joints] 0 or 1}
#pragma once

#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct PositionsJsonContacts {
  FootJoints feet;
  std::span<const ContactMask> masks;  // one per frame
};

// The "contacts" member above for the first frame_count frames (at most masks.size()).
nlohmann::json contacts_json(const Skeleton& skeleton, const PositionsJsonContacts& contacts, int frame_count);

std::string write_positions_json(const Skeleton& skeleton, const Motion& motion,
                                 const PositionsJsonContacts* contacts = nullptr);

}  // namespace mg
