#include "motiongraph/graph/candidates.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>

#include <fmt/format.h>

#include "motiongraph/core/stop.h"
#include "motiongraph/core/vector_clones.h"

namespace mg {

namespace {

// flags[m] = 1 where row[m] is a value (not NaN) and a local minimum of its 8 neighbours
// (row[m +- 1], up[m - 1 .. m + 1], down[m - 1 .. m + 1], all readable): none smaller, ties
// to the first in row-major order, NaN never smaller. The tests are combined with & (no
// branch), so the loop vectorises.
MG_VECTOR_CLONES void local_minimum_flags(int count, const float* __restrict row, const float* __restrict up,
                                          const float* __restrict down, unsigned char* __restrict flags) {
  for (int m = 0; m < count; ++m) {
    const float d = row[m];
    flags[m] = (d >= 0.0f) & !(row[m - 1] <= d) & !(row[m + 1] < d) & !(up[m - 1] <= d) & !(up[m] <= d) &
               !(up[m + 1] <= d) & !(down[m - 1] < d) & !(down[m] < d) & !(down[m + 1] < d);
  }
}

// Distances are >= 0 or NaN. The bits of such floats order as unsigned integers do, with NaN
// (either sign) above infinity and every value: an integer minimum, which vectorises, is the
// smallest value and never a NaN. column_min[m] = min(column_min[m], bits of row[m]).
constexpr std::uint32_t kInfinityBits = 0x7f800000u;

MG_VECTOR_CLONES void column_min_bits(int count, const float* __restrict row, std::uint32_t* __restrict column_min) {
  for (int m = 0; m < count; ++m) column_min[m] = std::min(column_min[m], std::bit_cast<std::uint32_t>(row[m]));
}

bool minimum_order(const Transition& x, const Transition& y) {
  return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
}

}  // namespace

Status CandidateSettings::validate() const {
  if (continuation_radius < -1) return Error{"", 0, "continuation radius must be >= 0 (or -1 for the window)"};
  if (max_matrix_frames < 0) return Error{"", 0, "max matrix frames must be >= 0"};
  if (picture_side < 16 || picture_side > 8192) return Error{"", 0, "picture side must be 16 to 8192 pixels"};
  return Ok{};
}

Result<CandidateSearch> empty_candidate_search(const FrameFeatures& f, const CandidateSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
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
  return search;
}

Status merge_candidates(CandidateSearch& into, const CandidateSearch& part) {
  if (part.window != into.window || part.continuation_radius != into.continuation_radius ||
      part.picture_side != into.picture_side || part.picture_block != into.picture_block ||
      part.picture.size() != into.picture.size() || !part.matrix.empty()) {
    return Error{"", 0, "a part of the distance stage does not fit the others (another window, radius or picture)"};
  }
  const auto middle = static_cast<std::ptrdiff_t>(into.minima.size());
  into.minima.insert(into.minima.end(), part.minima.begin(), part.minima.end());
  std::inplace_merge(into.minima.begin(), into.minima.begin() + middle, into.minima.end(), minimum_order);
  into.histogram.merge(part.histogram);
  if (into.tile_frames == 0) into.tile_frames = part.tile_frames;
  for (size_t i = 0; i < into.picture.size(); ++i) {
    const float value = part.picture[i];
    if (value == value && !(into.picture[i] <= value)) into.picture[i] = value;  // NaN or larger
  }
  into.tiles.tiles += part.tiles.tiles;
  into.tiles.pairs += part.tiles.pairs;
  into.tiles.seconds = std::max(into.tiles.seconds, part.tiles.seconds);
  return Ok{};
}

Result<CandidateSearch> find_candidates(const FrameFeatures& f, const DistanceSettings& distance,
                                        const CandidateSettings& settings,
                                        const std::function<void(long long, long long)>& on_tile_done,
                                        std::span<const long long> items, std::span<const unsigned char> sides,
                                        std::stop_token stop) {
  if (auto s = distance.validate(); !s) return s.error();
  if (!sides.empty() && sides.size() != items.size()) return Error{"", 0, "one side selection per work item is needed"};
  auto empty = empty_candidate_search(f, settings);
  if (!empty) return empty.error();
  CandidateSearch search = std::move(*empty);
  search.tile_frames = distance.tile_frames;
  const int n = f.frames;
  const int k = f.window;
  const int radius = search.continuation_radius;
  const int block = search.picture_block;
  const int side = search.picture_side;
  std::mutex mutex;
  search.tiles = for_each_distance_tile(f, distance, [&](const DistanceTile& tile) {
    DistanceHistogram histogram;
    std::vector<Transition> minima;
    // The picture's pixels this tile touches, [pixel_row0, ..) x [pixel_col0, ..): block
    // minima of its inner region (infinity where none is finite), merged at the end.
    const int pixel_row0 = tile.leave_begin / block, pixel_col0 = tile.arrive_begin / block;
    const int pixel_rows = (tile.leave_begin + tile.leave_count - 1) / block - pixel_row0 + 1;
    const int pixel_cols = (tile.arrive_begin + tile.arrive_count - 1) / block - pixel_col0 + 1;
    std::vector<float> pixels(static_cast<size_t>(pixel_rows) * pixel_cols, std::numeric_limits<float>::infinity());
    // A missing neighbour row (at the matrix's edge) reads as NaN, which never beats a value.
    const std::vector<float> nan_row(static_cast<size_t>(tile.cols), std::numeric_limits<float>::quiet_NaN());
    std::vector<unsigned char> is_minimum(static_cast<size_t>(tile.arrive_count));
    std::vector<std::uint32_t> column_min(static_cast<size_t>(tile.arrive_count), kInfinityBits);
    const int b_begin = tile.arrive_begin, b_end = tile.arrive_begin + tile.arrive_count;
    const size_t inner_at = static_cast<size_t>(tile.leave_begin - tile.row0) * tile.cols + (b_begin - tile.col0);
    histogram.add_block(&tile.distance[inner_at], tile.leave_count, tile.arrive_count, tile.cols);
    for (int a = tile.leave_begin; a < tile.leave_begin + tile.leave_count; ++a) {
      // The stored rows above, at and below a, indexed by frame b.
      const float* row = &tile.distance[static_cast<size_t>(a - tile.row0) * tile.cols] - tile.col0;
      const float* up = (a > tile.row0 ? row - tile.cols : nan_row.data() - tile.col0);
      const float* down = (a + 1 < tile.row0 + tile.rows ? row + tile.cols : nan_row.data() - tile.col0);
      if (!search.matrix.empty()) {
        std::copy(row + b_begin, row + b_end, search.matrix.data() + static_cast<size_t>(a) * n + b_begin);
      }
      // Picture: the smallest value of each block, first down each column over the rows of
      // one pixel row, then across the block's columns once that pixel row is complete.
      column_min_bits(tile.arrive_count, row + b_begin, column_min.data());
      if ((a + 1) % block == 0 || a + 1 == tile.leave_begin + tile.leave_count) {
        float* pixel = pixels.data() + static_cast<size_t>(a / block - pixel_row0) * pixel_cols;
        for (int b0 = b_begin; b0 < b_end; ++pixel) {
          const int b1 = std::min(b_end, (b0 / block + 1) * block);
          const std::uint32_t smallest =
              *std::min_element(column_min.begin() + (b0 - b_begin), column_min.begin() + (b1 - b_begin));
          *pixel = std::bit_cast<float>(smallest);  // infinity where none is finite
          b0 = b1;
        }
        std::fill(column_min.begin(), column_min.end(), kInfinityBits);
      }
      // Local minima: no neighbour smaller; ties go to the first in row-major order. The
      // tests are combined without branches (a vector loop); columns at the matrix's left and
      // right edges, which lack a neighbour, are treated apart.
      const int inner_begin = std::max(b_begin, 1), inner_end = std::min(b_end, n - 1);
      if (inner_begin < inner_end) {
        local_minimum_flags(inner_end - inner_begin, row + inner_begin, up + inner_begin, down + inner_begin,
                            is_minimum.data() + (inner_begin - b_begin));
      }
      for (int b : {b_begin, b_end - 1}) {
        if (b >= inner_begin && b < inner_end) continue;
        const float d = row[b];
        auto at = [&](const float* r, int c) {
          return c >= 0 && c < n ? r[c] : std::numeric_limits<float>::quiet_NaN();
        };
        is_minimum[b - b_begin] = (d >= 0.0f) && !(at(row, b - 1) <= d) && !(at(row, b + 1) < d) &&
                                  !(at(up, b - 1) <= d) && !(up[b] <= d) && !(at(up, b + 1) <= d) &&
                                  !(at(down, b - 1) < d) && !(down[b] < d) && !(at(down, b + 1) < d);
      }
      const int clip_a = f.clip_of_frame[a];
      // Flags are rare: memchr jumps from one to the next.
      const unsigned char* flags_end = is_minimum.data() + tile.arrive_count;
      auto next_flag = [&](const unsigned char* from) {
        return static_cast<const unsigned char*>(std::memchr(from, 1, static_cast<size_t>(flags_end - from)));
      };
      for (const unsigned char* flag = next_flag(is_minimum.data()); flag != nullptr; flag = next_flag(flag + 1)) {
        const int b = b_begin + static_cast<int>(flag - is_minimum.data());
        if (f.clip_of_frame[b] == clip_a && std::abs(b - (a + k - 1)) <= radius) continue;
        minima.push_back(Transition{a, b, row[b], 0.0f, 0.0f, 0.0f});
      }
    }
    std::lock_guard lock(mutex);
    search.histogram.merge(histogram);
    search.minima.insert(search.minima.end(), minima.begin(), minima.end());
    for (int r = 0; r < pixel_rows; ++r) {
      for (int c = 0; c < pixel_cols; ++c) {
        const float value = pixels[static_cast<size_t>(r) * pixel_cols + c];
        float& pixel = search.picture[static_cast<size_t>(pixel_row0 + r) * side + pixel_col0 + c];
        if (value < std::numeric_limits<float>::infinity() && !(pixel <= value)) pixel = value;  // NaN or larger
      }
    }
  }, on_tile_done, items, sides, stop);
  if (search.tiles.stopped) return stopped_error();
  std::sort(search.minima.begin(), search.minima.end(), minimum_order);
  return search;
}

}  // namespace mg
