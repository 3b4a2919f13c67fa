#include "motiongraph/synthesis/path_cost.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

#include "motiongraph/synthesis/tag_distance.h"

namespace mg {

PathCost::PathCost(const SynthesisContext& context, const FloorPath& path, std::vector<TagMask> segment_masks,
                   const PathSynthesisSettings& settings)
    : context_(context),
      path_(path),
      masks_(std::move(segment_masks)),
      penalty_(settings.tag_penalty_m2),
      max_step_(settings.lower_bound ? context.tracks.max_root_step_m : 0.0),
      min_step_(settings.min_speed_mps / context.db->fps),
      behind_penalty_(settings.behind_penalty_m),
      transition_penalty_(settings.transition_penalty_m2),
      bridge_penalty_(settings.bridge_penalty_m2),
      lookahead_(settings.tag_lookahead) {
  // The arc lengths where what is asked for may change, and what is asked for between them.
  for (const FloorPath::SegmentSpan& span : path.segment_spans()) {
    const TagMask wanted = span.segment < 0 ? TagMask{0} : masks_[static_cast<size_t>(span.segment)];
    if (!regions_.empty() && regions_.back().wanted == wanted) continue;
    Region region{span.from_m, wanted, nullptr};
    if (wanted != 0 && lookahead_ > 0.0) {
      region.to_tag = searched_costs_to_tag(context, {wanted, penalty_, transition_penalty_, bridge_penalty_});
    }
    regions_.push_back(region);
  }
}

double PathCost::cost(int frame, const Vec2& root, const Vec2&, double arc_m, TagMask tags, bool* goal) const {
  int segment = -1;
  return frame_cost(frame, root, arc_m, tags, goal, segment);
}

bool PathCost::add_costs(const PlayedFrames& frames, double bound, double* total, bool* goal) const {
  int segment = -1;
  return add_frame_costs(frames.roots.size(), bound, total, goal, [&](size_t p, bool* reached) {
    return frame_cost(frames.first_frame + static_cast<int>(p), frames.roots[p], frames.arcs_m[p], frames.tags[p],
                      reached, segment);
  });
}

double PathCost::frame_cost(int frame, const Vec2& root, double arc_m, TagMask tags, bool* goal, int& segment) const {
  double c = (viewed(root) - path_.point_at(arc_m, segment)).squaredNorm();
  // Behind the slowest schedule allowed: metres not covered since the search began.
  const double behind = search_arc_m_ + min_step_ * (frame + 1) - arc_m;
  if (behind > 0.0) c += behind_penalty_ * behind;
  const TagMask wanted = wanted_at(arc_m);
  if (wanted != 0 && (tags & wanted) == 0) c += penalty_;
  if (arc_m >= path_.length_m()) *goal = true;
  return c;
}

double PathCost::remaining_bound(int frames_left, const Vec2& root, double arc_m) const {
  if (!(max_step_ > 0.0)) return 0.0;
  const double d = (viewed(root) - path_.point_at(arc_m)).norm();
  const double before_end = (path_.length_m() - arc_m) / max_step_;
  double bound = 0.0;
  for (int m = 1; m <= frames_left && m < before_end; ++m) {
    const double gap = d - 2.0 * m * max_step_;
    if (gap <= 0.0) break;
    bound += gap * gap;
  }
  return bound;
}

double PathCost::transition_cost(const GraphEdge& edge, const SearchState& from) const {
  return transition_price(context_, edge, wanted_at(from.arc_m), transition_penalty_, bridge_penalty_);
}

double PathCost::terminal_cost(int edge, size_t costed, double horizon_arc_m, const SearchState& end) const {
  const Region& region = *region_at(horizon_arc_m);
  if (region.to_tag == nullptr) return 0.0;
  return lookahead_ *
         cost_to_tag_after(context_.tracks, edge, costed, end.node, region.wanted, penalty_, *region.to_tag);
}

double PathCost::node_bound(const SearchState& state, int frames_left) const {
  if (!(max_step_ > 0.0)) return 0.0;
  const auto at = region_at(state.arc_m);
  if (at->to_tag == nullptr) return 0.0;
  const double c = (*at->to_tag)[static_cast<size_t>(state.node)];
  if (!(c > 0.0)) return 0.0;
  const double length = path_.length_m();
  const double region_end = std::next(at) == regions_.end() ? length : std::min(std::next(at)->from_m, length);
  // The frames j = 1, 2, ... whose root has covered at most arc + j max_step < region_end (a
  // ratio within 1e-6 above a whole number n taken for n: the arcs are sums of rounded steps).
  const double in_region = std::ceil((region_end - state.arc_m) / max_step_ - 1e-6) - 1.0;
  double bound = lookahead_ * c;
  if (in_region < frames_left) bound = std::min(bound, penalty_ * std::max(0.0, in_region));
  return bound;
}

void PathCost::set_view(const FloorTransform& view) {
  c_ = std::cos(view.yaw_rad);
  s_ = std::sin(view.yaw_rad);
  x_ = view.x_m;
  z_ = view.z_m;
}

TagMask PathCost::wanted_at(double s) const {
  const int segment = path_.segment_at(s);
  return segment < 0 ? TagMask{0} : masks_[static_cast<size_t>(segment)];
}

std::vector<PathCost::Region>::const_iterator PathCost::region_at(double arc_m) const {
  const auto after = std::upper_bound(regions_.begin(), regions_.end(), arc_m,
                                      [](double s, const Region& r) { return s < r.from_m; });
  return after == regions_.begin() ? after : std::prev(after);
}

}  // namespace mg
