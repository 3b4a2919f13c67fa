#include "motiongraph/synthesis/control_script.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "motiongraph/core/json_text.h"
#include "motiongraph/core/text.h"

namespace mg {

const ScriptedControl& ControlScript::at(double t) const {
  size_t i = 0;
  while (i + 1 < controls.size() && controls[i + 1].at_s <= t) ++i;
  return controls[i];
}

Result<ControlScript> parse_control_script(std::string_view text, const std::string& file_name) {
  auto parsed = parse_json_text(text, file_name);
  if (!parsed) return parsed.error();
  const nlohmann::json& doc = *parsed;
  auto fail = [&](const std::string& what) { return Error{file_name, 0, what}; };
  if (!doc.is_object() || !doc.contains("controls") || !doc["controls"].is_array() || doc["controls"].empty()) {
    return fail("expected an object with a non-empty \"controls\" array");
  }
  if (const std::string key = unknown_key(doc, {"duration_s", "controls"}); !key.empty()) {
    return fail(fmt::format("unknown key \"{}\" (a script has \"duration_s\" and \"controls\")", key));
  }
  ControlScript script;
  ScriptedControl current;
  for (size_t i = 0; i < doc["controls"].size(); ++i) {
    const auto& c = doc["controls"][i];
    if (!c.is_object() || !c.contains("at_s") || !c["at_s"].is_number()) {
      return fail(fmt::format("controls[{}] needs \"at_s\" (seconds)", i));
    }
    if (const std::string key = unknown_key(c, {"at_s", "heading", "heading_deg", "tag", "rest"}); !key.empty()) {
      return fail(fmt::format("controls[{}]: unknown key \"{}\" (a control has \"at_s\", \"heading\" or "
                              "\"heading_deg\", \"tag\" and \"rest\")",
                              i, key));
    }
    if (c.contains("heading") && c.contains("heading_deg")) {
      return fail(fmt::format("controls[{}] gives both \"heading\" and \"heading_deg\": give one", i));
    }
    const double at = c["at_s"].get<double>();
    if (i == 0 && at != 0.0) {
      return fail(fmt::format("controls[0]: the first control is at 0 s (the script's start), not {:g} s", at));
    }
    if (!std::isfinite(at) || at < 0.0 || (i > 0 && at <= current.at_s)) {
      return fail(fmt::format("controls[{}]: at_s {:g} must come after the control before it ({:g} s)", i, at,
                              current.at_s));
    }
    if (at > ControlScript::kMaxSeconds) {
      return fail(fmt::format("controls[{}]: at_s {:g} is past a day ({:g} s)", i, at, ControlScript::kMaxSeconds));
    }
    current.at_s = at;
    if (c.contains("heading")) {
      const std::string h = c["heading"].is_string() ? c["heading"].get<std::string>() : "";
      if (h == "north") current.bearing_deg = 0.0;
      else if (h == "east") current.bearing_deg = 90.0;
      else if (h == "south") current.bearing_deg = 180.0;
      else if (h == "west") current.bearing_deg = 270.0;
      else {
        return fail(fmt::format("controls[{}]: heading must be north, east, south or west (a bearing in degrees is "
                                "\"heading_deg\": {})",
                                i, c["heading"].is_number() ? c["heading"].dump() : "90"));
      }
    }
    if (c.contains("heading_deg")) {
      if (!c["heading_deg"].is_number() || !std::isfinite(c["heading_deg"].get<double>())) {
        return fail(fmt::format("controls[{}]: heading_deg must be a number", i));
      }
      if (std::abs(c["heading_deg"].get<double>()) > ControlScript::kMaxHeadingDeg) {
        return fail(fmt::format("controls[{}]: heading_deg {:g} is past +-{:g} degrees", i,
                                c["heading_deg"].get<double>(), ControlScript::kMaxHeadingDeg));
      }
      current.bearing_deg = c["heading_deg"].get<double>();
    }
    if (c.contains("tag")) {
      if (!c["tag"].is_string()) return fail(fmt::format("controls[{}]: tag must be a string", i));
      current.tag = c["tag"].get<std::string>();
      if (ascii_lower(current.tag) == "any") current.tag.clear();
    }
    if (c.contains("rest")) {
      if (!c["rest"].is_boolean()) return fail(fmt::format("controls[{}]: rest must be true or false", i));
      current.rest = c["rest"].get<bool>();
    }
    if (!c.contains("heading") && !c.contains("heading_deg") && !c.contains("tag") && !c.contains("rest")) {
      return fail(fmt::format("controls[{}] gives no \"heading\", \"heading_deg\", \"tag\" or \"rest\": it changes "
                              "nothing",
                              i));
    }
    script.controls.push_back(current);
  }
  script.duration_s = script.controls.back().at_s + 4.0;
  if (doc.contains("duration_s")) {
    if (!doc["duration_s"].is_number() || !(doc["duration_s"].get<double>() > 0.0) ||
        !std::isfinite(doc["duration_s"].get<double>())) {
      return fail("\"duration_s\" must be a positive number of seconds");
    }
    if (doc["duration_s"].get<double>() > ControlScript::kMaxSeconds) {
      return fail(fmt::format("\"duration_s\" {:g} is longer than a day ({:g} s)", doc["duration_s"].get<double>(),
                              ControlScript::kMaxSeconds));
    }
    script.duration_s = doc["duration_s"].get<double>();
    if (script.controls.back().at_s >= script.duration_s) {
      return fail(fmt::format("controls[{}] at {:g} s comes at or after the script's end (\"duration_s\" {:g})",
                              script.controls.size() - 1, script.controls.back().at_s, script.duration_s));
    }
  }
  return script;
}

}  // namespace mg
