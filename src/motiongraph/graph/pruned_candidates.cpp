// The pruned distance stage: the window embedding's bound picks the tiles, the exhaustive
// stage runs them, and what lies above the ceiling is set aside.
#include "motiongraph/graph/pruned_candidates.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "motiongraph/core/parallel_for.h"
#include "motiongraph/metric/bounded_tiles.h"

namespace mg {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The pairs with a defined D: a window can leave from a and arrive at b.
long long defined_pairs(const FrameFeatures& f) {
  return std::count(f.can_leave.begin(), f.can_leave.end(), 1) * std::count(f.can_arrive.begin(), f.can_arrive.end(), 1);
}

}  // namespace

Status PrunedSearchSettings::validate() const {
  if (auto s = embedding.validate(); !s) return s;
  if (tile_frames != 0 && (tile_frames < 16 || tile_frames > 16384)) {
    return Error{"", 0, "the pruned stage's tile size must be 0 (automatic) or 16 to 16384 frames"};
  }
  if (threads < 0 || threads > 256) return Error{"", 0, "threads must be 0 (all cores) to 256"};
  return Ok{};
}

int PrunedSearchSettings::tile_for(int window) const {
  if (tile_frames > 0) return tile_frames;
  // Measured (docs/performance.md): 64 at 30 fps (k = 10) on the 8-subject library, 256 at
  // 120 fps (k = 40). Smaller tiles skip more pairs but cost more per pair (their halo of k
  // frames on each side, and BLAS on smaller products) and more to search.
  return std::max(64, static_cast<int>(std::lround(6.4 * window / 64.0)) * 64);
}

Result<PrunedPlan> plan_pruned_search(const FrameFeatures& f, double ceiling, const PrunedSearchSettings& pruned,
                                      PrunedSearchStatistics* statistics) {
  if (auto s = pruned.validate(); !s) return s.error();
  if (!(ceiling >= 0.0) || !std::isfinite(ceiling)) return Error{"", 0, "the pruned stage's ceiling must be >= 0"};
  PrunedSearchStatistics local;
  PrunedSearchStatistics& stats = statistics != nullptr ? *statistics : local;
  stats = {};
  const auto start = std::chrono::steady_clock::now();
  PrunedPlan plan;
  plan.distance.tile_frames = pruned.tile_for(f.window);
  plan.distance.threads = pruned.threads;
  const TileItems grid = tile_items(f, plan.distance);
  stats.tile_frames = grid.tile;
  stats.tiles = static_cast<long long>(grid.per_side) * grid.per_side;
  stats.defined_pairs = defined_pairs(f);
  if (stats.defined_pairs == 0) return plan;
  WindowEmbeddingSettings embedding_settings = pruned.embedding;
  if (embedding_settings.threads == 0) embedding_settings.threads = pruned.threads;
  auto embedding = make_window_embedding(f, embedding_settings);
  if (!embedding) return embedding.error();
  stats.embedding_seconds = seconds_since(start);
  // The bound is computed in float: a relative 1e-3 of slack keeps every pair at or below the
  // ceiling, and flags only tiles that may hold one.
  const auto search_start = std::chrono::steady_clock::now();
  BoundedTiles bounded = find_bounded_tiles(f, *embedding, grid.tile, ceiling * (1.0 + 1e-3), pruned.threads);
  // An item computes the products of tiles (I, J) and (J, I): it is run when either is flagged,
  // and visits the flagged ones only.
  TileSelection selected = items_of_flagged_tiles(grid, bounded.flags);
  plan.items = std::move(selected.items);
  plan.sides = std::move(selected.sides);
  for (size_t i = 0; i < plan.items.size(); ++i) stats.tiles_computed += grid.tile_count(plan.items[i], plan.sides[i]);
  stats.search_seconds = seconds_since(search_start);
  plan.embedding = std::move(*embedding);
  plan.tiles = std::move(bounded.flags);
  return plan;
}

void finish_pruned_search(const FrameFeatures& f, double ceiling, CandidateSearch& search) {
  search.ceiling = ceiling;
  // Minima above the ceiling: the tiles left out would hold more of them.
  std::erase_if(search.minima, [ceiling](const Transition& t) { return !(t.distance <= ceiling); });
  // The histogram holds every defined pair of the computed tiles: those above the ceiling's
  // bin join the pairs left out in the overflow bin.
  search.histogram.fold_above(ceiling);
  search.histogram.add_above(static_cast<std::uint64_t>(defined_pairs(f)) - search.histogram.total());
  // Pixels: exact at or below the ceiling; +infinity where the defined pairs all lie above it
  // (the pixel was not computed, or its smallest computed D is above).
  const int block = search.picture_block, side = search.picture_side;
  std::vector<char> leave_block(static_cast<size_t>(side), 0), arrive_block(static_cast<size_t>(side), 0);
  for (int a = 0; a < f.frames; ++a) {
    if (f.can_leave[static_cast<size_t>(a)]) leave_block[static_cast<size_t>(a / block)] = 1;
    if (f.can_arrive[static_cast<size_t>(a)]) arrive_block[static_cast<size_t>(a / block)] = 1;
  }
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  for (int r = 0; r < side; ++r) {
    for (int c = 0; c < side; ++c) {
      float& pixel = search.picture[static_cast<size_t>(r) * side + c];
      if (pixel > ceiling || (std::isnan(pixel) && leave_block[static_cast<size_t>(r)] &&
                              arrive_block[static_cast<size_t>(c)])) {
        pixel = kInfinity;
      }
    }
  }
}

Result<CandidateSearch> find_candidates_pruned(const FrameFeatures& f, double ceiling,
                                               const CandidateSettings& settings, const PrunedSearchSettings& pruned,
                                               PrunedSearchStatistics* statistics) {
  if (settings.keep_matrix) {
    return Error{"", 0, "the pruned distance stage holds no matrix (use the exhaustive stage to export it)"};
  }
  const auto start = std::chrono::steady_clock::now();
  PrunedSearchStatistics local;
  PrunedSearchStatistics& stats = statistics != nullptr ? *statistics : local;
  auto plan = plan_pruned_search(f, ceiling, pruned, &stats);
  if (!plan) return plan.error();
  auto empty = empty_candidate_search(f, settings);
  if (!empty) return empty.error();
  CandidateSearch search = std::move(*empty);
  if (!plan->items.empty()) {
    const auto exact_start = std::chrono::steady_clock::now();
    auto found = find_candidates(f, plan->distance, settings, {}, plan->items, plan->sides);
    if (!found) return found.error();
    search = std::move(*found);
    stats.exact_seconds = seconds_since(exact_start);
  }
  stats.computed_pairs = search.tiles.pairs;
  finish_pruned_search(f, ceiling, search);
  search.tiles.seconds = seconds_since(start);
  return search;
}

}  // namespace mg
