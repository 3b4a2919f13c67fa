// What a steering decision (controller.h) prices a walk at, frame by frame: (1 - cos) of the
// angle between the character's facing (holding the travel: its heading, travel_heading.h) and
// the direction asked for, plus tag_penalty for each frame without the tag asked for, plus the
// transition penalty for each transition taken (and the bridge penalty more for a bridge not
// leading into the tag); a walk that reaches the horizon also costs tag_lookahead times what any
// walk from where it ends must still pay before the tag (tag_distance.h), and a partial walk is
// bounded below by that much of its node's cost to the tag, so the branch and bound stays exact
// (tests/synthesis/steer_cost_test.cpp checks it against every walk). Asked for no tag, a walk
// pays travel_penalty per metre its root falls behind the pace asked, and one that reaches the
// horizon tag_lookahead times what any walk from there pays before a frame that travels at that
// pace (travelling_frames.h), each frame before it priced as a second behind the pace.
#pragma once

#include <vector>

#include "motiongraph/synthesis/controller.h"
#include "motiongraph/synthesis/horizon_search.h"
#include "motiongraph/synthesis/synthesis_context.h"
#include "motiongraph/synthesis/travelling_frames.h"

namespace mg {

class SteerCost final : public FrameCost {
 public:
  // With a tag asked for and settings.tag_lookahead > 0, the context's costs to it are made (or
  // found in its cache). `context` and `input` must outlive the cost.
  // `from`: where the decision starts (the travel asked of a walk with no tag is counted from its
  // root; null: none asked).
  SteerCost(const SynthesisContext& context, const ControlInput& input, const ControllerSettings& settings,
            const SearchState* from = nullptr);

  double cost(int frame, const Vec2& root, const Vec2& facing, double arc_m, TagMask tags, bool* goal) const override;
  // Holding the travel, the search judges the direction the edit holds: each frame's heading.
  bool uses_heading() const override { return judge_travel_; }
  // A bridge costs the bridge penalty more unless it lands in the motion type asked for.
  double transition_cost(const GraphEdge& edge, const SearchState& from) const override;
  // Past the horizon: what is still to pay before the tag, the rest of the last edge's frames
  // first (its transition cost was paid as it started), weighted. A node the tag cannot be
  // reached from costs nothing more: in a strongly connected graph none reaches it then.
  double terminal_cost(int edge, size_t costed, double horizon_arc_m, const SearchState& end) const override;
  // Any walk from a node pays its cost to the tag, within the horizon or past it (weighted by at
  // most 1, a lower bound of both).
  double node_bound(const SearchState& state, int frames_left) const override;

 private:
  const SynthesisContext& context_;
  const ControlInput& input_;
  double penalty_;
  double transition_penalty_;
  double bridge_penalty_;
  bool judge_travel_;
  double lookahead_;
  double travel_penalty_ = 0.0;  // per metre behind, per frame (0: no travel asked)
  double travel_m_per_frame_ = 0.0;
  Vec2 start_root_ = Vec2::Zero();
  TagCostCache::Costs cost_to_tag_;  // for input_.tag; null: the horizon only
  // With no tag and a pace asked: the way to travelling frames past the horizon (travelling_frames.h).
  TravelCosts to_travel_;
  double travel_per_frame_ = 0.0;
};

}  // namespace mg
