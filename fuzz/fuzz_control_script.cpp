// libFuzzer target for the controller's script reader: the input bytes are taken as the text
// of a control script (JSON) and given to mg::parse_control_script; a script that parses is
// then asked for the control in force over its duration, as the controller does.
// Errors are expected results; the fuzzer looks for crashes, hangs, leaks and sanitizer
// reports. Run it with scripts/fuzz.sh.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "motiongraph/synthesis/control_script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto script = mg::parse_control_script(text, "fuzz.json");
  if (!script.ok()) return 0;
  if (script->controls.empty()) std::abort();  // the parser asks for at least one
  const double duration = script->duration_s;
  for (int i = -1; i <= 9; ++i) {
    const double t = duration * i / 8.0;
    const mg::ScriptedControl& control = script->at(t);
    if (!std::isfinite(control.bearing_deg)) std::abort();
  }
  // Controls are in increasing time.
  for (size_t i = 1; i < script->controls.size(); ++i) {
    if (!(script->controls[i - 1].at_s < script->controls[i].at_s)) std::abort();
  }
  return 0;
}
