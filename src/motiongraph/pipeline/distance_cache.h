// Where build_graph() keeps the distance stage's result (the transition candidates and the
// histogram, no matrix) between runs, by a key of the inputs and the distance settings:
// another threshold, bridge or spacing setting on the same inputs then needs no distance
// stage. DistanceCache is the interface build_graph() takes (nullptr: no cache);
// FileDistanceCache is the one the CLI uses, one checksummed file per key
// (graph/graph_file.h's .mgcache framing) in a folder, written atomically.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/candidates.h"

namespace mg {

// The key of a distance stage's result: its settings' JSON text (DistanceStageSettings::to_json)
// and the resampled motion itself (rate, clips, rotations, translations and skeletons), so any
// change of input files, frame ranges, rate or reading options changes it.
std::uint64_t distance_cache_key(const MotionDatabase& db, const std::string& settings_json_text);

class DistanceCache {
 public:
  virtual ~DistanceCache() = default;

  // The candidates stored under `key`; nullopt when there are none. An error when an entry is
  // there but cannot be used (damaged, or for another key): the caller computes again.
  virtual Result<std::optional<CandidateSearch>> find(std::uint64_t key) = 0;
  // Stores the candidates under `key` (their matrix, if any, is not stored).
  virtual Status store(std::uint64_t key, const CandidateSearch& candidates) = 0;
  // Where the entry for `key` lives, for log lines ("from the cache ...").
  virtual std::string location(std::uint64_t key) const = 0;
};

class FileDistanceCache final : public DistanceCache {
 public:
  explicit FileDistanceCache(std::string folder) : folder_(std::move(folder)) {}

  // A file that cannot be read counts as no entry; one that cannot be parsed is an error.
  Result<std::optional<CandidateSearch>> find(std::uint64_t key) override;
  // Creates the folder when missing.
  Status store(std::uint64_t key, const CandidateSearch& candidates) override;
  // FOLDER/<key as 16 hex digits>.mgcache
  std::string location(std::uint64_t key) const override;

 private:
  std::string folder_;
};

// $XDG_CACHE_HOME/motiongraph, else $HOME/.cache/motiongraph, else .motiongraph-cache.
std::string default_distance_cache_folder();

}  // namespace mg
