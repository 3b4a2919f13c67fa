#include "motiongraph/metric/distance_tiles.h"

#include <atomic>
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
};

int worker_count(const DistanceSettings& settings) {
  if (settings.threads > 0) return settings.threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

// The BLAS products for rows [r0, r0 + rows) against columns [c0, c0 + cols), row-major.
struct Products {
  std::vector<float> g1, g2, g3;
  void compute(const FrameFeatures& f, int r0, int rows, int c0, int cols) {
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
};

class TileWorker {
 public:
  explicit TileWorker(const FrameFeatures& f) : f_(f) {}

  DistanceTile run(int a0, int a_count, int b0, int b_count) {
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
    products_.compute(f_, r0, rows, c0, cols);
    accumulate(r0, rows, c0, cols);
    distance_.assign(static_cast<size_t>(tile.rows) * tile.cols, std::numeric_limits<float>::quiet_NaN());
    const bool uniform = uniform_taper();
    const double w = f_.window_weight;
    for (int a = tile.row0; a < tile.row0 + tile.rows; ++a) {
      if (!f_.can_leave[a]) continue;
      float* out = distance_.data() + static_cast<size_t>(a - tile.row0) * tile.cols;
      for (int b = tile.col0; b < tile.col0 + tile.cols; ++b) {
        if (!f_.can_arrive[b]) continue;
        const int i0 = a - r0;
        const int j0 = b - k + 1 - c0;
        double c1, c2, c3;
        if (uniform) {
          // Running sums along the diagonal: sum over t of E(i0 + t, j0 + t).
          const size_t end = static_cast<size_t>(i0 + k - 1) * cols + (j0 + k - 1);
          c1 = e1_[end];
          c2 = e2_[end];
          c3 = e3_[end];
          if (i0 > 0 && j0 > 0) {
            const size_t before = static_cast<size_t>(i0 - 1) * cols + (j0 - 1);
            c1 -= e1_[before];
            c2 -= e2_[before];
            c3 -= e3_[before];
          }
          const double u = f_.taper[0];
          c1 *= u;
          c2 *= u;
          c3 *= u;
        } else {
          c1 = c2 = c3 = 0.0;
          for (int t = 0; t < k; ++t) {
            const size_t at = static_cast<size_t>(i0 + t) * cols + (j0 + t);
            c1 += f_.taper[t] * e1_[at];
            c2 += f_.taper[t] * e2_[at];
            c3 += f_.taper[t] * e3_[at];
          }
        }
        const int b_first = b - k + 1;
        const double x = f_.window_x[a], z = f_.window_z[a];
        const double x2 = f_.window_x[b_first], z2 = f_.window_z[b_first];
        const double big_a = c1 - (x * x2 + z * z2) / w;
        const double big_b = c2 - (x * z2 - z * x2) / w;
        const double d = f_.window_square[a] + f_.window_square[b_first] - (x * x + z * z + x2 * x2 + z2 * z2) / w -
                         2.0 * c3 - 2.0 * std::sqrt(big_a * big_a + big_b * big_b);
        out[b - tile.col0] = static_cast<float>(std::max(0.0, d));
      }
    }
    tile.distance = distance_;
    return tile;
  }

 private:
  bool uniform_taper() const {
    for (double u : f_.taper) {
      if (u != f_.taper[0]) return false;
    }
    return true;
  }

  // E = uncentred cross sums per frame pair, in double: the float products of the centred
  // clouds plus the reference offsets, added back exactly (DESIGN.md 3.3). For a uniform
  // taper they are then summed along diagonals in place.
  void accumulate(int r0, int rows, int c0, int cols) {
    const size_t size = static_cast<size_t>(rows) * cols;
    e1_.resize(size);
    e2_.resize(size);
    e3_.resize(size);
    const double v = f_.point_weight_sum;
    const bool running = uniform_taper();
    for (int i = 0; i < rows; ++i) {
      const int fr = r0 + i;
      const double rx = f_.root_x[fr], rz = f_.root_z[fr], mx = f_.moment_x[fr], mz = f_.moment_z[fr];
      const float* g1 = products_.g1.data() + static_cast<size_t>(i) * cols;
      const float* g2 = products_.g2.data() + static_cast<size_t>(i) * cols;
      const float* g3 = products_.g3.data() + static_cast<size_t>(i) * cols;
      double* e1 = e1_.data() + static_cast<size_t>(i) * cols;
      double* e2 = e2_.data() + static_cast<size_t>(i) * cols;
      double* e3 = e3_.data() + static_cast<size_t>(i) * cols;
      const double* p1 = i > 0 ? e1 - cols - 1 : nullptr;
      const double* p2 = i > 0 ? e2 - cols - 1 : nullptr;
      const double* p3 = i > 0 ? e3 - cols - 1 : nullptr;
      for (int j = 0; j < cols; ++j) {
        const int fc = c0 + j;
        const double sx = f_.root_x[fc], sz = f_.root_z[fc], nx = f_.moment_x[fc], nz = f_.moment_z[fc];
        double v1 = g1[j] + (rx * nx + rz * nz) + (mx * sx + mz * sz) + v * (rx * sx + rz * sz);
        double v2 = g2[j] + (rx * nz - rz * nx) + (mx * sz - mz * sx) + v * (rx * sz - rz * sx);
        double v3 = g3[j];
        if (running && i > 0 && j > 0) {
          v1 += p1[j];
          v2 += p2[j];
          v3 += p3[j];
        }
        e1[j] = v1;
        e2[j] = v2;
        e3[j] = v3;
      }
    }
  }

  const FrameFeatures& f_;
  Products products_;
  std::vector<double> e1_, e2_, e3_;
  std::vector<float> distance_;
};

template <class Work>
void run_tiles(const TileGrid& grid, int workers, const Work& work) {
  std::atomic<long long> next{0};
  auto loop = [&](int worker) {
    for (long long t = next++; t < grid.count(); t = next++) work(worker, static_cast<int>(t / grid.per_side),
                                                                      static_cast<int>(t % grid.per_side));
  };
  // Tiles are spread over our threads; BLAS itself then runs single-threaded.
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
  const int workers = static_cast<int>(std::min<long long>(worker_count(settings), std::max(1LL, grid.count())));
  std::vector<TileWorker> tile_workers;
  for (int w = 0; w < workers; ++w) tile_workers.emplace_back(features);
  std::atomic<long long> done{0};
  run_tiles(grid, workers, [&](int worker, int row_tile, int col_tile) {
    const int a0 = row_tile * grid.tile;
    const int b0 = col_tile * grid.tile;
    const DistanceTile tile = tile_workers[worker].run(a0, std::min(grid.tile, grid.n - a0), b0,
                                                       std::min(grid.tile, grid.n - b0));
    visitor(tile);
    const long long finished = ++done;
    if (on_tile_done) on_tile_done(finished, grid.count());
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
  run_tiles(grid, workers, [&](int worker, int row_tile, int col_tile) {
    const int a0 = row_tile * grid.tile;
    const int b0 = col_tile * grid.tile;
    products[worker].compute(features, a0, std::min(grid.tile, grid.n - a0), b0, std::min(grid.tile, grid.n - b0));
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace mg
