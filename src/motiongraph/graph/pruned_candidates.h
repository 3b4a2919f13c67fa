// The pruned distance stage (DESIGN.md section 5c): the transition candidates of the exhaustive
// stage (candidates.h) up to a ceiling on D, found without computing the tiles that cannot
// reach it.
//
// The window embedding (metric/window_embedding.h) bounds D from below; a tile of the pair
// matrix is computed only when one of its pairs has a bound at most the ceiling
// (metric/bounded_tiles.h, with a relative slack of 1e-3 for the bound's float rounding). The
// tiles computed are the exhaustive stage's own, with their halo: the same products, sums and
// local-minimum test, so every value computed is the exhaustive stage's bit for bit at the
// same tile size. A tile left out holds only pairs whose D is above the ceiling, and a pair at
// or below the ceiling lies in a computed tile whose halo holds its 8 neighbours. The minima
// at or below the ceiling are so exactly those of the exhaustive stage run with the same tile
// side (find_candidates), whatever the threads. (Between two tile sides the exhaustive stage's
// own minima differ in ties within float rounding: docs/performance.md.)
//
// The histogram holds the D of every pair of the computed tiles up to the ceiling's bin and
// counts all other pairs in its overflow bin, so fraction_below is exact up to the ceiling;
// the picture's block minima are exact where at or below the ceiling, +infinity where a
// block's defined pairs all lie above it, NaN where it has none. Minima above the ceiling are
// dropped (the tiles left out would hold more). Memory is one tile per thread, as the
// exhaustive stage's, plus the embedding (about 300 bytes a window) and a byte per tile for
// the search's flags (N^2 / T^2: 16 MB for 262 144 frames in tiles of 64, 1 MB in tiles of
// 256).
//
// Bridges read minima above any ceiling: on_demand_candidates.h finds those they need. Per-tag
// thresholds count every candidate of a tag and are refused on this stage's candidates
// (transition_selection.h), so `build` runs this stage only where they do not apply
// (BuildSettings::pruned_stage): docs/performance.md ("Bridges on demand").
#pragma once

#include <optional>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/metric/window_embedding.h"

namespace mg {

struct PrunedSearchSettings {
  WindowEmbeddingSettings embedding;
  // The tiles' side in frames; 0: chosen from the window k (tile_for).
  int tile_frames = 0;
  int threads = 0;  // 0: one per core

  Status validate() const;
  // The side used: tile_frames, or for 0 the measured best (docs/performance.md): a multiple
  // of 64 frames near 6.4 windows, at least 64 (64 at 30 fps, 256 at 120 fps).
  int tile_for(int window) const;
};

struct PrunedSearchStatistics {
  double embedding_seconds = 0.0;  // the projections
  double search_seconds = 0.0;     // finding the tiles the bound cannot rule out
  double exact_seconds = 0.0;      // those tiles: D, minima, histogram and picture
  int tile_frames = 0;             // the tiles' side
  long long tiles = 0;             // tiles of the pair matrix
  long long tiles_computed = 0;    // of them, run (the flagged ones)
  long long computed_pairs = 0;    // pairs in the computed tiles (their D was computed)
  long long defined_pairs = 0;     // pairs with a defined D (what the exhaustive stage computes)
};

// The stage in two halves, so that a team of processes (parallel/shared_candidates.h) can share
// the tiles: the plan (the embedding and the tile search; the same on every process, given the
// same features), the exhaustive stage's search of the plan's items with the plan's
// `distance`, then finish_pruned_search on the merged result.
struct PrunedPlan {
  DistanceSettings distance;     // the tile side and threads the items are numbered for
  std::vector<long long> items;  // TileItems numbers to run, increasing; may be empty
  // Per item, the tiles flagged (for_each_distance_tile's sides): a team that runs both tiles
  // of each item gets the same result, with more pairs computed above the ceiling.
  std::vector<unsigned char> sides;
  // The window embedding the bound used, and the tiles the items visit (a byte per tile,
  // row-major, of tile_frames' grid): for the searches that follow (OnDemandCandidates). Both
  // empty when no pair is defined.
  std::optional<WindowEmbedding> embedding;
  std::vector<char> tiles;
};

// `statistics` may be null; it gets the plan's figures (the exact_seconds and computed_pairs
// are find_candidates_pruned's to fill).
Result<PrunedPlan> plan_pruned_search(const FrameFeatures& features, double ceiling,
                                      const PrunedSearchSettings& pruned = {},
                                      PrunedSearchStatistics* statistics = nullptr);

// Turns the search of the plan's items into the pruned stage's result: the minima above the
// ceiling dropped, the histogram's pairs above the ceiling's bin and those of the tiles not run
// counted in its overflow bin, pixels above the ceiling or not computed +infinity (NaN where
// undefined), `ceiling` set.
void finish_pruned_search(const FrameFeatures& features, double ceiling, CandidateSearch& search);

// The candidates with D <= ceiling (>= 0, D units). CandidateSettings as for find_candidates;
// keep_matrix is refused (the pruned stage never has the whole matrix). `statistics` may be
// null.
Result<CandidateSearch> find_candidates_pruned(const FrameFeatures& features, double ceiling,
                                               const CandidateSettings& settings,
                                               const PrunedSearchSettings& pruned = {},
                                               PrunedSearchStatistics* statistics = nullptr);

}  // namespace mg
