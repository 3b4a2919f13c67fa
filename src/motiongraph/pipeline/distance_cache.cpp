// The distance cache: its key, and its files.
#include "motiongraph/pipeline/distance_cache.h"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>

#include "motiongraph/graph/graph_file.h"
#include "motiongraph/io/file.h"

namespace mg {

namespace fs = std::filesystem;

std::uint64_t distance_cache_key(const MotionDatabase& db, const std::string& settings_json_text) {
  std::string bytes = settings_json_text;
  bytes += fmt::format("fps={};", db.fps);
  for (const DatabaseClip& clip : db.clips) {
    bytes += fmt::format("{}:{}:{};", clip.skeleton, clip.first_frame, clip.frame_count);
    bytes.append(reinterpret_cast<const char*>(clip.motion.local_rotations.data()),
                 clip.motion.local_rotations.size() * sizeof(Quat));
    bytes.append(reinterpret_cast<const char*>(clip.motion.local_translations_m.data()),
                 clip.motion.local_translations_m.size() * sizeof(Vec3));
  }
  for (const Skeleton& skeleton : db.skeletons) {
    for (const JointDef& joint : skeleton.joints()) {
      bytes += fmt::format("{}/{}/{}/{}/{};", joint.name, joint.parent, joint.rest_offset_m.x(),
                           joint.rest_offset_m.y(), joint.rest_offset_m.z());
    }
  }
  return content_key(bytes);
}

Result<std::optional<CandidateSearch>> FileDistanceCache::find(std::uint64_t key) {
  const std::string path = location(key);
  auto bytes = read_text_file(path);
  if (!bytes) return std::optional<CandidateSearch>();
  auto cached = parse_distance_cache(*bytes, path, key);
  if (!cached) return cached.error();
  return std::optional<CandidateSearch>(std::move(*cached));
}

Status FileDistanceCache::store(std::uint64_t key, const CandidateSearch& candidates) {
  if (auto s = create_folders(folder_); !s) return s;
  return write_file_atomic(location(key), serialize_distance_cache(key, candidates));
}

std::string FileDistanceCache::location(std::uint64_t key) const {
  return (fs::path(folder_) / fmt::format("{:016x}.mgcache", key)).string();
}

std::string default_distance_cache_folder() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "motiongraph").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (fs::path(home) / ".cache" / "motiongraph").string();
  return ".motiongraph-cache";
}

}  // namespace mg
