// Which tiles of the pair matrix can hold a pair below a ceiling on D: the window embedding's
// lower bound (window_embedding.h, DESIGN.md section 5c) applied a tile at a time, so that the
// pruned distance stage (graph/pruned_candidates.h) runs the exhaustive stage's own tiles
// (distance_tiles.h) on those and skips the others.
//
// Tile (I, J) holds the pairs (a, b) with a in [I T, I T + T) and b in [J T, J T + T), T the
// tile side. It is flagged when one of them, a able to leave and b able to arrive, has an
// embedded bound (WindowEmbedding::bound of windows a and b - k + 1) at most the ceiling;
// D >= that bound, so an unflagged tile's pairs all have D above the ceiling. The search is
// exact (a tile is flagged only once such a pair is found): balls of consecutive windows (the
// motion is smooth, so they are small) are tested by the triangle inequality of the bound's
// square root, the tile's as a whole first, then middle balls of 8 small ones, then small ones
// of a fifth of a window (at least 2 windows), one ball against 8 in one vectorised pass, then
// the pairs of the small balls that may meet, stopping at the first pair found.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/metric/window_embedding.h"

namespace mg {

struct BoundedTiles {
  int tile = 0;              // T, frames per side
  int per_side = 0;          // tiles per side
  std::vector<char> flags;   // per_side x per_side, row-major: 1 where the tile may hold a pair
  long long pairs = 0;       // pairs whose bound was summed (partly, with an early exit)

  bool flagged(int i, int j) const { return flags[static_cast<size_t>(i) * per_side + j] != 0; }
  long long count() const;   // flagged tiles
};

// On `threads` threads (0: one per core). `ceiling` in D units (>= 0); `tile` >= 1. With `only`
// (a byte per tile, row-major), the tiles where it is 0 are not searched and stay unflagged; each
// searched tile's flag is the one the whole search gives it.
BoundedTiles find_bounded_tiles(const FrameFeatures& features, const WindowEmbedding& embedding, int tile,
                                double ceiling, int threads = 0, std::span<const char> only = {});

}  // namespace mg
