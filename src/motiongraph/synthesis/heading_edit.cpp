#include "motiongraph/synthesis/heading_edit.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "motiongraph/synthesis/travel_heading.h"

namespace mg {

Status HeadingEditSettings::validate() const {
  if (!std::isfinite(max_turn_deg_per_m) || max_turn_deg_per_m < 0.0) {
    return Error{"", 0, "heading edit: the turning it may add must be finite and >= 0 degrees per metre"};
  }
  if (!std::isfinite(turn_distance_m) || !(turn_distance_m > 0.0)) {
    return Error{"", 0, "heading edit: the turning distance must be > 0 metres"};
  }
  if (!std::isfinite(window_s) || window_s < 0.0) {
    return Error{"", 0, "heading edit: the facing's window must be finite and >= 0 seconds"};
  }
  if (!std::isfinite(travel_from_mps) || !std::isfinite(travel_full_mps) || travel_from_mps < 0.0 ||
      !(travel_full_mps > travel_from_mps)) {
    return Error{"", 0, "heading edit: the travel speeds must be finite, >= 0 and the second above the first"};
  }
  return Ok{};
}

HeadingEdit::HeadingEdit(const HeadingEditSettings& settings, double fps, const Vec3& forward_axis)
    : settings_(settings),
      forward_axis_(forward_axis),
      fps_(fps),
      half_window_(std::max(0, static_cast<int>(std::lround(0.5 * settings.window_s * fps)))) {}

FloorTransform HeadingEdit::apply(Motion& motion, int first, const Vec2* previous_root,
                                  std::span<const Vec2> planned_facings, std::span<const Vec2> planned_roots,
                                  const Vec2& direction) {
  FloorTransform move;
  if (first >= motion.frame_count) return move;
  const bool steer = direction.norm() > 1e-6;
  const double limit = settings_.max_turn_deg_per_m * std::numbers::pi / 180.0;
  // The facings of the frames played before, as they would play under the present placement
  // without the turning added since they played (turned on by what was added after them, which
  // the present placement holds): with the plan, one motion.
  // The root's floor steps likewise (each from the frame before; the first planned one from
  // previous_root), for the direction of travel over the window.
  std::vector<Vec2> window, steps;
  window.reserve(played_.size() + planned_facings.size());
  steps.reserve(window.capacity());
  for (const PlayedFrame& played : played_) {
    const FloorTransform since{total_added_ - played.added, 0.0, 0.0};
    window.push_back(turn(since, played.facing));
    steps.push_back(turn(since, played.step));
  }
  const int past = static_cast<int>(played_.size());
  window.insert(window.end(), planned_facings.begin(), planned_facings.end());
  for (size_t k = 0; k < planned_facings.size(); ++k) {
    const bool known = k < planned_roots.size() && (k > 0 || previous_root != nullptr);
    steps.push_back(known ? Vec2(planned_roots[k] - (k > 0 ? planned_roots[k - 1] : *previous_root)) : Vec2::Zero());
  }
  std::vector<Vec2> prefix(window.size() + 1, Vec2::Zero()), travel_prefix(window.size() + 1, Vec2::Zero());
  for (size_t i = 0; i < window.size(); ++i) {
    prefix[i + 1] = prefix[i] + window[i];
    travel_prefix[i + 1] = travel_prefix[i] + steps[i];
  }
  double added = 0.0;  // since frame first - 1, whose placement the frames have
  Vec2 last_unedited = previous_root != nullptr ? *previous_root : Vec2::Zero();
  Vec2 last_edited = last_unedited;
  bool has_last = previous_root != nullptr;
  for (int f = first; f < motion.frame_count; ++f) {
    Vec3& root = motion.translations(f)[0];
    const Vec2 at(root.x(), root.z());
    const Vec2 step = has_last ? Vec2(at - last_unedited) : Vec2::Zero();
    // 1-2. The facing judged at f, and the turn that puts it on the direction asked for.
    const int centre = past + (f - first);
    const int lo = std::max(0, centre - half_window_);
    const int hi = std::min(static_cast<int>(window.size()), centre + half_window_ + 1);
    Vec2 mean = hi > lo ? Vec2(prefix[hi] - prefix[lo]) : Vec2::Zero();
    // The steps lo + 1 .. end - 1 span the frames lo .. end - 1, as far as the roots are known.
    const int end = std::min(hi, past + static_cast<int>(planned_roots.size()));
    const Vec2 travel = end > lo + 1 ? Vec2(travel_prefix[end] - travel_prefix[lo + 1]) : Vec2::Zero();
    // A window cut short (the motion's first frames, the plan's end) counts as far as it spans.
    const double spanned = half_window_ > 0 ? (end - lo - 1) / (2.0 * half_window_) : 1.0;
    const double share = travel_share(settings_, mean, travel, (end - lo - 1) / fps_, spanned);
    if (share > 0.0) mean = (1.0 - share) * mean.normalized() + share * travel.normalized();
    stats_.travel_share += share;
    if (steer && mean.norm() > 1e-6 && step.norm() > 0.0) {
      const double wanted = yaw_between(mean.normalized(), direction.normalized());
      const double ds = step.norm();
      const double left = std::remainder(wanted - added, 2.0 * std::numbers::pi);  // the short way round
      const double change = std::clamp(left * std::min(1.0, ds / settings_.turn_distance_m), -limit * ds, limit * ds);
      stats_.max_rate_deg_per_m = std::max(stats_.max_rate_deg_per_m, std::abs(change) / ds * 180.0 / std::numbers::pi);
      stats_.added_turn_rad += std::abs(change);
      added += change;
    }
    // 3. The frame moved rigidly: turned by the angle added, its step from the last frame too.
    move.yaw_rad = added;
    const Vec2 edited = has_last ? Vec2(last_edited + turn(move, step)) : at;
    const Vec2 turned_at = turn(move, at);
    move.x_m = edited.x() - turned_at.x();
    move.z_m = edited.y() - turned_at.y();
    root = move.apply(root);
    Quat& rotation = motion.rotations(f)[0];
    rotation = (move.rotation() * rotation).normalized();
    last_unedited = at;
    last_edited = edited;
    has_last = true;
    played_.push_back({facing_on_floor(rotation, forward_axis_), turn(move, step), total_added_ + added});
    while (static_cast<int>(played_.size()) > half_window_) played_.pop_front();
    ++stats_.frames;
  }
  total_added_ += added;
  return move;
}

}  // namespace mg
