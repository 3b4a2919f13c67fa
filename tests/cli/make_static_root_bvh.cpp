// make_static_root_bvh [--z-up] OUT_DIR AMC...: writes each clip (AMC with the .asf beside it)
// as OUT_DIR/<stem>.bvh in a Bandai-like rig (tests/motion/static_root_bvh.h): a static root at
// the origin above the hips, 6 channels per joint, centimetres; with --z-up, every position
// turned as a z-up tool holds it (+y to +z). For cli_static_root_test.sh.
#include <cstdio>
#include <filesystem>
#include <string>

#include "motion/static_root_bvh.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/up_axis.h"

int main(int argc, char** argv) {
  const bool z_up = argc > 1 && std::string(argv[1]) == "--z-up";
  const int first = z_up ? 2 : 1;
  if (argc < first + 2) {
    std::fprintf(stderr, "usage: make_static_root_bvh [--z-up] OUT_DIR AMC...\n");
    return 2;
  }
  mg::ClipLoader loader({});
  for (int i = first + 1; i < argc; ++i) {
    auto loaded = loader.load(argv[i]);
    mg::Status written = mg::Ok{};
    if (loaded) {
      if (z_up) mg::turn_clip(loaded->clip, mg::up_axis_to_y(mg::UpAxis::kZ).conjugate());
      const auto out = std::filesystem::path(argv[first]) / (std::filesystem::path(argv[i]).stem().string() + ".bvh");
      written = mg::write_file_atomic(out.string(), mg::test::static_root_bvh(loaded->clip));
    }
    if (!loaded || !written) {
      std::fprintf(stderr, "%s\n", (loaded ? written.error() : loaded.error()).to_string().c_str());
      return 1;
    }
  }
  return 0;
}
