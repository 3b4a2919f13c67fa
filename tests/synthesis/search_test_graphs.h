// Small random graphs (no database behind them) and a brute force for checking the searches.
#pragma once

#include <random>
#include <string>

#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/synthesis/edge_tracks.h"
#include "motiongraph/synthesis/horizon_search.h"

namespace mg::test {

// A strongly connected random graph: a ring through every node plus random extra edges (a
// quarter of them transitions with a random distance), 1..max_frames frames per edge.
MotionGraph random_search_graph(std::mt19937& rng, int nodes, int extra_edges, int max_frames);

// Tracks for it: roots stepping up to 0.1 m a frame, unit facings, random tags (bits 0, 1)
// and a random placement change on transitions.
EdgeTracks random_tracks(std::mt19937& rng, const MotionGraph& graph);

// Every walk from `start` played out as horizon_search plays it, priced through the FrameCost
// interface: a transition's cost when it starts within the horizon, each frame's cost within it
// (the facing or, for a cost that judges headings, the heading), and the terminal cost of a walk
// that reaches the horizon without reaching the goal. The least.
double every_walk(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start, const FrameCost& cost,
                  int horizon);

// What node bounds saved: the depth-first searches' expansions with the bound and without it,
// in how many searches it cut, and how many partial walks were checked and had a node bound.
struct BoundTally {
  long long with_bound = 0, without_bound = 0;
  int cut = 0;
  long long partial_walks = 0, node_bounded = 0;
};

// Expects each partial walk's bound from `start` (remaining_bound plus node_bound, as
// horizon_search adds them) to be at most the least cost of the walks that complete it, and
// horizon_search with `cost` (a generous budget, with and without a beam) to find every_walk's
// least cost, without the cost's node bound too; tallies the expansions of both (a bound
// reorders the children too, so one search may take more; summed over many, fewer). `what`
// names the case in failures. Returns the least cost.
double expect_search_exact(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start,
                           const FrameCost& cost, int horizon, BoundTally& tally, const std::string& what);

// A cost without its node bound: a search with it is as exact, and only its pruning differs.
class WithoutNodeBound final : public FrameCost {
 public:
  explicit WithoutNodeBound(const FrameCost& cost) : cost_(cost) {}
  double cost(int frame, const Vec2& root, const Vec2& facing, double arc_m, TagMask tags, bool* goal) const override {
    return cost_.cost(frame, root, facing, arc_m, tags, goal);
  }
  bool add_costs(const PlayedFrames& frames, double bound, double* total, bool* goal) const override {
    return cost_.add_costs(frames, bound, total, goal);
  }
  bool uses_facing() const override { return cost_.uses_facing(); }
  bool uses_heading() const override { return cost_.uses_heading(); }
  double remaining_bound(int frames_left, const Vec2& root, double arc_m) const override {
    return cost_.remaining_bound(frames_left, root, arc_m);
  }
  double transition_cost(const GraphEdge& edge, const SearchState& from) const override {
    return cost_.transition_cost(edge, from);
  }
  double terminal_cost(int edge, size_t costed, double horizon_arc_m, const SearchState& end) const override {
    return cost_.terminal_cost(edge, costed, horizon_arc_m, end);
  }

 private:
  const FrameCost& cost_;
};

}  // namespace mg::test
