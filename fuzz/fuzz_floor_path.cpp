// libFuzzer target for the floor-path reader: the input bytes are taken as the text of a
// PATH.json and given to mg::parse_path_json; a path that parses is then queried along its
// length (point, direction, tag, distance), as path synthesis does for every frame it tries.
// Errors are expected results; the fuzzer looks for crashes, hangs, leaks and sanitizer
// reports. Run it with scripts/fuzz.sh.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "motiongraph/synthesis/floor_path.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto path = mg::parse_path_json(text, "fuzz.json");
  if (!path.ok()) return 0;
  const double length = path->length_m();
  // A path that parses has at least two distinct, finite points.
  if (!(length > 0.0) || !std::isfinite(length)) std::abort();
  for (int i = -1; i <= 9; ++i) {
    const double s = length * i / 8.0;
    const mg::Vec2 p = path->point_at(s);
    const mg::Vec2 d = path->direction_at(s);
    (void)path->tag_at(s);
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(d.x()) || !std::isfinite(d.y())) std::abort();
    if (!(path->distance_to(p) <= 1e-6 * (1.0 + length + p.norm()))) std::abort();
  }
  return 0;
}
