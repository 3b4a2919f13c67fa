#include "motiongraph/parallel/tile_checkpoint.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "motiongraph/io/file.h"

namespace mg {

namespace fs = std::filesystem;

Result<std::vector<CandidatePart>> TileCheckpoint::load() const {
  std::vector<CandidatePart> parts;
  std::error_code ec;
  if (!fs::exists(folder_, ec)) return parts;
  if (!fs::is_directory(folder_, ec)) return Error{folder_, 0, "--checkpoint: not a folder"};
  std::vector<std::string> paths;
  for (const auto& entry : fs::directory_iterator(folder_, ec)) {
    if (entry.path().extension() == ".mgtiles" && entry.path().filename().string()[0] != '.') {
      paths.push_back(entry.path().string());
    }
  }
  if (ec) return Error{folder_, 0, fmt::format("--checkpoint: cannot list the folder: {}", ec.message())};
  std::sort(paths.begin(), paths.end());
  std::set<long long> seen;
  for (const std::string& path : paths) {
    auto bytes = read_text_file(path);
    if (!bytes) return bytes.error();
    auto part = parse_candidate_part(*bytes, path);
    if (!part) return part.error();
    if (part->key != key_) {
      return Error{path, 0,
                   "a checkpoint of another build (other inputs or distance settings): give an empty --checkpoint "
                   "folder, or the one this build's earlier run used"};
    }
    if (part->frames != items_.frames || part->tile_frames != items_.tile) {
      return Error{path, 0,
                   fmt::format("a checkpoint made with --tile {} on {} frames: run again with --tile {}",
                               part->tile_frames, part->frames, part->tile_frames)};
    }
    for (long long item : part->items) {
      if (item < 0 || item >= items_.count() || !seen.insert(item).second) {
        return Error{path, 0, fmt::format("checkpoint chunk with tile item {} out of range or in another chunk too", item)};
      }
    }
    parts.push_back(std::move(*part));
  }
  return parts;
}

Status TileCheckpoint::save(CandidatePart part) const {
  if (part.items.empty()) return Ok{};
  part.key = key_;
  part.frames = items_.frames;
  part.tile_frames = items_.tile;
  if (auto s = create_folders(folder_); !s) return s;
  const fs::path path = fs::path(folder_) / fmt::format("{:016x}-{:010}.mgtiles", key_, part.items.front());
  return write_file_atomic(path.string(), serialize_candidate_part(part));
}

}  // namespace mg
