// What path synthesis (path_synthesis.h) prices a walk at, frame by frame (Kovar et al. 2002,
// section 5, and what this project adds): the squared floor distance between the root and the
// path's point at the arc length its root has covered, a penalty for each frame without the
// motion tag the path asks for there, a penalty for falling behind the slowest speed, and for
// each transition taken (more for a bridge not leading into the type asked for). A walk that
// reaches the horizon in a segment asking for a tag also costs, weighted by tag_lookahead, what
// any walk from where it ends must still pay before that tag (tag_distance.h), so that a motion
// type no walk within the horizon reaches is headed for.
//
// The search's bounds, of two parts of the cost: remaining_bound (the distance from the path: how
// far the root is from it, against how fast the root and the path's point can close in) and
// node_bound (the tag penalties, transitions and cost-to-go: the way to the tag, where the walk
// surely plays frames asking for it); together they stay below every walk's cost, so the branch
// and bound stays exact (tests/synthesis/path_cost_test.cpp checks it against every walk).
#pragma once

#include <vector>

#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/horizon_search.h"
#include "motiongraph/synthesis/path_synthesis.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

class PathCost final : public FrameCost {
 public:
  // `segment_masks`: the tag bits each of the path's segments asks for. With
  // settings.tag_lookahead > 0 the context's costs to each tag asked for are made (or found in
  // its cache). `context` and `path` must outlive the cost.
  PathCost(const SynthesisContext& context, const FloorPath& path, std::vector<TagMask> segment_masks,
           const PathSynthesisSettings& settings);

  double cost(int frame, const Vec2& root, const Vec2& facing, double arc_m, TagMask tags, bool* goal) const override;
  // The same costs as cost(), with the path's point found from the last frame's segment.
  bool add_costs(const PlayedFrames& frames, double bound, double* total, bool* goal) const override;
  bool uses_facing() const override { return false; }
  // In m more frames the root moves at most m * max_step and so does the path's point at its
  // arc length, so the root is at least d - 2 m max_step from it (d: the distance now); and
  // the path's end cannot be reached sooner than (length - arc) / max_step frames.
  double remaining_bound(int frames_left, const Vec2& root, double arc_m) const override;
  // A bridge costs the bridge penalty more unless it lands in the motion type asked for there.
  double transition_cost(const GraphEdge& edge, const SearchState& from) const override;
  // A walk whose root is in a segment asking for a tag at the horizon's last frame costs
  // tag_lookahead times what any walk from there must still pay before the tag: the rest of its
  // last edge's frames without it, then its node's cost to the tag (none where no walk reaches
  // the tag: in a strongly connected graph, a pruned one, that is every node or none).
  double terminal_cost(int edge, size_t costed, double horizon_arc_m, const SearchState& end) const override;
  // A partial walk in a segment asking for a tag pays, on the way to the tag, its node's cost c
  // to it: within the horizon, or past it (weighted) when the walk ends in the segment, which it
  // surely does when the root cannot reach the segment's end (nor the path's) in the frames left
  // at its fastest step. Otherwise the frames it surely plays in the segment, g of them, cost
  // the tag penalty each until the tag: min(c tag_lookahead, g penalty) bounds it. The frames'
  // distance from the path, another part of their cost, is remaining_bound's.
  double node_bound(const SearchState& state, int frames_left) const override;

  // Each search starts where the root has covered arc_m (the behind penalty counts from there).
  void start_search(double arc_m) { search_arc_m_ = arc_m; }
  // Roots are compared with the path where `view` puts them (the edit's move of the last frame
  // committed: where the edited motion is).
  void set_view(const FloorTransform& view);
  Vec2 viewed(const Vec2& p) const { return {c_ * p.x() + s_ * p.y() + x_, -s_ * p.x() + c_ * p.y() + z_}; }
  // The tag asked for at arc length s: the last segment given that holds it (0: none).
  TagMask wanted_at(double s) const;

 private:
  double frame_cost(int frame, const Vec2& root, double arc_m, TagMask tags, bool* goal, int& segment) const;

  // From from_m to the next region's, `wanted` is asked for (the last region goes on past the
  // path's end); to_tag: its costs, when the search looks past its horizon.
  struct Region {
    double from_m = 0.0;
    TagMask wanted = 0;
    TagCostCache::Costs to_tag;
  };
  std::vector<Region>::const_iterator region_at(double arc_m) const;

  const SynthesisContext& context_;
  const FloorPath& path_;
  std::vector<TagMask> masks_;
  double penalty_;
  double max_step_;  // the most a root moves in a frame (0: no bounds)
  double min_step_;
  double behind_penalty_;
  double transition_penalty_;
  double bridge_penalty_;
  double lookahead_;
  double search_arc_m_ = 0.0;
  double c_ = 1.0, s_ = 0.0, x_ = 0.0, z_ = 0.0;
  std::vector<Region> regions_;
};

}  // namespace mg
