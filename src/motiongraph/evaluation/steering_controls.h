// Steering controls as a user gives them (a heading, a motion type, rest) turned into the
// controller's input (synthesis/controller.h), telling once what the graph cannot give: a motion
// type it plays in no frame or hardly (unplayable_tag), and rest where no clip of the graph ends
// standing still. A stop the graph can hardly play, or has no tag for, is rest (stop_means_rest)
// where the graph has a clip to rest at. The CLI's steer, the
// Python Controller and the studio's steering sessions read their controls with it, so that they
// treat a stop alike and warn alike; what it said is also their reports' "warnings".
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/synthesis/controller.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

struct SteeringControl {
  double heading_deg = 0.0;  // bearing, clockwise from north (-z)
  std::string tag;           // a motion tag of the graph; empty: any motion
  bool rest = false;         // come to rest
};

// Whether `next`, set on `controller`, asks to turn while the character stands still at rest (more
// than a degree from the heading in force, rest asked of both): not heard, as it turns only on its
// way to rest and as it starts off.
bool turns_at_rest(const ControlInput& next, const Controller& controller);

class SteeringControls {
 public:
  // `context` must outlive this.
  explicit SteeringControls(const SynthesisContext& context) : context_(&context) {}

  // The controller's input for `control`; a new warning (at most one per motion type, and one for
  // rest) is appended to warnings(), starting with `who` ("the control at 4 s"). An unknown tag
  // or a heading that is not finite is an error.
  Result<ControlInput> input(const SteeringControl& control, std::string_view who);

  // Says once (appended to warnings(); true when said now) that a turn asked with rest while the
  // character stands still (turns_at_rest) is not heard, starting with `who`.
  bool turn_at_rest(std::string_view who);

  // Every warning said so far, in order.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  const SynthesisContext* context_;
  // Per tag asked, what unplayable_tag says of it and whether it means rest (found once: they run
  // over the graph's frames and edges, and a game steps many times a second).
  struct TagNote {
    std::optional<std::string> unplayable;
    bool rest = false;
    bool warned = false;
  };
  std::map<std::string, TagNote> tags_;
  bool warned_rest_ = false;
  bool warned_stop_ = false;  // 'stop' asked of a graph without the tag
  bool warned_turn_ = false;  // a turn asked at rest
  std::vector<std::string> warnings_;
};

}  // namespace mg
