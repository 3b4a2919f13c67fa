// Minima above the pruned stage's ceiling, computed tile by tile when bridges ask for them.
#include "motiongraph/graph/on_demand_candidates.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "motiongraph/metric/bounded_tiles.h"

namespace mg {

namespace {

constexpr double kAll = std::numeric_limits<double>::infinity();
// Levels rise 4x in D (2x in RMS) a step; past this many times the ceiling, to every pair.
constexpr double kLastStep = 256.0;

bool by_frames(const Transition& x, const Transition& y) {
  return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
}

}  // namespace

OnDemandCandidates::OnDemandCandidates(const FrameFeatures& features, const CandidateSearch& search,
                                       const WindowEmbeddingSettings& embedding, int threads, PrunedStageWork done)
    : features_(features),
      leave_tags_(features.leave_tags),
      arrive_tags_(features.arrive_tags),
      ceiling_(search.ceiling),
      embedding_(std::move(done.embedding)) {
  pruned_.embedding = embedding;
  pruned_.tile_frames = search.tile_frames;
  pruned_.threads = threads;
  candidate_settings_.continuation_radius = search.continuation_radius;
  tile_ = std::max(1, pruned_.tile_for(features_.window));
  side_ = (features_.frames + tile_ - 1) / tile_;
  known_.assign(static_cast<size_t>(side_) * side_, ceiling_);
  if (done.tiles.size() == known_.size()) {
    for (size_t tile = 0; tile < known_.size(); ++tile) {
      if (done.tiles[tile]) known_[tile] = kAll;
    }
    for (const Transition& t : done.above) {
      const size_t tile = static_cast<size_t>(t.from_frame / tile_) * side_ + static_cast<size_t>(t.to_frame / tile_);
      if (t.distance > ceiling_ && tile < known_.size() && done.tiles[tile]) above_.push_back(t);
    }
    std::sort(above_.begin(), above_.end(), by_frames);
  }
}

OnDemandCandidates::Regions OnDemandCandidates::regions(std::span<const std::vector<char>> cores) const {
  Regions out;
  out.tags = std::min(kBridgeTags, static_cast<int>(cores.size()));
  out.rows.assign(static_cast<size_t>(side_) * out.tags, 0);
  out.columns.assign(static_cast<size_t>(side_) * out.tags, 0);
  for (int t = 0; t < out.tags; ++t) {
    const std::vector<char>& core = cores[t];
    const TagMask mt = TagMask{1} << t;
    const int frames = std::min(features_.frames, static_cast<int>(core.size()));
    for (int f = 0; f < frames; ++f) {
      if (!core[f]) continue;
      const size_t at = static_cast<size_t>(f / tile_) * out.tags + t;
      const TagMask leaving = leave_tags_[static_cast<size_t>(f)];
      const TagMask arriving = arrive_tags_[static_cast<size_t>(f)];
      if (leaving & mt) out.rows[at] |= ~leaving;
      if (arriving & mt) out.columns[at] |= ~arriving;
    }
  }
  return out;
}

void OnDemandCandidates::tag_windows(int tag, std::span<const char> in_class) {
  if (tag < 0 || tag >= kBridgeTags) return;
  const TagMask bit = TagMask{1} << tag;
  const int k = features_.window;
  const auto frames = static_cast<int>(std::min(in_class.size(), leave_tags_.size()));
  for (int a = 0; a + k <= frames; ++a) {
    if (!features_.can_leave[static_cast<size_t>(a)]) continue;
    const auto first = in_class.begin() + a;
    if (std::find(first, first + k, 0) != first + k) continue;
    leave_tags_[static_cast<size_t>(a)] |= bit;
    arrive_tags_[static_cast<size_t>(a + k - 1)] |= bit;  // the window arriving at its last frame
  }
}

template <class Visit>
void OnDemandCandidates::for_each_region_tile(const Regions& regions, int s, int u, Visit visit) const {
  if (s == u || s >= regions.tags || u >= regions.tags) return;
  const TagMask ms = TagMask{1} << s, mu = TagMask{1} << u;
  for (int i = 0; i < side_; ++i) {
    if (!(regions.rows[static_cast<size_t>(i) * regions.tags + s] & mu)) continue;
    for (int j = 0; j < side_; ++j) {
      if (!(regions.columns[static_cast<size_t>(j) * regions.tags + u] & ms)) continue;
      if (!visit(static_cast<size_t>(i) * side_ + j)) return;
    }
  }
}

double OnDemandCandidates::lowest_known(const Regions& regions, int s, int u, double floor) const {
  double level = kAll;
  for_each_region_tile(regions, s, u, [&](size_t tile) {
    level = std::min(level, known_[tile]);
    return level > floor;
  });
  return level;
}

std::vector<double> OnDemandCandidates::levels(std::span<const std::vector<char>> cores) const {
  std::vector<double> out(static_cast<size_t>(kBridgeTags) * kBridgeTags, kAll);
  const Regions all = regions(cores);
  for (int s = 0; s < all.tags; ++s) {
    for (int u = 0; u < all.tags; ++u) {
      out[static_cast<size_t>(s) * kBridgeTags + u] = lowest_known(all, s, u, ceiling_);  // no tile knows less
    }
  }
  return out;
}

Status OnDemandCandidates::raise(std::span<const TagPair> pairs, std::span<const std::vector<char>> cores) {
  const auto start = std::chrono::steady_clock::now();
  const bool any_window = std::find(features_.can_leave.begin(), features_.can_leave.end(), 1) !=
                          features_.can_leave.end();
  // Each pair's new level, and the tiles of its region below it.
  const Regions all = regions(cores);
  std::vector<std::pair<double, std::vector<size_t>>> raised;
  for (const TagPair& pair : pairs) {
    if (pair.from_tag < 0 || pair.from_tag >= kBridgeTags || pair.to_tag < 0 || pair.to_tag >= kBridgeTags) {
      return Error{"", 0, "a bridge's tag is out of range"};
    }
    const double level = lowest_known(all, pair.from_tag, pair.to_tag, -kAll);
    if (level == kAll) continue;
    double next = 4.0 * level;
    if (!(next > 0.0) || next > kLastStep * ceiling_ || !any_window) next = kAll;
    std::vector<size_t> tiles;
    for_each_region_tile(all, pair.from_tag, pair.to_tag, [&](size_t tile) {
      if (known_[tile] < next) tiles.push_back(tile);
      return true;
    });
    raised.emplace_back(next, std::move(tiles));
  }
  std::sort(raised.begin(), raised.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  // Level by level upwards, one search each: the tiles below it that the bound cannot rule out
  // are computed, the others are known up to it.
  std::vector<char> wanted(known_.size(), 0), only(known_.size(), 0);
  for (size_t first = 0; first < raised.size();) {
    const double next = raised[first].first;
    size_t last = first;
    bool any = false;
    std::fill(only.begin(), only.end(), 0);
    for (; last < raised.size() && raised[last].first == next; ++last) {
      for (const size_t tile : raised[last].second) {
        if (known_[tile] < next && !wanted[tile]) only[tile] = 1, any = true;
      }
    }
    first = last;
    if (!any) continue;
    if (next == kAll) {
      for (size_t tile = 0; tile < only.size(); ++tile) wanted[tile] |= only[tile];
      continue;
    }
    if (!embedding_) {
      WindowEmbeddingSettings settings = pruned_.embedding;
      if (settings.threads == 0) settings.threads = pruned_.threads;
      auto made = make_window_embedding(features_, settings);
      if (!made) return made.error();
      embedding_ = std::move(*made);
    }
    // The slack of plan_pruned_search: the bound is summed in float.
    const auto search_start = std::chrono::steady_clock::now();
    const BoundedTiles bounded =
        find_bounded_tiles(features_, *embedding_, tile_, next * (1.0 + 1e-3), pruned_.threads, only);
    statistics_.search_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - search_start).count();
    for (size_t tile = 0; tile < only.size(); ++tile) {
      if (!only[tile]) continue;
      if (bounded.flags[tile]) {
        wanted[tile] = 1;
      } else {
        known_[tile] = next;
      }
    }
  }
  // The wanted tiles as the exhaustive stage's work items.
  DistanceSettings distance;
  distance.tile_frames = tile_;
  distance.threads = pruned_.threads;
  const TileItems grid = tile_items(features_, distance);
  const TileSelection selected = items_of_flagged_tiles(grid, wanted);
  if (!selected.items.empty()) {
    const auto tiles_start = std::chrono::steady_clock::now();
    auto found = find_candidates(features_, distance, candidate_settings_, {}, selected.items, selected.sides);
    statistics_.tile_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - tiles_start).count();
    if (!found) return found.error();
    const size_t before = above_.size();
    for (const Transition& t : found->minima) {
      if (t.distance > ceiling_) above_.push_back(t);
    }
    std::inplace_merge(above_.begin(), above_.begin() + static_cast<std::ptrdiff_t>(before), above_.end(), by_frames);
    for (size_t tile = 0; tile < wanted.size(); ++tile) {
      if (wanted[tile]) known_[tile] = kAll;
    }
    statistics_.raises += 1;
    statistics_.tiles += found->tiles.tiles;
    statistics_.pairs += found->tiles.pairs;
  }
  statistics_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return Ok{};
}

}  // namespace mg
