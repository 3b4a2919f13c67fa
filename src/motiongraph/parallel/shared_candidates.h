// The distance stage's candidates (graph/candidates.h) found by a team of processes
// (process_team.h), optionally checkpointed (tile_checkpoint.h): every process reads the
// checkpoint, takes its share of the work items not in it (tile_share.h, balanced by pairs),
// runs them on its threads as find_candidates() does, in chunks saved to the checkpoint as they
// finish, and hands its part to rank 0, which merges them with the checkpoint's into the search
// of all tiles: the same candidates, histogram and picture as one process finds, for any number
// of processes and any restart.
//
// Fails on every process when any process fails (rank 0 gets the first error, the others
// ErrorKind::kOtherProcess); a process that dies ends the job (process_team.h).
#pragma once

#include <cstdint>
#include <stop_token>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/core/progress.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/parallel/process_team.h"

namespace mg {

struct SharedSearchSettings {
  std::string checkpoint_folder;          // empty: no checkpoint
  long long checkpoint_pairs = 1LL << 31; // frame pairs per chunk saved (about half a minute of 2 cores)
  bool progress_bar = false;              // rank 0's bar over its own tiles
  ProgressLines progress_lines;           // and, given, a line of it every kProgressLineSeconds
  // Asks this process to stop (core/stop.h): its tiles not yet begun are passed over and the
  // search fails with stopped_error() (the team's other processes with ErrorKind::kOtherProcess).
  std::stop_token stop;

  Status validate() const;
};

struct SharedSearch {
  CandidateSearch search;                // rank 0: of all tiles; the other processes: empty
  int processes = 1;
  long long restored_tiles = 0;          // from the checkpoint
  std::vector<double> peak_memory_mb;    // rank 0: each process's peak resident memory, by rank
  std::vector<double> share_seconds;     // rank 0: the seconds each process took for its tiles, by rank
};

// `key` is the build's distance cache key (it ties the checkpoint to the inputs and settings).
// The matrix (settings.keep_matrix) is held by one process without a checkpoint only.
// `only_items` (when not null): the work items to run, TileItems numbers in increasing order
// (the pruned stage's plan, graph/pruned_candidates.h); the others are left out, as
// find_candidates leaves out the items it is not given. The same on every process.
// `only_sides` (with only_items, one per item, or null: both): which of an item's tiles to
// visit, as find_candidates takes them; used by one process without a checkpoint (a team and
// a checkpoint visit both tiles of an item: the pruned stage's result is the same).
Result<SharedSearch> find_candidates_shared(const FrameFeatures& features, const DistanceSettings& distance,
                                            const CandidateSettings& settings, std::uint64_t key, ProcessTeam& team,
                                            const SharedSearchSettings& shared,
                                            const std::vector<long long>* only_items = nullptr,
                                            const std::vector<unsigned char>* only_sides = nullptr);

// This process's peak resident memory so far, in MB (0 where the system does not say).
double peak_memory_mb();

}  // namespace mg
