#include "motiongraph/metric/distance_tiles.h"

#include <atomic>
#include <cassert>
#include <memory>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include <cblas.h>

namespace mg {

namespace {

struct TileGrid {
  int n = 0, tile = 0, per_side = 0;
  long long count() const { return static_cast<long long>(per_side) * per_side; }
  // Work items: the pairs of tile rows I <= J (tile (J, I) comes with tile (I, J)).
  long long pair_count() const { return static_cast<long long>(per_side) * (per_side + 1) / 2; }
  std::pair<int, int> pair(long long item) const {
    int i = 0;
    while (item >= per_side - i) {
      item -= per_side - i;
      ++i;
    }
    return {i, i + static_cast<int>(item)};
  }
};

int worker_count(const DistanceSettings& settings) {
  if (settings.threads > 0) return settings.threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

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

class TileWorker {
 public:
  explicit TileWorker(const FrameFeatures& f) : f_(f), uniform_(uniform_taper(f)) {}

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
    distance_.assign(static_cast<size_t>(tile.rows) * tile.cols, std::numeric_limits<float>::quiet_NaN());
    // Rows of E (or of its running diagonal sums) live in a ring of k + 1 rows: the pairs of
    // row a need block rows a - r0 .. a - r0 + k - 1 only.
    const int ring = k + 1;
    for (auto* buffer : {&e1_, &e2_, &e3_}) buffer->assign(static_cast<size_t>(ring) * cols, 0.0);
    for (int i = 0; i < rows; ++i) {
      accumulate_row(i, r0, c0, cols, ring);
      const int a = r0 + i - (k - 1);  // the leaving frame whose window ends on this row
      if (a >= tile.row0 && a < tile.row0 + tile.rows && f_.can_leave[a]) distances_for_row(tile, a, r0, c0, cols, ring);
    }
    tile.distance = distance_;
    return tile;
  }

 private:
  static bool uniform_taper(const FrameFeatures& f) {
    for (double u : f.taper) {
      if (u != f.taper[0]) return false;
    }
    return true;
  }

  double* ring_row(std::vector<double>& buffer, int i, int ring, int cols) {
    return buffer.data() + static_cast<size_t>(i % ring) * cols;
  }

  // E = uncentred cross sums per frame pair, in double: the float products of the centred
  // clouds plus the reference offsets, added back exactly (DESIGN.md 3.3). For a uniform
  // taper they are summed along diagonals as they go (cum(i, j) = E(i, j) + cum(i-1, j-1)).
  void accumulate_row(int i, int r0, int c0, int cols, int ring) {
    const double v = f_.point_weight_sum;
    const int fr = r0 + i;
    const double rx = f_.root_x[fr], rz = f_.root_z[fr], mx = f_.moment_x[fr], mz = f_.moment_z[fr];
    const size_t at = static_cast<size_t>(r0 + i - products_->row0) * products_->cols + (c0 - products_->col0);
    const float* g1 = products_->g1.data() + at;
    const float* g2 = products_->g2.data() + at;
    const float* g3 = products_->g3.data() + at;
    double* e1 = ring_row(e1_, i, ring, cols);
    double* e2 = ring_row(e2_, i, ring, cols);
    double* e3 = ring_row(e3_, i, ring, cols);
    const double* sx = f_.root_x.data() + c0;
    const double* sz = f_.root_z.data() + c0;
    const double* nx = f_.moment_x.data() + c0;
    const double* nz = f_.moment_z.data() + c0;
    for (int j = 0; j < cols; ++j) {
      e1[j] = g1[j] + (rx * nx[j] + rz * nz[j]) + (mx * sx[j] + mz * sz[j]) + v * (rx * sx[j] + rz * sz[j]);
      e2[j] = g2[j] + (rx * nz[j] - rz * nx[j]) + (mx * sz[j] - mz * sx[j]) + v * (rx * sz[j] - rz * sx[j]);
      e3[j] = g3[j];
    }
    if (uniform_ && i > 0) {
      const double* p1 = ring_row(e1_, i - 1, ring, cols);
      const double* p2 = ring_row(e2_, i - 1, ring, cols);
      const double* p3 = ring_row(e3_, i - 1, ring, cols);
      for (int j = 1; j < cols; ++j) {
        e1[j] += p1[j - 1];
        e2[j] += p2[j - 1];
        e3[j] += p3[j - 1];
      }
    }
  }

  // D(a, b) for every column b of the tile, once block row a - r0 + k - 1 is accumulated.
  void distances_for_row(const DistanceTile& tile, int a, int r0, int c0, int cols, int ring) {
    const int k = f_.window;
    const int i0 = a - r0;
    const int i1 = i0 + k - 1;
    const double w = f_.window_weight;
    const double x = f_.window_x[a], z = f_.window_z[a], s = f_.window_square[a];
    const double u = f_.taper[0];
    const double* end1 = ring_row(e1_, i1, ring, cols);
    const double* end2 = ring_row(e2_, i1, ring, cols);
    const double* end3 = ring_row(e3_, i1, ring, cols);
    const double* start1 = i0 > 0 ? ring_row(e1_, i0 - 1, ring, cols) : nullptr;
    const double* start2 = i0 > 0 ? ring_row(e2_, i0 - 1, ring, cols) : nullptr;
    const double* start3 = i0 > 0 ? ring_row(e3_, i0 - 1, ring, cols) : nullptr;
    float* out = distance_.data() + static_cast<size_t>(a - tile.row0) * tile.cols;
    for (int b = std::max(tile.col0, k - 1); b < tile.col0 + tile.cols; ++b) {
      if (!f_.can_arrive[b]) continue;
      const int j0 = b - k + 1 - c0;  // block column of the arrival window's first frame
      const int j1 = j0 + k - 1;
      double c1, c2, c3;
      if (uniform_) {
        c1 = end1[j1];
        c2 = end2[j1];
        c3 = end3[j1];
        if (i0 > 0 && j0 > 0) {
          c1 -= start1[j0 - 1];
          c2 -= start2[j0 - 1];
          c3 -= start3[j0 - 1];
        }
        c1 *= u;
        c2 *= u;
        c3 *= u;
      } else {
        c1 = c2 = c3 = 0.0;
        for (int t = 0; t < k; ++t) {
          const size_t at = static_cast<size_t>((i0 + t) % ring) * cols + (j0 + t);
          c1 += f_.taper[t] * e1_[at];
          c2 += f_.taper[t] * e2_[at];
          c3 += f_.taper[t] * e3_[at];
        }
      }
      const int b_first = b - k + 1;
      const double x2 = f_.window_x[b_first], z2 = f_.window_z[b_first];
      const double big_a = c1 - (x * x2 + z * z2) / w;
      const double big_b = c2 - (x * z2 - z * x2) / w;
      const double d = s + f_.window_square[b_first] - (x * x + z * z + x2 * x2 + z2 * z2) / w - 2.0 * c3 -
                       2.0 * std::sqrt(big_a * big_a + big_b * big_b);
      out[b - tile.col0] = static_cast<float>(std::max(0.0, d));
    }
  }

  const FrameFeatures& f_;
  const bool uniform_;
  const Products* products_ = nullptr;
  std::vector<double> e1_, e2_, e3_;
  std::vector<float> distance_;
};

template <class Work>
void run_items(long long items, int workers, const Work& work) {
  std::atomic<long long> next{0};
  auto loop = [&](int worker) {
    for (long long t = next++; t < items; t = next++) work(worker, t);
  };
  // Work is spread over our threads; BLAS itself then runs single-threaded.
  if (workers > 1) openblas_set_num_threads(1);
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w) threads.emplace_back(loop, w);
  loop(0);
  for (auto& thread : threads) thread.join();
  if (workers > 1) openblas_set_num_threads(workers);
}

TileGrid grid_for(const FrameFeatures& f, const DistanceSettings& settings) {
  TileGrid grid;
  grid.n = f.frames;
  grid.tile = settings.tile_frames;
  grid.per_side = (f.frames + grid.tile - 1) / grid.tile;
  return grid;
}

}  // namespace

TileRunStatistics for_each_distance_tile(const FrameFeatures& features, const DistanceSettings& settings,
                                         const TileVisitor& visitor,
                                         const std::function<void(long long, long long)>& on_tile_done) {
  const auto start = std::chrono::steady_clock::now();
  const TileGrid grid = grid_for(features, settings);
  const int n = grid.n;
  const int k = features.window;
  const int workers = static_cast<int>(std::min<long long>(worker_count(settings), std::max(1LL, grid.pair_count())));
  struct Scratch {
    explicit Scratch(const FrameFeatures& f) : worker(f) {}
    TileWorker worker;
    Products forward, backward;
  };
  std::vector<std::unique_ptr<Scratch>> scratch;
  for (int w = 0; w < workers; ++w) scratch.push_back(std::make_unique<Scratch>(features));
  std::atomic<long long> done{0};
  run_items(grid.pair_count(), workers, [&](int w, long long item) {
    const auto [ti, tj] = grid.pair(item);
    Scratch& s = *scratch[w];
    const int a0 = ti * grid.tile, a_count = std::min(grid.tile, n - a0);
    const int b0 = tj * grid.tile, b_count = std::min(grid.tile, n - b0);
    // Frames touched by both tiles (I, J) and (J, I): each range with a window and a halo
    // on both sides.
    const int r0 = std::max(0, a0 - k), r1 = std::min(n, a0 + a_count + k);
    const int c0 = std::max(0, b0 - k), c1 = std::min(n, b0 + b_count + k);
    s.forward.compute(features, r0, r1 - r0, c0, c1 - c0);
    visitor(s.worker.run(a0, a_count, b0, b_count, s.forward));
    if (on_tile_done) on_tile_done(++done, grid.count());
    if (ti != tj) {
      s.backward.transpose_from(s.forward);
      visitor(s.worker.run(b0, b_count, a0, a_count, s.backward));
      if (on_tile_done) on_tile_done(++done, grid.count());
    }
  });
  TileRunStatistics stats;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.tiles = grid.count();
  stats.pairs = static_cast<long long>(grid.n) * grid.n;
  return stats;
}

double time_plain_products(const FrameFeatures& features, const DistanceSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const TileGrid grid = grid_for(features, settings);
  const int workers = static_cast<int>(std::min<long long>(worker_count(settings), std::max(1LL, grid.count())));
  std::vector<Products> products(workers);
  run_items(grid.count(), workers, [&](int worker, long long item) {
    const int a0 = static_cast<int>(item / grid.per_side) * grid.tile;
    const int b0 = static_cast<int>(item % grid.per_side) * grid.tile;
    products[worker].compute(features, a0, std::min(grid.tile, grid.n - a0), b0, std::min(grid.tile, grid.n - b0));
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace mg
