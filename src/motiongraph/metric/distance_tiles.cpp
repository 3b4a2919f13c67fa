#include "motiongraph/metric/distance_tiles.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <memory>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include <cblas.h>

#include "motiongraph/core/parallel_for.h"
#include "motiongraph/core/vector_clones.h"
#include "motiongraph/metric/closed_form.h"

namespace mg {

namespace {

int worker_count(const DistanceSettings& settings) { return worker_threads(settings.threads); }

// The BLAS products for rows [r0, r0 + rows) against columns [c0, c0 + cols), row-major.
struct Products {
  std::vector<float> g1, g2, g3;
  int row0 = 0, rows = 0, col0 = 0, cols = 0;  // frames covered: [row0, row0 + rows) x [col0, col0 + cols)

  void compute(const FrameFeatures& f, int r0, int row_count, int c0, int col_count) {
    row0 = r0;
    rows = row_count;
    col0 = c0;
    cols = col_count;
    const int p = f.points;
    g1.resize(static_cast<size_t>(rows) * cols);
    g2.resize(g1.size());
    g3.resize(g1.size());
    const float* xz_rows = f.xz.data() + static_cast<size_t>(r0) * 2 * p;
    const float* xz_cols = f.xz.data() + static_cast<size_t>(c0) * 2 * p;
    const float* zx_cols = f.zx.data() + static_cast<size_t>(c0) * 2 * p;
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, rows, cols, 2 * p, 1.0f, xz_rows, 2 * p, xz_cols, 2 * p,
                0.0f, g1.data(), cols);
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, rows, cols, 2 * p, 1.0f, xz_rows, 2 * p, zx_cols, 2 * p,
                0.0f, g2.data(), cols);
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, rows, cols, p, 1.0f, f.y.data() + static_cast<size_t>(r0) * p,
                p, f.y.data() + static_cast<size_t>(c0) * p, p, 0.0f, g3.data(), cols);
  }

  // The products of the columns' frames against the rows' frames, from these: G1 and G3 are
  // symmetric, G2 antisymmetric (DESIGN.md 3.2), so no new BLAS call is needed.
  void transpose_from(const Products& other) {
    row0 = other.col0;
    rows = other.cols;
    col0 = other.row0;
    cols = other.rows;
    const size_t size = static_cast<size_t>(rows) * cols;
    g1.resize(size);
    g2.resize(size);
    g3.resize(size);
    constexpr int kBlock = 32;  // cache-friendly transposition
    for (int i0 = 0; i0 < other.rows; i0 += kBlock) {
      for (int j0 = 0; j0 < other.cols; j0 += kBlock) {
        for (int i = i0; i < std::min(other.rows, i0 + kBlock); ++i) {
          for (int j = j0; j < std::min(other.cols, j0 + kBlock); ++j) {
            const size_t from = static_cast<size_t>(i) * other.cols + j;
            const size_t to = static_cast<size_t>(j) * cols + i;
            g1[to] = other.g1[from];
            g2[to] = -other.g2[from];
            g3[to] = other.g3[from];
          }
        }
      }
    }
  }
};

// The per-pair loops below are free functions (restrict arguments let them vectorise) and
// carry MG_VECTOR_CLONES (an AVX2 version beside the baseline one).
// One row of E (DESIGN.md 3.3) plus p (the previous row's diagonal sums, or zeros).
MG_VECTOR_CLONES void accumulate_kernel(int cols, Offsets o, const float* __restrict g1, const float* __restrict g2,
                       const float* __restrict g3, const double* __restrict sx, const double* __restrict sz,
                       const double* __restrict nvx, const double* __restrict nvz, const double* __restrict p1,
                       const double* __restrict p2, const double* __restrict p3, double* __restrict e1,
                       double* __restrict e2, double* __restrict e3) {
  for (int j = 0; j < cols; ++j) {
    e1[j] = uncentred_e1(o, g1[j], sx[j], sz[j], nvx[j], nvz[j]) + p1[j];
    e2[j] = uncentred_e2(o, g2[j], sx[j], sz[j], nvx[j], nvz[j]) + p2[j];
    e3[j] = g3[j] + p3[j];
  }
}

// D for `count` consecutive arrival frames from the diagonal sums at the windows' ends and
// before their starts (uniform taper u). NaN where the arrival window is undefined (mask).
MG_VECTOR_CLONES void window_distance_kernel(int count, double u, const RowTerms row, const double* __restrict end1,
                            const double* __restrict end2, const double* __restrict end3,
                            const double* __restrict start1, const double* __restrict start2,
                            const double* __restrict start3, const double* __restrict x2,
                            const double* __restrict z2, const double* __restrict square2,
                            const float* __restrict mask, float* __restrict out) {
  for (int m = 0; m < count; ++m) {
    out[m] = closed_form(u * (end1[m] - start1[m]), u * (end2[m] - start2[m]), u * (end3[m] - start3[m]), row, x2[m],
                         z2[m], square2[m]) +
             mask[m];
  }
}

class TileWorker {
 public:
  explicit TileWorker(const FrameFeatures& f) : f_(f), uniform_(uniform_taper(f.taper)) {
    // Per-frame terms of the closed form that depend on one window only, computed once.
    const int n = f.frames;
    const double v = f.point_weight_sum;
    const double inv_w = 1.0 / f.window_weight;
    moment_vx_.resize(n);
    moment_vz_.resize(n);
    centred_square_.resize(n);
    arrive_mask_.resize(n);
    for (int i = 0; i < n; ++i) {
      moment_vx_[i] = f.moment_x[i] + v * f.root_x[i];
      moment_vz_[i] = f.moment_z[i] + v * f.root_z[i];
      const double x = f.window_x[i], z = f.window_z[i];
      centred_square_[i] = centred_window_square(f.window_square[i], x, z, inv_w);
      arrive_mask_[i] = f.can_arrive[i] ? 0.0f : std::numeric_limits<float>::quiet_NaN();
    }
  }

  // The distances of the tile from products that cover every frame its windows touch.
  DistanceTile run(int a0, int a_count, int b0, int b_count, const Products& products) {
    const int n = f_.frames;
    const int k = f_.window;
    DistanceTile tile;
    tile.leave_begin = a0;
    tile.leave_count = a_count;
    tile.arrive_begin = b0;
    tile.arrive_count = b_count;
    tile.row0 = std::max(0, a0 - 1);
    tile.rows = std::min(n, a0 + a_count + 1) - tile.row0;
    tile.col0 = std::max(0, b0 - 1);
    tile.cols = std::min(n, b0 + b_count + 1) - tile.col0;
    // Frames the windows of these pairs touch: rows a..a+k-1, columns b-k+1..b.
    const int r0 = tile.row0;
    const int rows = std::min(n, tile.row0 + tile.rows + k - 1) - r0;
    const int c0 = std::max(0, tile.col0 - k + 1);
    const int cols = tile.col0 + tile.cols - c0;
    assert(products.row0 <= r0 && r0 + rows <= products.row0 + products.rows);
    assert(products.col0 <= c0 && c0 + cols <= products.col0 + products.cols);
    products_ = &products;
    distance_.resize(static_cast<size_t>(tile.rows) * tile.cols);
    // Rows of E (or of its running diagonal sums) live in a ring of k + 1 rows: the pairs of
    // row a need block rows a - r0 .. a - r0 + k - 1 only. Each ring row starts with a zero
    // (block column -1), and row -1 is all zeros, so diagonal sums need no edge tests.
    const int ring = k + 1;
    stride_ = cols + 1;
    for (auto* buffer : {&e1_, &e2_, &e3_}) buffer->resize(static_cast<size_t>(ring) * stride_);
    zeros_.assign(stride_, 0.0);
    for (int i = 0; i < rows; ++i) {
      accumulate_row(i, r0, c0, cols, ring);
      const int a = r0 + i - (k - 1);  // the leaving frame whose window ends on this row
      if (a >= tile.row0 && a < tile.row0 + tile.rows) distances_for_row(tile, a, r0, c0, ring);
    }
    // Rows whose window would leave the matrix (a > n - k) never get there: undefined.
    for (int a = std::max(tile.row0, r0 + rows - (k - 1)); a < tile.row0 + tile.rows; ++a) {
      std::fill_n(distance_.data() + static_cast<size_t>(a - tile.row0) * tile.cols, tile.cols,
                  std::numeric_limits<float>::quiet_NaN());
    }
    tile.distance = distance_;
    return tile;
  }

 private:
  double* ring_row(std::vector<double>& buffer, int i, int ring) {
    return buffer.data() + static_cast<size_t>(i % ring) * stride_;
  }
  const double* ring_row_or_zeros(std::vector<double>& buffer, int i, int ring) {
    return i < 0 ? zeros_.data() : ring_row(buffer, i, ring);
  }

  // E = uncentred cross sums per frame pair, in double: the float products of the centred
  // clouds plus the reference offsets, added back exactly (DESIGN.md 3.3). For a uniform
  // taper they are summed along diagonals as they go (cum(i, j) = E(i, j) + cum(i-1, j-1)),
  // in the same pass. Block column j is stored at j + 1.
  void accumulate_row(int i, int r0, int c0, int cols, int ring) {
    const int fr = r0 + i;
    const double rx = f_.root_x[fr], rz = f_.root_z[fr], mx = f_.moment_x[fr], mz = f_.moment_z[fr];
    const size_t at = static_cast<size_t>(r0 + i - products_->row0) * products_->cols + (c0 - products_->col0);
    const float* g1 = products_->g1.data() + at;
    const float* g2 = products_->g2.data() + at;
    const float* g3 = products_->g3.data() + at;
    double* e1 = ring_row(e1_, i, ring) + 1;
    double* e2 = ring_row(e2_, i, ring) + 1;
    double* e3 = ring_row(e3_, i, ring) + 1;
    e1[-1] = e2[-1] = e3[-1] = 0.0;
    // With the previous row's sums shifted by one column: p[j] = cum(i - 1, j - 1).
    const bool running = uniform_;
    accumulate_kernel(cols, Offsets{rx, rz, mx, mz}, g1, g2, g3, f_.root_x.data() + c0, f_.root_z.data() + c0,
                      moment_vx_.data() + c0, moment_vz_.data() + c0,
                      running ? ring_row_or_zeros(e1_, i - 1, ring) : zeros_.data(),
                      running ? ring_row_or_zeros(e2_, i - 1, ring) : zeros_.data(),
                      running ? ring_row_or_zeros(e3_, i - 1, ring) : zeros_.data(), e1, e2, e3);
  }

  // D(a, b) for every column b of the tile, once block row a - r0 + k - 1 is accumulated.
  void distances_for_row(const DistanceTile& tile, int a, int r0, int c0, int ring) {
    const int k = f_.window;
    const int i0 = a - r0;
    const int i1 = i0 + k - 1;
    float* out = distance_.data() + static_cast<size_t>(a - tile.row0) * tile.cols;
    // Arrival windows must start inside the matrix: b >= k - 1.
    const int b_begin = std::max(tile.col0, k - 1);
    const int count = tile.col0 + tile.cols - b_begin;
    std::fill(out, out + (b_begin - tile.col0), std::numeric_limits<float>::quiet_NaN());
    out += b_begin - tile.col0;
    if (!f_.can_leave[a]) {
      std::fill(out, out + count, std::numeric_limits<float>::quiet_NaN());
      return;
    }
    const double inv_w = 1.0 / f_.window_weight;
    const double x = f_.window_x[a], z = f_.window_z[a];
    const double row_square = centred_square_[a];
    const int first = b_begin - k + 1;  // the first arrival window's first frame
    const double* x2 = f_.window_x.data() + first;
    const double* z2 = f_.window_z.data() + first;
    const double* square2 = centred_square_.data() + first;
    const float* mask = arrive_mask_.data() + b_begin;
    const RowTerms row{x, z, row_square, inv_w};
    if (uniform_) {
      // Window sum = cum(i1, j1) - cum(i0 - 1, j0 - 1), block columns j1 = b - c0 and
      // j0 - 1 = b - k - c0, stored one further on.
      const int end_at = b_begin - c0 + 1, start_at = first - c0;
      const double* end1 = ring_row(e1_, i1, ring);
      const double* end2 = ring_row(e2_, i1, ring);
      const double* end3 = ring_row(e3_, i1, ring);
      const double* start1 = ring_row_or_zeros(e1_, i0 - 1, ring);
      const double* start2 = ring_row_or_zeros(e2_, i0 - 1, ring);
      const double* start3 = ring_row_or_zeros(e3_, i0 - 1, ring);
      window_distance_kernel(count, f_.taper[0], row, end1 + end_at, end2 + end_at, end3 + end_at, start1 + start_at,
                             start2 + start_at, start3 + start_at, x2, z2, square2, mask, out);
    } else {
      for (int m = 0; m < count; ++m) {
        const int j0 = first + m - c0;  // block column of the arrival window's first frame
        double c1 = 0.0, c2 = 0.0, c3 = 0.0;
        for (int t = 0; t < k; ++t) {
          const size_t at = static_cast<size_t>((i0 + t) % ring) * stride_ + (j0 + t + 1);
          c1 += f_.taper[t] * e1_[at];
          c2 += f_.taper[t] * e2_[at];
          c3 += f_.taper[t] * e3_[at];
        }
        out[m] = closed_form(c1, c2, c3, row, x2[m], z2[m], square2[m]) + mask[m];
      }
    }
  }

  const FrameFeatures& f_;
  const bool uniform_;
  std::vector<double> moment_vx_, moment_vz_, centred_square_;
  std::vector<float> arrive_mask_;  // 0 where a window can arrive, NaN elsewhere
  const Products* products_ = nullptr;
  int stride_ = 0;
  std::vector<double> e1_, e2_, e3_, zeros_;
  std::vector<float> distance_;
};

template <class Work>
void run_items(long long items, int workers, const Work& work) {
  // Work is spread over our threads; BLAS itself runs single-threaded, always: OpenBLAS rounds
  // differently on more threads, and D must not depend on how many threads or processes (or
  // tiles per thread) there are, so that every run makes the same graph.
  const int blas_threads = openblas_get_num_threads();
  openblas_set_num_threads(1);
  parallel_for(items, workers, 1, work);
  openblas_set_num_threads(blas_threads);
}

}  // namespace

std::pair<int, int> TileItems::tiles_of(long long item) const {
  // Row I starts at item I * per_side - I * (I - 1) / 2: the last row starting at or before it.
  const long long side = per_side;
  auto row_start = [side](long long i) { return i * side - i * (i - 1) / 2; };
  long long low = 0, high = side - 1;
  while (low < high) {
    const long long mid = (low + high + 1) / 2;
    if (row_start(mid) <= item) {
      low = mid;
    } else {
      high = mid - 1;
    }
  }
  return {static_cast<int>(low), static_cast<int>(low + item - row_start(low))};
}

long long TileItems::tile_count(long long item) const { return tile_count(item, 3); }

long long TileItems::pairs(long long item) const { return pairs(item, 3); }

long long TileItems::tile_count(long long item, unsigned char sides) const {
  const auto [i, j] = tiles_of(item);
  const int first = (sides & 1) != 0 ? 1 : 0, mirror = (sides & 2) != 0 ? 1 : 0;
  return i == j ? first : first + mirror;
}

long long TileItems::pairs(long long item, unsigned char sides) const {
  const auto [i, j] = tiles_of(item);
  const long long rows = std::min(tile, frames - i * tile), cols = std::min(tile, frames - j * tile);
  return rows * cols * tile_count(item, sides);
}

TileItems tile_items(const FrameFeatures& f, const DistanceSettings& settings) {
  TileItems grid;
  grid.frames = f.frames;
  grid.tile = settings.tile_frames;
  grid.per_side = (f.frames + grid.tile - 1) / grid.tile;
  return grid;
}

TileSelection items_of_flagged_tiles(const TileItems& grid, std::span<const char> flags) {
  TileSelection out;
  const auto flagged = [&](int i, int j) { return flags[static_cast<size_t>(i) * grid.per_side + j] != 0; };
  for (long long item = 0; item < grid.count(); ++item) {
    const auto [i, j] = grid.tiles_of(item);
    const auto sides = static_cast<unsigned char>((flagged(i, j) ? 1 : 0) | (i != j && flagged(j, i) ? 2 : 0));
    if (sides == 0) continue;
    out.items.push_back(item);
    out.sides.push_back(sides);
  }
  return out;
}

TileRunStatistics for_each_distance_tile(const FrameFeatures& features, const DistanceSettings& settings,
                                         const TileVisitor& visitor,
                                         const std::function<void(long long, long long)>& on_tile_done,
                                         std::span<const long long> items, std::span<const unsigned char> sides,
                                         std::stop_token stop) {
  const auto start = std::chrono::steady_clock::now();
  const TileItems grid = tile_items(features, settings);
  const int n = grid.frames;
  const int k = features.window;
  const long long item_count = items.empty() ? grid.count() : static_cast<long long>(items.size());
  auto item_at = [&](long long i) { return items.empty() ? i : items[static_cast<size_t>(i)]; };
  auto sides_at = [&](long long i) -> unsigned char { return sides.empty() ? 3 : sides[static_cast<size_t>(i)]; };
  TileRunStatistics stats;
  for (long long i = 0; i < item_count; ++i) {
    stats.tiles += grid.tile_count(item_at(i), sides_at(i));
    stats.pairs += grid.pairs(item_at(i), sides_at(i));
  }
  const int workers = static_cast<int>(std::min<long long>(worker_count(settings), std::max(1LL, item_count)));
  struct Scratch {
    explicit Scratch(const FrameFeatures& f) : worker(f) {}
    TileWorker worker;
    Products forward, backward;
  };
  std::vector<std::unique_ptr<Scratch>> scratch;
  for (int w = 0; w < workers; ++w) scratch.push_back(std::make_unique<Scratch>(features));
  std::atomic<long long> done{0};
  std::atomic<bool> stopped{false};
  run_items(item_count, workers, [&](int w, long long i) {
    if (stop.stop_requested()) {
      stopped.store(true, std::memory_order_relaxed);
      return;
    }
    const auto [ti, tj] = grid.tiles_of(item_at(i));
    Scratch& s = *scratch[w];
    const int a0 = ti * grid.tile, a_count = std::min(grid.tile, n - a0);
    const int b0 = tj * grid.tile, b_count = std::min(grid.tile, n - b0);
    // Frames touched by both tiles (I, J) and (J, I): each range with a window and a halo
    // on both sides.
    const int r0 = std::max(0, a0 - k), r1 = std::min(n, a0 + a_count + k);
    const int c0 = std::max(0, b0 - k), c1 = std::min(n, b0 + b_count + k);
    s.forward.compute(features, r0, r1 - r0, c0, c1 - c0);
    const unsigned char side = sides_at(i);
    if ((side & 1) != 0) {
      visitor(s.worker.run(a0, a_count, b0, b_count, s.forward));
      if (on_tile_done) on_tile_done(++done, stats.tiles);
    }
    if (ti != tj && (side & 2) != 0) {
      s.backward.transpose_from(s.forward);
      visitor(s.worker.run(b0, b_count, a0, a_count, s.backward));
      if (on_tile_done) on_tile_done(++done, stats.tiles);
    }
  });
  stats.stopped = stopped.load();
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

double time_plain_products(const FrameFeatures& features, const DistanceSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const TileItems grid = tile_items(features, settings);
  const long long tiles = static_cast<long long>(grid.per_side) * grid.per_side;
  const int workers = static_cast<int>(std::min<long long>(worker_count(settings), std::max(1LL, tiles)));
  std::vector<Products> products(workers);
  run_items(tiles, workers, [&](int worker, long long item) {
    const int a0 = static_cast<int>(item / grid.per_side) * grid.tile;
    const int b0 = static_cast<int>(item % grid.per_side) * grid.tile;
    products[worker].compute(features, a0, std::min(grid.tile, grid.frames - a0), b0,
                             std::min(grid.tile, grid.frames - b0));
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace mg
