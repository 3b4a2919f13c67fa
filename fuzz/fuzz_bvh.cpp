// libFuzzer target for the BVH (Biovision hierarchy) reader: the input bytes are taken as the
// text of a .bvh file and given to mg::parse_bvh; when that succeeds, the document is turned
// into a skeleton and motion with mg::clip_from_bvh (default settings, which include the
// detection of leading rest frames, of a static root above the hips and of the length unit).
// Errors are expected results; the fuzzer looks for crashes, hangs, leaks and sanitizer
// reports. Run it with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/motion/bvh_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto bvh = mg::parse_bvh(text, "fuzz.bvh");
  if (!bvh.ok()) return 0;
  auto clip = mg::clip_from_bvh(bvh.value(), mg::BvhImportSettings{});
  (void)clip.ok();
  return 0;
}
