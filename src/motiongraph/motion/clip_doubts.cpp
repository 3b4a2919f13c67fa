// What looks wrong with a clip as read (clip_doubts.h).
#include "motiongraph/motion/clip_doubts.h"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "motiongraph/core/quantile.h"
#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

Status ClipDoubtSettings::validate() const {
  if (!(off_floor_m > 0.0)) return Error{"", 0, "the distance off the floor must be positive"};
  if (!(min_contactless_s >= 0.0)) return Error{"", 0, "the shortest clip without contact must be >= 0 s"};
  return Ok{};
}

std::vector<std::string> clip_doubts(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                                     std::span<const ContactMask> contacts, const ClipDoubtSettings& settings) {
  std::vector<std::string> out;
  if (joint_count <= 0 || world_positions_m.empty()) return out;
  const size_t frames = world_positions_m.size() / static_cast<size_t>(joint_count);
  std::vector<double> lowest(frames, std::numeric_limits<double>::infinity());
  for (size_t f = 0; f < frames; ++f) {
    for (int j = 0; j < joint_count; ++j) {
      lowest[f] = std::min(lowest[f], static_cast<double>(world_positions_m[f * joint_count + j].y()));
    }
  }
  const double low = quantile(lowest, 0.02), median = quantile(lowest, 0.5), high = quantile(lowest, 0.98);
  if (median < -settings.off_floor_m) {
    out.push_back(fmt::format("its lowest joint is {:.2f}-{:.2f} m below the floor (y = 0)", -high, -low));
  } else if (low > settings.off_floor_m) {
    out.push_back(fmt::format("its lowest joint stays {:.2f}-{:.2f} m above the floor (y = 0)", low, high));
  }
  if (contacts.size() == frames && fps > 0.0 && static_cast<double>(frames) / fps >= settings.min_contactless_s &&
      std::all_of(contacts.begin(), contacts.end(), [](ContactMask m) { return m == 0; })) {
    out.push_back("no foot rests on the floor in any frame");
  }
  return out;
}

std::vector<std::string> clip_doubts(const Skeleton& skeleton, const Motion& motion,
                                     const ClipDoubtSettings& settings) {
  const std::vector<Vec3> positions = world_positions(skeleton, motion);
  std::vector<ContactMask> masks;
  if (auto feet = find_foot_joints(skeleton, {})) {
    if (auto contacts = detect_foot_contacts(positions, skeleton.joint_count(), motion.fps, *feet, {})) {
      for (int f = 0; f < motion.frame_count; ++f) masks.push_back(contact_mask(*contacts, f));
    }
  }
  return clip_doubts(positions, skeleton.joint_count(), motion.fps, masks, settings);
}

std::string clip_doubts_text(const std::vector<std::string>& doubts) {
  std::string joined;
  for (size_t i = 0; i < doubts.size(); ++i) joined += (i == 0 ? "" : ", and ") + doubts[i];
  return joined + "; its root translation may be wrong";
}

std::string clip_doubt_line(const std::string& name, const std::vector<std::string>& doubts) {
  return fmt::format("{}: {} (the distances compare clips as read, so the graph may join it to nothing)", name,
                     clip_doubts_text(doubts));
}

}  // namespace mg
