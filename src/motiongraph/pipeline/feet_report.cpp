#include "motiongraph/pipeline/feet_report.h"

#include <fmt/format.h>

namespace mg {

namespace {

// "lfoot > ltoes": a foot's joints (the ankle alone when it has no toe).
std::string foot_text(const Skeleton& skeleton, const Foot& foot) {
  const std::string& ankle = skeleton.joint(foot.ankle).name;
  return foot.toe < 0 ? ankle : ankle + " > " + skeleton.joint(foot.toe).name;
}

// Share of the frames in which a foot (its ankle or its toe) rests on the floor.
double planted_share(std::span<const ContactMask> masks, FootSide side) {
  if (masks.empty()) return 0.0;
  const auto bits = static_cast<ContactMask>(contact_bit(side, FootPart::kAnkle) | contact_bit(side, FootPart::kToe));
  size_t planted = 0;
  for (ContactMask mask : masks) planted += (mask & bits) != 0 ? 1 : 0;
  return static_cast<double>(planted) / static_cast<double>(masks.size());
}

}  // namespace

std::string feet_description(const Skeleton& skeleton, const FootJoints& feet, std::span<const ContactMask> masks,
                             const std::string& source) {
  if (masks.size() < 2) {  // a held pose of one frame: no motion to see a foot rest in
    return fmt::format("{}, {} ({}; one frame: contacts not measured)", foot_text(skeleton, feet.left),
                       foot_text(skeleton, feet.right), source);
  }
  return fmt::format("{}, {} ({}; planted {:.0f} % and {:.0f} % of frames)", foot_text(skeleton, feet.left),
                     foot_text(skeleton, feet.right), source, 100.0 * planted_share(masks, FootSide::kLeft),
                     100.0 * planted_share(masks, FootSide::kRight));
}

nlohmann::json feet_json(const Skeleton& skeleton, const FootJoints& feet, std::span<const ContactMask> masks,
                         const std::string& source) {
  const auto foot_json = [&](const Foot& foot, FootSide side) {
    return nlohmann::json{{"ankle", skeleton.joint(foot.ankle).name},
                          {"toe", foot.toe < 0 ? nlohmann::json() : nlohmann::json(skeleton.joint(foot.toe).name)},
                          {"planted_share",
                           masks.size() < 2 ? nlohmann::json() : nlohmann::json(planted_share(masks, side))}};
  };
  return {{"source", source}, {"left", foot_json(feet.left, FootSide::kLeft)},
          {"right", foot_json(feet.right, FootSide::kRight)}};
}

std::string missing_feet_description(const std::string& why) {
  return fmt::format("not found: {}; without them there is no foot clean-up and no travel from the feet (--feet "
                     "names them)",
                     why);
}

nlohmann::json missing_feet_json(const std::string& why) { return {{"source", nullptr}, {"missing", why}}; }

}  // namespace mg
