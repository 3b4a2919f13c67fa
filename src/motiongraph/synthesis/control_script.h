// A timed control script for the controller, so steering can be replayed without a display:
//   {"duration_s": 12,
//    "controls": [{"at_s": 0, "heading": "north", "tag": "walk"},
//                 {"at_s": 4, "heading_deg": 90},
//                 {"at_s": 8, "tag": "run"}]}
// heading: north, east, south, west (north = -z, east = +x) or heading_deg, a bearing in
// degrees clockwise from north; "rest": true comes to rest (controller.h) and false takes it
// back. A control keeps what it does not say from the one before (the first starts from north,
// any tag and no rest), and says something (a heading, a tag or rest); tag "" or "any" clears
// the tag. Controls must be in increasing time from 0, and end within a day
// (kMaxSeconds); headings lie within +-kMaxHeadingDeg.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"

namespace mg {

struct ScriptedControl {
  double at_s = 0.0;
  double bearing_deg = 0.0;
  std::string tag;  // "" = any
  bool rest = false;
};

struct ControlScript {
  static constexpr double kMaxSeconds = 86400.0;  // a day: the latest control and the longest duration
  static constexpr double kMaxHeadingDeg = 36000.0;  // a hundred turns: past it no heading is meant

  double duration_s = 0.0;
  std::vector<ScriptedControl> controls;  // each complete (earlier values carried over)

  // The control in force at time t.
  const ScriptedControl& at(double t) const;
};

Result<ControlScript> parse_control_script(std::string_view text, const std::string& file_name);

}  // namespace mg
