// make_static_root_bvh OUT_DIR AMC...: writes each clip (AMC with the .asf beside it) as
// OUT_DIR/<stem>.bvh in a Bandai-like rig (tests/motion/static_root_bvh.h): a static root at
// the origin above the hips, 6 channels per joint, centimetres. For cli_static_root_test.sh.
#include <cstdio>
#include <filesystem>

#include "motion/static_root_bvh.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: make_static_root_bvh OUT_DIR AMC...\n");
    return 2;
  }
  mg::ClipLoader loader({});
  for (int i = 2; i < argc; ++i) {
    auto loaded = loader.load(argv[i]);
    mg::Status written = mg::Ok{};
    if (loaded) {
      const auto out = std::filesystem::path(argv[1]) / (std::filesystem::path(argv[i]).stem().string() + ".bvh");
      written = mg::write_file_atomic(out.string(), mg::test::static_root_bvh(loaded->clip));
    }
    if (!loaded || !written) {
      std::fprintf(stderr, "%s\n", (loaded ? written.error() : loaded.error()).to_string().c_str());
      return 1;
    }
  }
  return 0;
}
