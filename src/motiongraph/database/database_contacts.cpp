#include "motiongraph/database/database_contacts.h"

#include <fmt/format.h>

#include <string>

namespace mg {

Result<std::vector<ContactMask>> database_contacts(const MotionDatabase& db, const FootContactSettings& settings,
                                                   const FootJointNames& names) {
  if (auto s = settings.validate(); !s) return s.error();
  std::vector<FootJoints> feet;
  for (size_t s = 0; s < db.skeletons.size(); ++s) {
    auto found = find_foot_joints(db.skeletons[s], names);
    if (!found) {
      const std::string name = s < db.skeleton_names.size() ? db.skeleton_names[s] : std::to_string(s);
      return Error{"", 0, fmt::format("skeleton '{}': {}", name, found.error().message)};
    }
    feet.push_back(*found);
  }
  std::vector<ContactMask> masks(static_cast<size_t>(db.frame_count()), 0);
  for (const DatabaseClip& clip : db.clips) {
    auto contacts = detect_foot_contacts(db.skeletons[clip.skeleton], clip.motion, feet[clip.skeleton], settings);
    if (!contacts) return Error{"", 0, fmt::format("clip '{}': {}", clip.name, contacts.error().message)};
    for (int f = 0; f < clip.frame_count; ++f) masks[clip.first_frame + f] = contact_mask(*contacts, f);
  }
  return masks;
}

}  // namespace mg
