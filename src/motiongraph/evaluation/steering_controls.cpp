#include "motiongraph/evaluation/steering_controls.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "motiongraph/database/travel_tags.h"
#include "motiongraph/evaluation/synthesis_run.h"

namespace mg {

Result<ControlInput> SteeringControls::input(const SteeringControl& control, std::string_view who) {
  if (!std::isfinite(control.heading_deg)) {
    return Error{"", 0, fmt::format("{}: the heading must be finite, not {}", who, control.heading_deg)};
  }
  ControlInput in;
  in.direction = bearing_direction(control.heading_deg);
  in.rest = control.rest;
  if (!control.tag.empty()) {
    auto mask = context_->tag_mask(control.tag);
    // A stop asked of a graph with no such tag (most libraries tag none): rest where it can; where
    // no clip ends standing still, any motion, as rest is not heard there.
    if (!mask && is_stop_tag(control.tag)) {
      const bool can_rest = !context_->rest().empty();
      if (!warned_stop_) {
        warned_stop_ = true;
        warnings_.push_back(fmt::format(
            "{} asks for 'stop', which is not a motion tag of this graph; {}", who,
            can_rest ? "the character comes to rest instead, at the end of a clip that ends standing still"
                     : "nor does any clip of the graph end standing still to rest at: the character goes on"));
      }
      in.rest = can_rest;
      return in;
    }
    if (!mask) return mask.error();
    const std::string name = context_->db->tag_names_of(*mask).front();  // the graph's spelling
    auto [note, inserted] = tags_.try_emplace(name);
    if (inserted) {
      note->second.unplayable = unplayable_tag(*context_, name);
      note->second.rest = stop_means_rest(*context_, name);
    }
    TagNote& tag = note->second;
    if (tag.unplayable && !tag.warned) {
      tag.warned = true;
      warnings_.push_back(fmt::format(
          "{} asks for {}{}", who, *tag.unplayable,
          tag.rest ? "; the character comes to rest instead, at the end of a clip that ends standing still" : ""));
    }
    in.rest = in.rest || tag.rest;
    if (!in.rest) in.tag = *mask;
  }
  if (in.rest && context_->rest().empty() && !warned_rest_) {
    warned_rest_ = true;
    warnings_.push_back(
        fmt::format("{} asks to rest, but no clip of the graph ends standing still: the character goes on", who));
  }
  return in;
}

bool turns_at_rest(const ControlInput& next, const Controller& controller) {
  return next.rest && controller.input().rest && controller.still() &&
         next.direction.dot(controller.input().direction) < std::cos(std::numbers::pi / 180.0);
}

bool SteeringControls::turn_at_rest(std::string_view who) {
  if (warned_turn_) return false;
  warned_turn_ = true;
  warnings_.push_back(fmt::format("{} asks to turn while the character stands at rest, which it does not: it turns "
                                  "on its way to rest and as it starts off (when asked to move)",
                                  who));
  return true;
}

}  // namespace mg
