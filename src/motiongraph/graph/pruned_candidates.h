// The pruned distance stage (DESIGN.md section 5c): the transition candidates of the exhaustive
// stage (candidates.h) up to a ceiling on D, found without computing the pairs that cannot
// reach it.
//
// The yaw-invariant window embedding (metric/window_embedding.h) bounds D from below; its ball
// search returns every pair whose bound is at most the ceiling (with a relative slack of
// 1e-3 for rounding), and only those pairs get their exact D, along diagonal runs
// (metric/diagonal_runs.h). A pair the search leaves out has D above the ceiling, so it never
// beats a pair at or below it: the local-minimum test of a pair at or below the ceiling reads
// its computed neighbours and treats the others as larger, which is the exhaustive test's
// answer. The minima at or below the ceiling are so the exhaustive stage's, up to float
// rounding: D agrees with the tiles' in all but the last bits (diagonal_runs.h), so a pair
// whose D ties a neighbour's or the ceiling that closely may be decided the other way. The
// exhaustive stage's own minima move as much with its tile size (docs/performance.md: 4 of
// 1 220 on subject 16 at 120 fps, either way).
//
// Not used by `build` yet: slower than the tiles at the automatic threshold's ceiling on this
// project's machines (docs/performance.md, "The pruned stage measured against the tiles").
//
// The histogram holds the exact D of the pairs at or below the ceiling and counts the others in
// its overflow bin (so fraction_below is exact up to the ceiling); the picture's block minima
// are exact where a block has a pair at or below it, +infinity where all its pairs lie above.
// Pairs are visited a band of leaving frames at a time: memory is linear in the frames plus a
// band's candidates.
#pragma once

#include "motiongraph/core/error.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/metric/window_embedding.h"

namespace mg {

struct PrunedSearchSettings {
  WindowEmbeddingSettings embedding;
  int threads = 0;                  // 0: one per core
  long long band_pairs = 1LL << 22; // candidates gathered before a band's D is computed

  Status validate() const;
};

struct PrunedSearchStatistics {
  double embedding_seconds = 0.0;  // the projections
  double search_seconds = 0.0;     // the ball search (its visits excluded)
  double exact_seconds = 0.0;      // D along the runs, minima, histogram and picture
  long long candidate_pairs = 0;   // pairs the bound left: their D was computed
  long long runs = 0;              // diagonal runs they formed (per band)
  long long defined_pairs = 0;     // pairs with a defined D (what the exhaustive stage computes)
};

// The candidates with D <= ceiling (>= 0, D units). CandidateSettings as for find_candidates;
// keep_matrix is refused (the pruned stage never has the whole matrix). `statistics` may be
// null.
Result<CandidateSearch> find_candidates_pruned(const FrameFeatures& features, double ceiling,
                                               const CandidateSettings& settings,
                                               const PrunedSearchSettings& pruned = {},
                                               PrunedSearchStatistics* statistics = nullptr);

}  // namespace mg
