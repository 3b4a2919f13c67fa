#include "motiongraph/graph/candidates.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include <fmt/format.h>

namespace mg {

Status CandidateSettings::validate() const {
  if (continuation_radius < -1) return Error{"", 0, "continuation radius must be >= 0 (or -1 for the window)"};
  if (max_matrix_frames < 0) return Error{"", 0, "max matrix frames must be >= 0"};
  if (picture_side < 16 || picture_side > 8192) return Error{"", 0, "picture side must be 16 to 8192 pixels"};
  return Ok{};
}

Result<CandidateSearch> find_candidates(const FrameFeatures& f, const DistanceSettings& distance,
                                        const CandidateSettings& settings,
                                        const std::function<void(long long, long long)>& on_tile_done) {
  if (auto s = settings.validate(); !s) return s.error();
  if (auto s = distance.validate(); !s) return s.error();
  const int n = f.frames;
  CandidateSearch search;
  search.window = f.window;
  search.continuation_radius = settings.continuation_radius < 0 ? f.window : settings.continuation_radius;
  if (settings.keep_matrix) {
    if (n > settings.max_matrix_frames) {
      return Error{"", 0, fmt::format("the distance matrix of {} frames is too large to hold (limit {} frames)", n,
                                      settings.max_matrix_frames)};
    }
    search.matrix.assign(static_cast<size_t>(n) * n, std::numeric_limits<float>::quiet_NaN());
  }
  search.picture_block = std::max(1, (n + settings.picture_side - 1) / settings.picture_side);
  search.picture_side = (n + search.picture_block - 1) / search.picture_block;
  search.picture.assign(static_cast<size_t>(search.picture_side) * search.picture_side,
                        std::numeric_limits<float>::quiet_NaN());

  const int k = f.window;
  const int radius = search.continuation_radius;
  std::mutex mutex;
  search.tiles = for_each_distance_tile(f, distance, [&](const DistanceTile& tile) {
    DistanceHistogram histogram;
    std::vector<Transition> minima;
    const int block = search.picture_block;
    const int side = search.picture_side;
    std::vector<std::pair<size_t, float>> picture_updates;
    const float kNan = std::numeric_limits<float>::quiet_NaN();
    for (int a = tile.leave_begin; a < tile.leave_begin + tile.leave_count; ++a) {
      float* matrix_row = search.matrix.empty() ? nullptr : search.matrix.data() + static_cast<size_t>(a) * n;
      // The stored rows above, at and below a; a missing neighbour row reads as NaN, which
      // never beats a value.
      const float* row = &tile.distance[static_cast<size_t>(a - tile.row0) * tile.cols] - tile.col0;
      const float* up = a > tile.row0 ? row - tile.cols : nullptr;
      const float* down = a + 1 < tile.row0 + tile.rows ? row + tile.cols : nullptr;
      const int first_col = tile.col0, last_col = tile.col0 + tile.cols - 1;
      auto at = [&](const float* r, int b) { return r && b >= first_col && b <= last_col ? r[b] : kNan; };
      const int clip_a = f.clip_of_frame[a];
      float block_min = std::numeric_limits<float>::infinity();
      int block_column = tile.arrive_begin / block;
      for (int b = tile.arrive_begin; b < tile.arrive_begin + tile.arrive_count; ++b) {
        const float d = row[b];
        if (matrix_row) matrix_row[b] = d;
        if (b / block != block_column) {
          if (std::isfinite(block_min)) {
            picture_updates.emplace_back(static_cast<size_t>(a / block) * side + block_column, block_min);
          }
          block_column = b / block;
          block_min = std::numeric_limits<float>::infinity();
        }
        if (!(d >= 0.0f)) continue;  // NaN: undefined
        block_min = std::min(block_min, d);
        histogram.add(d);
        // A local minimum: no neighbour smaller; ties go to the first in row-major order.
        if (at(row, b - 1) <= d || at(row, b + 1) < d) continue;
        if (at(up, b - 1) <= d || at(up, b) <= d || at(up, b + 1) <= d) continue;
        if (at(down, b - 1) < d || at(down, b) < d || at(down, b + 1) < d) continue;
        if (f.clip_of_frame[b] == clip_a && std::abs(b - (a + k - 1)) <= radius) continue;
        minima.push_back(Transition{a, b, d, 0.0f, 0.0f, 0.0f});
      }
      if (std::isfinite(block_min)) {
        picture_updates.emplace_back(static_cast<size_t>(a / block) * side + block_column, block_min);
      }
    }
    std::lock_guard lock(mutex);
    search.histogram.merge(histogram);
    search.minima.insert(search.minima.end(), minima.begin(), minima.end());
    for (const auto& [at, value] : picture_updates) {
      float& pixel = search.picture[at];
      if (!(pixel <= value)) pixel = value;  // NaN or larger
    }
  }, on_tile_done);
  std::sort(search.minima.begin(), search.minima.end(), [](const Transition& x, const Transition& y) {
    return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
  });
  return search;
}

}  // namespace mg
