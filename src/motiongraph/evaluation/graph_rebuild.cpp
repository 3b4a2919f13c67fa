// The features and settings of a graph file, for selecting its transitions again.
#include "motiongraph/evaluation/graph_rebuild.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "motiongraph/core/json_text.h"
#include "motiongraph/metric/point_cloud.h"

namespace mg {

Result<GraphRebuild> prepare_graph_rebuild(const GraphFile& file, const std::string& file_name) {
  auto parsed = parse_json_text(file.settings_json, file_name);
  if (!parsed) return parsed.error();
  const nlohmann::json& settings = *parsed;
  GraphRebuild out;
  PointCloudSettings cloud;
  DistanceSettings distance;
  try {
    const nlohmann::json& d = settings.at("distance");
    const std::string kind = d.at("cloud").get<std::string>();
    if (kind == "joints") {
      cloud.kind = PointCloudSettings::Kind::kJoints;
    } else if (kind != "rings") {
      return Error{file_name, 0, fmt::format("unknown point cloud '{}' in the graph's settings", kind)};
    }
    cloud.ring_spacing_m = d.at("ring_spacing_m").get<double>();
    cloud.ring_radius_m = d.at("ring_radius_m").get<double>();
    cloud.points_per_ring = d.at("points_per_ring").get<int>();
    for (const auto& [name, weight] : d.at("joint_weights").items()) cloud.joint_weights.emplace_back(name, weight.get<double>());
    distance.window_frames = d.at("window").get<int>();
    distance.taper = d.at("taper").get<std::string>() == "hann" ? DistanceSettings::Taper::kHann
                                                                 : DistanceSettings::Taper::kUniform;
    TransitionSettings& t = out.settings.transitions;
    t.threshold = settings.at("threshold").get<double>();
    t.threshold_quantile = settings.at("threshold_quantile").get<double>();
    t.locality_radius = settings.at("locality_radius").get<int>();
    t.per_tag_thresholds = settings.value("per_tag_thresholds", true);
    t.max_threshold = settings.value("max_threshold", -1.0);
    // Files written before transitions were spaced had none.
    TransitionSpacing& spacing = out.settings.spacing;
    spacing.min_piece_frames = settings.value("min_piece_frames", 0);
    spacing.max_out = settings.value("max_out", 0);
    spacing.out_window_frames = settings.value("out_window_frames", -1);
    out.settings.bridges.per_tag_pair = settings.value("bridges_per_tag_pair", BridgeSettings{}.per_tag_pair);
    if (settings.contains("connected_tags")) {
      const auto names = settings.at("connected_tags").get<std::vector<std::string>>();
      auto mask = tag_mask_of(file.database, names);
      if (!mask) return Error{file_name, 0, "connected_tags: " + mask.error().message};
      out.settings.connected_tags = *mask;
    } else {
      out.settings.connected_tags = motion_type_tags(file.database);
    }
  } catch (const nlohmann::json::exception& e) {
    return Error{file_name, 0, fmt::format("the graph's settings are not what build writes: {}", e.what())};
  }
  if (file.database.skeletons.empty()) return Error{file_name, 0, "the graph's database has no skeleton"};
  auto layout = make_cloud_layout(file.database.skeletons.front(), cloud);
  if (!layout) return Error{file_name, 0, layout.error().message};
  auto features = make_frame_features(file.database, *layout, distance);
  if (!features) return Error{file_name, 0, features.error().message};
  if (features->window != file.candidates.window) {
    return Error{file_name, 0, fmt::format("the settings give a window of {} frames, the candidates {}",
                                           features->window, file.candidates.window)};
  }
  out.features = std::move(*features);
  out.distance = distance;
  return out;
}

}  // namespace mg
