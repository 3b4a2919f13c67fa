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

Status find_database_contacts(MotionDatabase& db, const FootContactSettings& settings) {
  db.frame_contacts.clear();
  db.contacts_error.clear();
  auto contacts = database_contacts(db, settings, db.foot_names);
  if (contacts) {
    db.frame_contacts = std::move(*contacts);
    return Ok{};
  }
  if (!db.foot_names.empty()) return contacts.error();
  db.contacts_error = contacts.error().message;
  return Ok{};
}

Result<std::vector<ContactMask>> contacts_of(const MotionDatabase& db) {
  if (static_cast<int>(db.frame_contacts.size()) == db.frame_count() && db.frame_count() > 0) return db.frame_contacts;
  if (!db.contacts_error.empty()) return Error{"", 0, db.contacts_error};
  return database_contacts(db, {}, db.foot_names);
}

}  // namespace mg
