// libFuzzer target for the database manifest reader: the input bytes are taken as the text
// of a TOML manifest and given to mg::parse_manifest (TOML syntax, known keys, value types,
// frame ranges, tag names). A manifest that parses is checked against the rules the parser
// promises (docs/manifest.md), so that a rule it lets through is a finding too.
// Errors are expected results; the fuzzer looks for crashes, hangs, leaks and sanitizer
// reports. Run it with scripts/fuzz.sh.
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "motiongraph/database/manifest.h"

namespace {

void check(bool condition) {
  if (!condition) std::abort();
}

// glTF and FBX files hold animations by name.
bool is_scene_extension(const std::string& ext) {
  return ext == ".glb" || ext == ".gltf" || ext == ".fbx";
}

// The file's extension (from its last dot) in lower case (the reader accepts .AMC as .amc, as
// the loader does).
std::string lower_extension(const std::string& file) {
  const std::size_t dot = file.rfind('.');
  std::string ext = dot == std::string::npos ? std::string() : file.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// The clip formats docs/manifest.md names.
bool is_clip_extension(const std::string& ext) {
  return ext == ".amc" || ext == ".bvh" || is_scene_extension(ext);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto manifest = mg::parse_manifest(text, "fuzz.toml");
  if (!manifest.ok()) return 0;
  check(!manifest->clips.empty());
  for (const mg::ManifestClip& clip : manifest->clips) {
    const std::string ext = lower_extension(clip.file);
    check(is_clip_extension(ext));
    if (clip.animation) check(is_scene_extension(ext));
    if (clip.skeleton) check(ext == ".amc");
    if (clip.bvh_scale) check(ext == ".bvh" && *clip.bvh_scale > 0);
    if (clip.first_frame) check(*clip.first_frame >= 1);
    if (clip.first_frame && clip.last_frame) check(*clip.last_frame >= *clip.first_frame);
    for (const mg::ManifestRange& range : clip.ranges) {
      check(range.first_frame >= 1 && range.last_frame >= range.first_frame && !range.tags.empty());
      for (const auto& tag : range.tags) check(mg::is_valid_tag_name(tag));
    }
    if (clip.tags) {
      for (const auto& tag : *clip.tags) check(mg::is_valid_tag_name(tag));
    }
  }
  return 0;
}
