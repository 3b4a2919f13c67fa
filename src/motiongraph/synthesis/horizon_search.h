// Branch and bound over walks of a fixed horizon (Kovar et al. 2002, section 4): among the
// walks from a state that play `horizon_frames` frames (or reach the goal sooner), find the
// one whose summed frame costs are least. Frame costs are non-negative, so the cost of a
// partial walk, plus the cost model's lower bound for the frames still to come, bounds every
// walk that extends it: depth first, children in increasing cost,
// and a branch is cut as soon as its cost reaches the best complete walk's. The first walk
// found is the greedy one (or follows a hint), so there is always an answer; an expansion budget and an optional
// time budget bound the work (the answer is then the best walk found so far).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/synthesis/edge_tracks.h"

namespace mg {

// Where a walk is: the node, the placement of what it plays next, the arc length its root
// has covered on the floor and the root's last world floor position.
struct SearchState {
  int node = 0;
  FloorTransform placement;
  double arc_m = 0.0;
  Vec2 last_root = Vec2::Zero();
  bool has_last = false;  // false before the first frame: arc length starts there
  long long frames = 0;   // frames played so far
};

// The frames of one edge as a walk plays them, in order: the root's world floor position and
// facing, the arc length covered (including the frame) and the frame's tags.
struct PlayedFrames {
  int first_frame = 0;             // index from the search's start of the first frame
  std::span<const Vec2> roots;
  std::span<const Vec2> facings;   // empty when the cost does not read them (FrameCost::uses_facing)
  std::span<const double> arcs_m;
  std::span<const TagMask> tags;
};

class FrameCost {
 public:
  virtual ~FrameCost() = default;
  // The cost (>= 0) of a frame the walk plays: its index from the search's start, the
  // root's world floor position and facing, the arc length covered (including this frame)
  // and the frame's tags. Setting *goal ends the walk here: it is complete.
  virtual double cost(int frame, const Vec2& root, const Vec2& facing, double arc_m, TagMask tags,
                      bool* goal) const = 0;
  // Adds the costs of the frames to *total one after the other, as cost() gives them, and stops
  // after the frame that sets the goal (*goal = true) or as soon as *total >= bound (returns
  // false). Searches call this once per edge played; a cost may override it with a loop of
  // its own that adds the very same values (PathCost does, to look up the path incrementally).
  virtual bool add_costs(const PlayedFrames& frames, double bound, double* total, bool* goal) const;
  // Whether cost() reads the facing: false spares the search turning each frame's facing.
  virtual bool uses_facing() const { return true; }
  // Whether the facing cost() is given is the frame's heading (EdgeTracks::headings, the
  // direction a walk goes) instead, where the tracks have headings.
  virtual bool uses_heading() const { return false; }
  // A lower bound of the cost of the next `frames_left` frames of any walk from a state whose
  // last frame had this root and arc length (0 is always right; tighter bounds cut more), of the
  // parts of the cost node_bound does not bound.
  virtual double remaining_bound(int frames_left, const Vec2& root, double arc_m) const {
    (void)frames_left, (void)root, (void)arc_m;
    return 0.0;
  }
  // The cost (>= 0) of taking transition edge `edge` from state `from`, when it starts within
  // the horizon: each one is a blend, so a cost here keeps captured motion between blends where
  // the path allows it; a bridge (GraphEdge::bridge, a visible blend between motion types) may
  // cost more unless it leads into the motion type asked for.
  virtual double transition_cost(const GraphEdge& edge, const SearchState& from) const {
    (void)edge, (void)from;
    return 0.0;
  }
  // The cost (>= 0) of what follows a walk that reaches the horizon (not the goal): it reached
  // it in edge `edge`, whose first `costed` frames were costed (the last of them with the root
  // at arc length horizon_arc_m), and leaves the character at `end` (the edge played out). A
  // cost-to-go: what any continuation must still pay (0 by default: the search sees its horizon
  // only). It is added to complete walks only; the bounds of partial walks (remaining_bound,
  // node_bound) must stay below it plus the frames' costs.
  virtual double terminal_cost(int edge, size_t costed, double horizon_arc_m, const SearchState& end) const {
    (void)edge, (void)costed, (void)horizon_arc_m, (void)end;
    return 0.0;
  }
  // A lower bound of what any walk from `state` (a partial walk's end, at a node, `frames_left`
  // frames short of the horizon) still costs, the frames within the horizon and terminal_cost
  // together, of the parts of the cost remaining_bound does not bound (0 is always right): a
  // partial walk's priority adds both, so that walks whose cost-to-go is high are cut before they
  // are played out.
  virtual double node_bound(const SearchState& state, int frames_left) const {
    (void)state, (void)frames_left;
    return 0.0;
  }
};

// The loop of FrameCost::add_costs, for `count` frames whose costs frame_cost(p, &reached)
// gives (inline: an override's per-frame cost is then inlined into it).
template <class PerFrame>
bool add_frame_costs(size_t count, double bound, double* total, bool* goal, PerFrame&& frame_cost) {
  for (size_t p = 0; p < count; ++p) {
    bool reached = false;
    *total += frame_cost(p, &reached);
    if (*total >= bound) return false;
    if (reached) {
      *goal = true;
      break;
    }
  }
  return true;
}

// The widest beam a search takes (each partial walk is kept in memory).
inline constexpr int kMaxBeamWidth = 1'000'000;
// The furthest a path or steering search looks ahead: a minute of motion (each partial walk of
// the beam holds its frames; 1e5 s ran out of memory, where 3-5 s is what searches want).
inline constexpr double kMaxHorizonS = 60.0;
// A search's horizon (above 0, at most kMaxHorizonS) and the commit kept of each (above 0, at
// most the horizon); the error's message starts with `who` ("path search").
Status check_horizon_and_commit(double horizon_s, double commit_s, const char* who);

struct HorizonSettings {
  int horizon_frames = 90;
  long long max_expansions = 200000;  // edges evaluated
  double time_budget_s = 0.0;         // 0: none
  // > 0: before the depth-first search, a beam search over frames played keeps, at each
  // frame count, the beam_width partial walks of least cost plus bound (one per node) and
  // extends them; its best complete walk is the branch and bound's first bound and answer.
  // On a dense graph of short pieces (a large database) the depth-first search alone spends
  // its budget near the end of the greedy walk; the beam looks wide early on. Its work is
  // bounded by beam_width x out-degree x horizon edges, counted in the expansions.
  int beam_width = 0;

  Status validate() const;
};

struct HorizonResult {
  std::vector<int> edges;  // the best walk found
  double cost = std::numeric_limits<double>::infinity();
  bool goal_reached = false;
  long long expansions = 0;
  bool budget_exhausted = false;  // expansion or time budget ran out before the search did
};

// `hint` (optional): a walk from start to try first, e.g. what is left of the previous
// search's best walk; it only changes the order of the search, not its result.
HorizonResult horizon_search(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start,
                             const FrameCost& cost, const HorizonSettings& settings, std::span<const int> hint = {});

// The state after playing edge `edge` from `state`.
SearchState advance(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& state, int edge);

// The world floor facings of the frames `edges` play from `state`, in order: the first `count`
// (all when they play fewer).
std::vector<Vec2> walk_facings(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& state,
                               std::span<const int> edges, size_t count);
// Their world floor root positions likewise.
std::vector<Vec2> walk_roots(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& state,
                             std::span<const int> edges, size_t count);

}  // namespace mg
