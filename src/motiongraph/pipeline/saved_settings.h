// The record a graph file keeps of how it was built (GraphFile::settings_json): the distance
// stage's settings (distance_stage_settings.h) and the transition, spacing, bridge and tag
// settings as build resolved them (the threshold it chose, the locality radius, the connected
// motion types by name). What eval and the studio need to select transitions again as build
// did (evaluation/graph_rebuild.h). Reading accepts files written before spacing, bridges or
// connected tags were recorded, or before bridges were capped and blended longer (then as long as a transition): what a file does not record takes build's defaults.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/bridges.h"
#include "motiongraph/graph/transition_selection.h"
#include "motiongraph/graph/transition_spacing.h"
#include "motiongraph/pipeline/distance_stage_settings.h"

namespace mg {

struct SavedSettings {
  DistanceStageSettings distance_stage;  // distance.window_frames: the window as resolved
  double fps = 0.0;                      // the database's rate
  std::string threshold_mode;            // "auto", "quantile", "distance" or "rms_cm"
  TransitionSettings transitions;        // threshold, quantile and locality radius as selected
  TransitionSpacing spacing;
  BridgeSettings bridges;  // max_distance as D (-1: no cap)
  // The motion types kept connected; nullopt in files that do not record them.
  std::optional<std::vector<std::string>> connected_tags;

  nlohmann::json to_json() const;
  // Fails (file name left empty) when a key build always writes is missing or has another type.
  static Result<SavedSettings> from_json(const nlohmann::json& json);
};

}  // namespace mg
