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
                                       const WindowEmbeddingSettings& embedding, int threads)
    : features_(features),
      ceiling_(search.ceiling),
      levels_(static_cast<size_t>(kBridgeTags) * kBridgeTags, search.ceiling) {
  pruned_.embedding = embedding;
  pruned_.tile_frames = search.tile_frames;
  pruned_.threads = threads;
  candidate_settings_.continuation_radius = search.continuation_radius;
}


Status OnDemandCandidates::raise(std::span<const TagPair> pairs) {
  const auto start = std::chrono::steady_clock::now();
  DistanceSettings distance;
  distance.tile_frames = pruned_.tile_for(features_.window);
  distance.threads = pruned_.threads;
  const TileItems grid = tile_items(features_, distance);
  const int side = grid.per_side;
  if (computed_.empty()) {
    computed_.assign(static_cast<size_t>(side) * side, 0);
    leave_lacks_.assign(static_cast<size_t>(side) * kBridgeTags, 0);
    arrive_lacks_.assign(static_cast<size_t>(side) * kBridgeTags, 0);
    for (int f = 0; f < features_.frames; ++f) {
      const size_t band = static_cast<size_t>(f / grid.tile) * kBridgeTags;
      const TagMask leaving = features_.leave_tags[static_cast<size_t>(f)];
      const TagMask arriving = features_.arrive_tags[static_cast<size_t>(f)];
      for (int s = 0; s < kBridgeTags; ++s) {
        if (leaving >> s & 1) leave_lacks_[band + static_cast<size_t>(s)] |= ~leaving;
        if (arriving >> s & 1) arrive_lacks_[band + static_cast<size_t>(s)] |= ~arriving;
      }
    }
  }
  const bool any_window = std::find(features_.can_leave.begin(), features_.can_leave.end(), 1) !=
                          features_.can_leave.end();
  // Each raised pair's region: rows leaving a window of s without u, columns arriving at one of
  // u without s, the tiles not computed yet.
  struct Raised {
    size_t at;
    double level;
    std::vector<char> region;
  };
  std::vector<Raised> raised;
  for (const TagPair& pair : pairs) {
    if (pair.from_tag < 0 || pair.from_tag >= kBridgeTags || pair.to_tag < 0 || pair.to_tag >= kBridgeTags) {
      return Error{"", 0, "a bridge's tag is out of range"};
    }
    const size_t at = static_cast<size_t>(pair.from_tag) * kBridgeTags + pair.to_tag;
    if (levels_[at] == kAll) continue;
    double next = 4.0 * levels_[at];
    if (!(next > 0.0) || next > kLastStep * ceiling_ || !any_window) next = kAll;
    const TagMask s = TagMask{1} << pair.from_tag, u = TagMask{1} << pair.to_tag;
    std::vector<char> region(computed_.size(), 0);
    for (int i = 0; i < side; ++i) {
      if (!(leave_lacks_[static_cast<size_t>(i) * kBridgeTags + static_cast<size_t>(pair.from_tag)] & u)) continue;
      for (int j = 0; j < side; ++j) {
        const size_t tile = static_cast<size_t>(i) * side + j;
        region[tile] = (arrive_lacks_[static_cast<size_t>(j) * kBridgeTags + static_cast<size_t>(pair.to_tag)] & s) &&
                       !computed_[tile];
      }
    }
    raised.push_back({at, next, std::move(region)});
  }
  // The bound searched at each new level, on the tiles of the regions raised to it that no
  // search at that level has looked at yet (one search per level).
  for (const Raised& r : raised) {
    if (r.level == kAll) continue;
    if (!embedding_) {
      WindowEmbeddingSettings settings = pruned_.embedding;
      if (settings.threads == 0) settings.threads = pruned_.threads;
      auto made = make_window_embedding(features_, settings);
      if (!made) return made.error();
      embedding_ = std::move(*made);
    }
    LevelFlags& at_level = flags_[r.level];
    if (at_level.searched.empty()) at_level.searched.assign(computed_.size(), 0);
    std::vector<char> only(computed_.size(), 0);
    bool any = false;
    for (const Raised& q : raised) {
      if (q.level != r.level) continue;
      for (size_t tile = 0; tile < only.size(); ++tile) {
        only[tile] |= q.region[tile] && !at_level.searched[tile];
        any = any || only[tile];
      }
    }
    if (!any) continue;
    // The slack of plan_pruned_search: the bound is summed in float.
    const auto search_start = std::chrono::steady_clock::now();
    const BoundedTiles found =
        find_bounded_tiles(features_, *embedding_, grid.tile, r.level * (1.0 + 1e-3), pruned_.threads, only);
    statistics_.search_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - search_start).count();
    if (at_level.flags.empty()) at_level.flags.assign(computed_.size(), 0);
    for (size_t tile = 0; tile < only.size(); ++tile) {
      if (!only[tile]) continue;
      at_level.flags[tile] = found.flags[tile];
      at_level.searched[tile] = 1;
    }
  }
  // The tiles the raised pairs need: their regions, where the bound at their new level allows.
  std::vector<char> wanted(computed_.size(), 0);
  for (const Raised& r : raised) {
    const LevelFlags* bounded = r.level == kAll ? nullptr : &flags_.at(r.level);
    for (size_t tile = 0; tile < wanted.size(); ++tile) {
      if (r.region[tile] && (bounded == nullptr || bounded->flags[tile])) wanted[tile] = 1;
    }
  }
  // The wanted tiles as the exhaustive stage's work items.
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
    for (size_t tile = 0; tile < wanted.size(); ++tile) computed_[tile] |= wanted[tile];
    statistics_.raises += 1;
    statistics_.tiles += found->tiles.tiles;
    statistics_.pairs += found->tiles.pairs;
  }
  for (const Raised& r : raised) levels_[r.at] = r.level;
  statistics_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return Ok{};
}

}  // namespace mg
