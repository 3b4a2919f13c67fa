// A graph file's record of its build settings, written and read in one place.
#include "motiongraph/pipeline/saved_settings.h"

#include <fmt/format.h>

#include "motiongraph/graph/bridges.h"

namespace mg {

nlohmann::json SavedSettings::to_json() const {
  // One flat object, as graph files have always had it: each part's keys are its own JSON form.
  nlohmann::json json = transitions;
  json.update(nlohmann::json(spacing.resolved(distance_stage.distance.window_frames)));
  json.update(nlohmann::json(bridges));
  json["distance"] = distance_stage.to_json(distance_stage.distance.window_frames);
  json["threshold_mode"] = threshold_mode;
  json["fps"] = fps;
  if (connected_tags) json["connected_tags"] = *connected_tags;
  return json;
}

Result<SavedSettings> SavedSettings::from_json(const nlohmann::json& json) {
  SavedSettings out;
  try {
    auto distance = DistanceStageSettings::from_json(json.at("distance"));
    if (!distance) return distance.error();
    out.distance_stage = std::move(*distance);
    out.fps = json.value("fps", 0.0);
    out.threshold_mode = json.value("threshold_mode", std::string());
    out.transitions = json.get<TransitionSettings>();
    out.spacing = json.get<TransitionSpacing>();
    out.bridges = json.get<BridgeSettings>();
    if (json.contains("connected_tags")) out.connected_tags = json.at("connected_tags").get<std::vector<std::string>>();
  } catch (const nlohmann::json::exception& e) {
    return Error{"", 0, fmt::format("the graph's settings are not what build writes: {}", e.what())};
  }
  return out;
}

}  // namespace mg
