// The features and settings of a graph file, for selecting its transitions again.
#include "motiongraph/evaluation/graph_rebuild.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "motiongraph/core/json_text.h"
#include "motiongraph/metric/point_cloud.h"
#include "motiongraph/pipeline/saved_settings.h"

namespace mg {

Result<GraphRebuild> prepare_graph_rebuild(const GraphFile& file, const std::string& file_name) {
  auto parsed = parse_json_text(file.settings_json, file_name);
  if (!parsed) return parsed.error();
  auto saved = SavedSettings::from_json(*parsed);
  if (!saved) return Error{file_name, 0, saved.error().message};
  GraphRebuild out;
  out.settings.transitions = saved->transitions;
  out.settings.spacing = saved->spacing;
  out.settings.bridges = saved->bridges;
  if (saved->connected_tags) {
    auto mask = tag_mask_of(file.database, *saved->connected_tags);
    if (!mask) return Error{file_name, 0, "connected_tags: " + mask.error().message};
    out.settings.connected_tags = *mask;
  } else {
    out.settings.connected_tags = motion_type_tags(file.database);
  }
  if (file.database.skeletons.empty()) return Error{file_name, 0, "the graph's database has no skeleton"};
  auto layout = make_cloud_layout(file.database.skeletons.front(), saved->distance_stage.cloud);
  if (!layout) return Error{file_name, 0, layout.error().message};
  const DistanceSettings& distance = saved->distance_stage.distance;
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
