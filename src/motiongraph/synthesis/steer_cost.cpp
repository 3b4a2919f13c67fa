#include "motiongraph/synthesis/steer_cost.h"

#include "motiongraph/synthesis/tag_distance.h"

namespace mg {

SteerCost::SteerCost(const SynthesisContext& context, const ControlInput& input, const ControllerSettings& settings,
                     const SearchState* from)
    : context_(context),
      input_(input),
      penalty_(settings.tag_penalty),
      transition_penalty_(settings.transition_penalty),
      bridge_penalty_(settings.bridge_penalty),
      judge_travel_(settings.heading_edit.hold_travel),
      lookahead_(settings.tag_lookahead) {
  if (input.tag == 0 && from != nullptr && from->has_last && settings.travel_mps > 0.0) {
    travel_penalty_ = settings.travel_penalty;
    travel_m_per_frame_ = settings.travel_mps / context.db->fps;
    start_root_ = from->last_root;
    if (lookahead_ > 0.0 && travel_penalty_ > 0.0) {
      // Past the horizon a frame that does not travel costs what a frame a second behind the
      // pace costs within it.
      travel_per_frame_ = travel_penalty_ * settings.travel_mps;
      to_travel_ = searched_costs_to_travel(context, settings.travel_mps, travel_per_frame_, transition_penalty_,
                                            bridge_penalty_);
    }
  }
  if (lookahead_ > 0.0 && input.tag != 0) {
    cost_to_tag_ = searched_costs_to_tag(context, {input.tag, penalty_, transition_penalty_, bridge_penalty_});
  }
}

double SteerCost::cost(int frame, const Vec2& root, const Vec2& facing, double, TagMask tags, bool*) const {
  double c = 1.0 - facing.dot(input_.direction);
  if (input_.tag != 0 && (tags & input_.tag) == 0) c += penalty_;
  if (travel_penalty_ > 0.0) {
    const double behind = travel_m_per_frame_ * (frame + 1) - (root - start_root_).dot(input_.direction);
    if (behind > 0.0) c += travel_penalty_ * behind;
  }
  return c;
}

double SteerCost::transition_cost(const GraphEdge& edge, const SearchState&) const {
  return transition_price(context_, edge, input_.tag, transition_penalty_, bridge_penalty_);
}

double SteerCost::terminal_cost(int edge, size_t costed, double, const SearchState& end) const {
  if (to_travel_.to_travel != nullptr) {
    const EdgeTrack& track = context_.tracks.edges[static_cast<size_t>(edge)];
    const auto marks = std::span<const TagMask>(*to_travel_.marks)
                           .subspan(static_cast<size_t>(track.first), static_cast<size_t>(track.count));
    return lookahead_ *
           cost_to_mark_after(marks, costed, end.node, kTravellingMark, travel_per_frame_, *to_travel_.to_travel);
  }
  if (cost_to_tag_ == nullptr) return 0.0;
  return lookahead_ * cost_to_tag_after(context_.tracks, edge, costed, end.node, input_.tag, penalty_, *cost_to_tag_);
}

double SteerCost::node_bound(const SearchState& state, int) const {
  // (The way to travelling frames bounds nothing: within the horizon a frame that stands may cost
  // less than its price past it, while the walk is still ahead of the pace.)
  if (cost_to_tag_ == nullptr) return 0.0;
  const double beyond = (*cost_to_tag_)[static_cast<size_t>(state.node)];
  return beyond < 0.0 ? 0.0 : lookahead_ * beyond;
}

}  // namespace mg
