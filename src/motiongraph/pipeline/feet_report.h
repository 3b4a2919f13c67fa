// How `info` and Python's load_library() tell the feet found (skeleton/foot_joints.h) and their
// contacts (motion/foot_contacts.h): for one clip, and for a library.
#pragma once

#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/skeleton/skeleton.h"

namespace mg {

// "lfoot > ltoes, rfoot > rtoes (found by name; planted 84 % and 83 % of frames)"; source says
// how the feet were got ("found by name", "--feet").
std::string feet_description(const Skeleton& skeleton, const FootJoints& feet, std::span<const ContactMask> masks,
                             const std::string& source);
// {"source", "left": {"ankle", "toe" (null without one), "planted_share" (null for one frame)},
// "right": {...}}.
nlohmann::json feet_json(const Skeleton& skeleton, const FootJoints& feet, std::span<const ContactMask> masks,
                         const std::string& source);
// "not found: WHY; without them there is no foot clean-up and no travel from the feet (--feet
// names them)", and its JSON {"source": null, "missing": WHY}.
std::string missing_feet_description(const std::string& why);
nlohmann::json missing_feet_json(const std::string& why);

}  // namespace mg
