// Transition candidates (Kovar et al. 2002, section 3.2): the local minima of the distance
// matrix, found while its tiles stream by (DESIGN.md 3.4). A pair (a, b) is a candidate when
// D(a, b) is finite and no defined neighbour among its 8 is smaller (ties go to the first in
// row-major order), across tile borders (tiles carry a one-frame halo). Pairs of a clip simply
// continuing (same clip, |b - (a + k - 1)| <= continuation radius) are not candidates: their
// D is ~0 trivially.
//
// The same pass fills the histogram of all finite D (for quantile thresholds), the distance
// picture (block minima, for the PNG) and, when asked and small enough, the full matrix.
// Everything a threshold needs is here, so re-thresholding never redoes this stage.
//
// A search may cover some of the tiles only (TileItems numbers, metric/distance_tiles.h): such
// parts, from other processes or a checkpoint, merge into the search of all tiles, the same
// whichever way the tiles were shared.
#pragma once

#include <functional>
#include <span>
#include <stop_token>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/transition.h"
#include "motiongraph/metric/distance_histogram.h"
#include "motiongraph/metric/distance_tiles.h"

namespace mg {

struct CandidateSettings {
  int continuation_radius = -1;  // frames; -1 = the window length k
  bool keep_matrix = false;      // hold the N x N matrix (for --export-matrix)
  int max_matrix_frames = 16384; // refuse to hold it beyond this (N^2 floats)
  int picture_side = 1024;       // the block-minimum picture is at most this many pixels wide

  Status validate() const;
};

struct CandidateSearch {
  int window = 0;
  int tile_frames = 0;             // the tiles' side (ties between local minima depend on it)
  int continuation_radius = 0;
  std::vector<Transition> minima;  // sorted by (from_frame, to_frame); no alignment yet
  DistanceHistogram histogram;
  std::vector<float> matrix;       // N x N when kept (NaN undefined), else empty
  std::vector<float> picture;      // picture_side_used^2 block minima (NaN where undefined)
  int picture_side = 0;            // pixels per side
  int picture_block = 1;           // frames per pixel
  TileRunStatistics tiles;         // the pruned stage: seconds, tiles 0, pairs whose D it computed
  // < 0: everything above is complete (the exhaustive tiles). >= 0: the pruned stage's
  // (pruned_candidates.h): minima, histogram and picture are exact up to this D only. The
  // histogram counts the pairs above it in its overflow bin; the picture's pixels whose pairs
  // all lie above it are +infinity.
  double ceiling = -1.0;
};

// `items`: the work items to search (empty: all); the others' pixels stay NaN. `sides`: which
// of each item's tiles (for_each_distance_tile). Fails with stopped_error() (core/stop.h) when
// `stop` asks before every tile is done.
Result<CandidateSearch> find_candidates(const FrameFeatures& features, const DistanceSettings& distance,
                                        const CandidateSettings& settings,
                                        const std::function<void(long long, long long)>& on_tile_done = {},
                                        std::span<const long long> items = {},
                                        std::span<const unsigned char> sides = {}, std::stop_token stop = {});

// A search of no tiles yet: nothing found, the picture all NaN (what merge_candidates starts
// from). Fails as find_candidates does on invalid settings or a matrix too large.
Result<CandidateSearch> empty_candidate_search(const FrameFeatures& features, const CandidateSettings& settings);

// Adds a part (the search of other tiles, with the same window, radius and picture) to `into`:
// minima merged in order, histograms added, pictures by pixel minimum, tile and pair counts
// added (seconds: the larger). Fails, changing nothing, when the part does not fit.
Status merge_candidates(CandidateSearch& into, const CandidateSearch& part);

}  // namespace mg
