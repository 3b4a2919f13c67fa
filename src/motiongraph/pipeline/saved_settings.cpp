// A graph file's record of its build settings, written and read in one place.
#include "motiongraph/pipeline/saved_settings.h"

#include <fmt/format.h>

#include "motiongraph/graph/bridges.h"

namespace mg {

nlohmann::json SavedSettings::to_json() const {
  nlohmann::json json = {{"distance", distance_stage.to_json(distance_stage.distance.window_frames)},
                         {"threshold", transitions.threshold},
                         {"threshold_quantile", transitions.threshold_quantile},
                         {"threshold_mode", threshold_mode},
                         {"max_threshold", transitions.max_threshold},
                         {"locality_radius", transitions.locality_radius},
                         {"per_tag_thresholds", transitions.per_tag_thresholds},
                         {"min_piece_frames", spacing.min_piece_frames},
                         {"out_window_frames", spacing.out_window_frames},
                         {"max_out", spacing.max_out},
                         {"bridges_per_tag_pair", bridges.per_tag_pair},
                         {"max_bridge_distance", bridges.max_distance},
                         {"bridge_blend_factor", bridges.max_blend_factor},
                         {"fps", fps}};
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
    TransitionSettings& t = out.transitions;
    t.threshold = json.at("threshold").get<double>();
    t.threshold_quantile = json.at("threshold_quantile").get<double>();
    t.locality_radius = json.at("locality_radius").get<int>();
    t.per_tag_thresholds = json.value("per_tag_thresholds", true);
    t.max_threshold = json.value("max_threshold", -1.0);
    // Files written before transitions were spaced had none.
    out.spacing.min_piece_frames = json.value("min_piece_frames", 0);
    out.spacing.max_out = json.value("max_out", 0);
    out.spacing.out_window_frames = json.value("out_window_frames", -1);
    out.bridges.per_tag_pair = json.value("bridges_per_tag_pair", BridgeSettings{}.per_tag_pair);
    out.bridges.max_distance = json.value("max_bridge_distance", -1.0);
    // Files written before bridges blended longer blended them as transitions.
    out.bridges.max_blend_factor = json.value("bridge_blend_factor", 1.0);
    if (json.contains("connected_tags")) out.connected_tags = json.at("connected_tags").get<std::vector<std::string>>();
  } catch (const nlohmann::json::exception& e) {
    return Error{"", 0, fmt::format("the graph's settings are not what build writes: {}", e.what())};
  }
  return out;
}

}  // namespace mg
