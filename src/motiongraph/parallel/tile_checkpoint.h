// A build's checkpoint (`motiongraph build --checkpoint DIR`): the distance stage's finished
// work items, saved as they finish, so that a job started again (after a crash, a kill, the end
// of a cluster allocation) skips them and makes the same graph. The folder holds one file per
// chunk of work items (graph/graph_file.h CandidatePart, written to a temporary name and
// renamed, so a killed process leaves no torn chunk): <key>-<first item>.mgtiles. Chunks carry
// the build's distance cache key and the tiling, so the folder of another build (other inputs,
// settings, rate or --tile) is refused, not mixed in. Any number of processes may write chunks
// (their items are disjoint); every process reads the folder before any of them writes to it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/metric/distance_tiles.h"

namespace mg {

class TileCheckpoint {
 public:
  TileCheckpoint(std::string folder, std::uint64_t key, const TileItems& items)
      : folder_(std::move(folder)), key_(key), items_(items) {}

  // The chunks in the folder (none when it does not exist yet). Fails on a chunk of another
  // build, a damaged chunk, or an item in two chunks.
  Result<std::vector<CandidatePart>> load() const;
  // Writes `part` (its key and tiling set here); creates the folder when missing.
  Status save(CandidatePart part) const;

  const std::string& folder() const { return folder_; }

 private:
  std::string folder_;
  std::uint64_t key_;
  TileItems items_;
};

}  // namespace mg
