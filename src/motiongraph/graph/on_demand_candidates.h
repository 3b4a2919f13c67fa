// The local minima above the pruned distance stage's ceiling that bridges need, found when they
// need them. The pruned stage (pruned_candidates.h) knows every minimum up to its ceiling;
// bridges (bridges.h) take the best minima between the cores of two motion types whatever
// their D (on subject 16, walk to run at 20-26 cm RMS, above the 10 cm ceiling). Each tile of
// the pair matrix has a level up to which its minima are known: the ceiling at first, +infinity
// once it is computed. A pair of tags (s, u)'s level, for the cores of one selection, is the
// lowest level of the tiles of its region: the tiles that hold a pair leaving a frame of s's
// core whose window carries s but not u, and arriving at a frame of u's core whose window
// carries u but not s (a bridge's frames). When bridges ask for more, the pair's level rises (4x
// in D a step; past 256x the ceiling, to every pair): the tiles of its region below the new
// level are searched with the window embedding's bound (bounded_tiles.h), those it cannot rule
// out computed as the exhaustive stage computes them, the others known up to the new level.
// Minima above the ceiling are kept (those at or below it are the search's already).
// select_bridges, fed the levels and these minima, picks the bridges that all the minima give
// (the exhaustive stage's bridges at the same tile side). Regions follow the cores, so the low
// thresholds the automatic choice tries first, whose cores are small, compute few tiles.
//
// Memory: the window embedding (about 300 bytes a window: the stage's, or made at the first
// raise), 8 bytes per tile, and the minima found. Not thread-safe: one selection at a time.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/bridges.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/graph/pruned_candidates.h"
#include "motiongraph/metric/bounded_tiles.h"

namespace mg {

// What the pruned stage had made beyond its result, so that it is not made again: its window
// embedding (of these features, with these settings), the tiles it computed (a byte per tile,
// row-major, on its grid) and their minima above the ceiling (exact: a tile's minima need no
// other tile; finish_pruned_search drops them from the result, which holds every minimum only
// up to the ceiling).
struct PrunedStageWork {
  std::optional<WindowEmbedding> embedding;
  std::vector<char> tiles;
  std::vector<Transition> above;
};

struct OnDemandStatistics {
  int raises = 0;             // calls of raise that computed anything
  long long tiles = 0;        // tiles computed
  long long pairs = 0;        // pairs in them
  double seconds = 0.0;       // embedding, searches and tiles
  double search_seconds = 0.0;  // of them, finding the tiles the bound cannot rule out at each level
  double tile_seconds = 0.0;    // and computing the tiles
};

class OnDemandCandidates {
 public:
  // For `search`, a pruned stage's result (ceiling >= 0): its ceiling, tile side and continuation
  // radius are the tiles'; `embedding` and `threads` (0: one per core) as for the stage. The
  // tags are the features' (their windows'); `features` must outlive this object.
  // `done`: what the stage itself computed (its tiles must be on this object's grid).
  OnDemandCandidates(const FrameFeatures& features, const CandidateSearch& search,
                     const WindowEmbeddingSettings& embedding = {}, int threads = 0, PrunedStageWork done = {});

  // kBridgeTags^2 levels (bridges.h) for tags' cores (cores[t]: a byte per frame, empty when t
  // has none): each the lowest level of its region's tiles, +infinity when the region is empty
  // (a tag without a core, say) or computed.
  std::vector<double> levels(std::span<const std::vector<char>> cores) const;
  // The minima above the ceiling found so far, sorted by (from_frame, to_frame).
  std::span<const Transition> above() const { return above_; }
  const OnDemandStatistics& statistics() const { return statistics_; }

  // Raises the level of each pair for these cores (those at +infinity stay) and computes what
  // that needs.
  Status raise(std::span<const TagPair> pairs, std::span<const std::vector<char>> cores);

  // The windows whose every frame `in_class` holds (a byte per frame) carry `tag` too, beside the
  // features' tags: the untagged class bridged as one more tag (bridges.h untagged_bridge_tag).
  // Again with the same arguments, nothing changes.
  void tag_windows(int tag, std::span<const char> in_class);

 private:
  // The regions of every pair for some cores, worked out in one pass over the frames: per tile
  // row i and tag s (rows[i * tags + s]), the tags that the leaving windows of s's core frames
  // in that row lack, so that row i belongs to (s, u)'s region when u is among them; per tile
  // column j and tag u (columns[j * tags + u]), the tags the arriving windows of u's core frames
  // in that column lack.
  struct Regions {
    int tags = 0;
    std::vector<TagMask> rows, columns;
  };
  Regions regions(std::span<const std::vector<char>> cores) const;
  // visit(tile) for each tile of (s, u)'s region, row-major, until it returns false.
  template <class Visit>
  void for_each_region_tile(const Regions& regions, int s, int u, Visit visit) const;
  // The lowest level of (s, u)'s tiles (+infinity when it has none), stopping at `floor`.
  double lowest_known(const Regions& regions, int s, int u, double floor) const;

  const FrameFeatures& features_;
  // The tags of each frame's leaving and arriving windows: the features', and tag_windows'.
  std::vector<TagMask> leave_tags_, arrive_tags_;
  double ceiling_;
  PrunedSearchSettings pruned_;
  CandidateSettings candidate_settings_;
  int tile_ = 0, side_ = 0;
  std::vector<double> known_;  // per tile, row-major: the level up to which its minima are known
  std::vector<Transition> above_;
  std::optional<WindowEmbedding> embedding_;

  OnDemandStatistics statistics_;
};

}  // namespace mg
