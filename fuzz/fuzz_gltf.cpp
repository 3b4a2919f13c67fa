// libFuzzer target for the glTF reader: the input bytes are taken as a .glb (or, without glTF's
// binary magic, a .gltf's JSON text) and given to mg::clips_from_gltf with default settings
// (the keys' rate, a static root folded, glTF's y up; at most 2 million joint poses a file, so
// that a run stays within the fuzzer's time and memory). External buffers are looked for
// in a folder that does not exist, so that no input reads this machine's files. Errors are
// expected results; the fuzzer looks for crashes, hangs, leaks and sanitizer reports.
//
// Seeds: with MOTIONGRAPH_FUZZ_GLTF_SEED=FOLDER and MOTIONGRAPH_FUZZ_CLIPS=A.amc,B.amc (a
// skeleton beside them), the target writes a .glb of the first frames of each clip, and one of
// them all as one animation set, into FOLDER and exits (scripts/fuzz.sh does this first).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/export/gltf_writer.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/gltf_import.h"

namespace {

void write_seeds(const std::string& folder, const std::string& clips) {
  mg::ClipLoader loader(mg::ClipLoadSettings{});
  std::vector<mg::Clip> read;
  std::stringstream list(clips);
  for (std::string path; std::getline(list, path, ',');) {
    auto loaded = loader.load(path);
    if (!loaded) std::abort();
    loaded->clip.motion = loaded->clip.motion.slice(0, std::min(loaded->clip.motion.frame_count, 6));
    read.push_back(std::move(loaded->clip));
  }
  std::vector<mg::GltfAnimation> set;
  for (const mg::Clip& clip : read) {
    auto one = mg::write_glb(clip.skeleton, clip.motion, clip.name);
    if (!one || !mg::write_file_atomic(folder + "/" + clip.name + ".glb", *one)) std::abort();
    set.push_back({clip.name, &clip.motion});
  }
  auto all = mg::write_glb(read.front().skeleton, set, mg::GltfWriteSettings{false});
  if (!all || !mg::write_file_atomic(folder + "/set.glb", *all)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const char* folder = std::getenv("MOTIONGRAPH_FUZZ_GLTF_SEED");
  const char* clips = std::getenv("MOTIONGRAPH_FUZZ_CLIPS");
  if (folder != nullptr && clips != nullptr) {
    write_seeds(folder, clips);
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mg::GltfImportSettings settings;
  settings.base_dir = "/nonexistent-motiongraph-fuzz";
  settings.max_joint_poses = 2e6;  // a fuzzed file sampled within the fuzzer's time and memory
  auto clips = mg::clips_from_gltf(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.glb", settings);
  (void)clips.ok();
  return 0;
}
