// The frame distance D(a, b) for all pairs, fast: three float32 BLAS products per tile plus
// sums along the tile's diagonals (DESIGN.md sections 3.2-3.4).
//
// The pair matrix (row a = frame we leave, column b = frame we arrive at) is cut into square
// tiles of settings.tile_frames. For each tile the products xz*xz^T, xz*zx^T and y*y^T of the
// per-frame centred clouds are taken over the tile's rows and columns plus halos (k - 1 frames
// for the window sums, 1 for neighbour tests); the per-frame offsets are added back in double
// (DESIGN.md 3.3), summed along diagonals (running sums for a uniform taper, O(1) per pair;
// O(k) with a taper), and put through the closed form. Undefined pairs (a window leaving its
// clip) are NaN. Tiles are independent and run on settings.threads threads; nothing but one
// tile per thread is ever held. The work comes in items (TileItems): a run may take any subset
// of them (another process, or an earlier run kept in a checkpoint, does the rest).
#pragma once

#include <functional>
#include <span>
#include <stop_token>
#include <utility>
#include <vector>

#include "motiongraph/metric/frame_features.h"

namespace mg {

// A computed tile: the inner region [leave_begin, leave_begin + leave_count) x
// [arrive_begin, arrive_begin + arrive_count) and one frame of halo around it (clipped at the
// matrix edges), row-major in `distance`.
struct DistanceTile {
  int leave_begin = 0, leave_count = 0;    // inner rows
  int arrive_begin = 0, arrive_count = 0;  // inner columns
  int row0 = 0, rows = 0;                  // stored rows: row0 .. row0 + rows - 1 (with halo)
  int col0 = 0, cols = 0;                  // stored columns
  std::span<const float> distance;         // rows x cols

  float at(int a, int b) const { return distance[static_cast<size_t>(a - row0) * cols + (b - col0)]; }
};

// The distance stage's work items: the pairs of tile rows I <= J, numbered row by row (I = 0:
// J = 0 .. per_side - 1, then I = 1, ...). Item (I, J) gives tile (I, J) and, when I != J, tile
// (J, I) from the same products (G1 and G3 are symmetric, G2 antisymmetric).
struct TileItems {
  int frames = 0, tile = 0, per_side = 0;

  long long count() const { return static_cast<long long>(per_side) * (per_side + 1) / 2; }
  std::pair<int, int> tiles_of(long long item) const;  // (I, J)
  long long tile_count(long long item) const;          // 1 or 2
  long long pairs(long long item) const;               // frame pairs of its tiles
  // The pairs of the tiles `sides` selects (see for_each_distance_tile), and their number.
  long long pairs(long long item, unsigned char sides) const;
  long long tile_count(long long item, unsigned char sides) const;
};

TileItems tile_items(const FrameFeatures& features, const DistanceSettings& settings);

// The work items that hold a flagged tile (`flags`: per_side x per_side, row-major, nonzero
// where flagged), increasing, and per item which of its tiles are flagged (the `sides` of
// for_each_distance_tile).
struct TileSelection {
  std::vector<long long> items;
  std::vector<unsigned char> sides;
};
TileSelection items_of_flagged_tiles(const TileItems& grid, std::span<const char> flags);

// Called once per tile, from worker threads (the callback must be thread-safe). The tile's
// memory is reused after the callback returns.
using TileVisitor = std::function<void(const DistanceTile&)>;

struct TileRunStatistics {
  double seconds = 0.0;
  long long tiles = 0;
  long long pairs = 0;
  bool stopped = false;  // a stop was asked for: some tiles were not visited
};

// Progress is reported as tiles done through on_tile_done (may be empty). `items` are the work
// items to run (TileItems numbers, each at most once); empty: all of them. `sides` (empty, or
// one per item): which of an item's tiles to visit, 1 for (I, J), 2 for (J, I), 3 for both (an
// item of one tile, I = J, has only the first); the products are the item's either way, so a
// tile's values do not depend on whether its mirror is visited. The statistics count the tiles
// and pairs visited. Once `stop` asks (core/stop.h), the items not yet begun are passed over
// and the statistics say `stopped`.
TileRunStatistics for_each_distance_tile(const FrameFeatures& features, const DistanceSettings& settings,
                                         const TileVisitor& visitor,
                                         const std::function<void(long long done, long long total)>& on_tile_done = {},
                                         std::span<const long long> items = {},
                                         std::span<const unsigned char> sides = {}, std::stop_token stop = {});

// Times the three plain BLAS products the distance stage needs, over a whole N x N matrix in
// tiles of the same size and on the same threads, without the diagonal sums: the ceiling
// that `motiongraph bench distance` measures the stage against.
double time_plain_products(const FrameFeatures& features, const DistanceSettings& settings);

}  // namespace mg
