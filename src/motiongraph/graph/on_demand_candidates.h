// The local minima above the pruned distance stage's ceiling that bridges need, found when they
// need them. The pruned stage (pruned_candidates.h) knows every minimum up to its ceiling;
// bridges (bridges.h) take the best minima between two motion types whatever their D (on
// subject 16, walk to run at 20-26 cm RMS, above the 10 cm ceiling). So bridges ask, per
// ordered pair of tags (s, u) still short of bridges, for more: the pair's level rises (4x in
// D a step, then to every pair), and the tiles of its region with a bound at most the new level
// that were not computed yet are computed as the exhaustive stage computes them. The region:
// a bridge leaves a window carrying s but not u and arrives at one carrying u but not s, so the
// tiles holding such pairs. Their minima above the ceiling are kept (those at or below it are
// the search's already). The region's minima up to the level are then all known, and
// select_bridges, fed the levels and these minima, picks the bridges that all the minima give
// (the exhaustive stage's bridges at the same tile side).
//
// Memory: the window embedding (about 300 bytes a window, made at the first raise), a byte per
// tile, and two bytes per tile for each level searched (at most four: 4, 16, 64 and 256 times the
// ceiling), kept so that no tile is searched twice at a level; and the minima found. Not thread-safe: one
// selection at a time.
#pragma once

#include <map>
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
  OnDemandCandidates(const FrameFeatures& features, const CandidateSearch& search,
                     const WindowEmbeddingSettings& embedding = {}, int threads = 0);

  // kBridgeTags^2 levels (bridges.h), each the ceiling until raised, +infinity once every tile
  // of its region is computed.
  std::span<const double> levels() const { return levels_; }
  // The minima above the ceiling found so far, sorted by (from_frame, to_frame).
  std::span<const Transition> above() const { return above_; }
  const OnDemandStatistics& statistics() const { return statistics_; }

  // Raises the level of each pair (those at +infinity stay) and computes what that needs.
  Status raise(std::span<const TagPair> pairs);

 private:
  const FrameFeatures& features_;
  double ceiling_;
  PrunedSearchSettings pruned_;
  CandidateSettings candidate_settings_;
  std::vector<double> levels_;
  std::vector<Transition> above_;
  std::vector<char> computed_;              // per tile, row-major
  // Per band of tiles and tag s (band * kBridgeTags + s): the tags u that one of its leaving
  // windows carrying s lacks (it may bridge s to u), and that one of its arriving windows
  // carrying s lacks (it may be arrived at from u to s).
  std::vector<TagMask> leave_lacks_, arrive_lacks_;
  std::optional<WindowEmbedding> embedding_;
  struct LevelFlags {
    std::vector<char> searched;  // per tile: the bound at this level looked at it
    std::vector<char> flags;     // and found that it may hold a pair at most the level
  };
  std::map<double, LevelFlags> flags_;  // by level: two bytes per tile each

  OnDemandStatistics statistics_;
};

}  // namespace mg
