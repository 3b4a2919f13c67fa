// libFuzzer target for the ASF (Acclaim skeleton) reader: the input bytes are taken as the
// text of an .asf file and given to mg::parse_asf; when that succeeds, the document is built
// into a rig with mg::build_acclaim_rig (names, hierarchy, cycles, units).
// Errors are expected results; the fuzzer looks for crashes, hangs, leaks and sanitizer
// reports. Run it with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "motiongraph/io/asf_parser.h"
#include "motiongraph/motion/acclaim_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto asf = mg::parse_asf(text, "fuzz.asf");
  if (!asf.ok()) return 0;
  auto rig = mg::build_acclaim_rig(asf.value());
  (void)rig.ok();
  return 0;
}
