#include "motiongraph/pipeline/build_options.h"

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "motiongraph/core/file_extension.h"
#include "motiongraph/core/text.h"
#include "motiongraph/motion/in_place.h"
#include "motiongraph/motion/up_axis.h"

namespace mg {

Result<BuildSettings> build_settings_from(const BuildOptions& o) {
  BuildSettings s;
  s.distance_stage.cloud = o.cloud_settings;
  s.distance_stage.distance = o.distance;
  s.exhaustive = o.exhaustive;
  s.pruned_from_frames = o.pruned_from;
  if (o.tile_frames != 0) {
    s.distance_stage.distance.tile_frames = o.tile_frames;
    s.pruned.tile_frames = o.tile_frames;
  }
  s.distance_stage.continuation_radius = o.continuation_radius;
  auto cloud = parse_cloud_kind(o.cloud);
  if (!cloud) return Error{"", 0, fmt::format("--cloud must be 'rings' or 'joints', not '{}'", o.cloud)};
  s.distance_stage.cloud.kind = *cloud;
  for (const std::string& item : o.joint_weights) {
    const size_t eq = item.find('=');
    char* end = nullptr;
    const double weight = eq == std::string::npos ? -1.0 : std::strtod(item.c_str() + eq + 1, &end);
    if (eq == std::string::npos || end == item.c_str() + eq + 1 || *end != '\0') {
      return Error{"", 0, fmt::format("--joint-weight '{}' is not NAME=WEIGHT", item)};
    }
    s.distance_stage.cloud.joint_weights.emplace_back(item.substr(0, eq), weight);
  }
  auto taper = parse_taper(o.taper);
  if (!taper) return Error{"", 0, fmt::format("--taper must be 'uniform' or 'hann', not '{}'", o.taper)};
  s.distance_stage.distance.taper = *taper;
  // The threshold: chosen from the data (auto), a quantile of all pairs, D, or an RMS in cm.
  s.transitions = o.transitions;
  if (o.quantile) {  // checked with the settings: in (0, 1]
    if (o.threshold != "auto") return Error{"", 0, "give --threshold or --threshold-quantile, not both"};
    s.threshold_mode = ThresholdMode::kQuantile;
    s.threshold_value = *o.quantile;
  } else if (o.threshold != "auto") {
    std::string text = o.threshold;
    s.threshold_mode = ThresholdMode::kDistance;
    if (text.size() > 2 && text.compare(text.size() - 2, 2, "cm") == 0) {
      s.threshold_mode = ThresholdMode::kRmsCm;
      text.resize(text.size() - 2);
    }
    const std::optional<double> value = parse_finite(text);
    if (!value || *value < 0.0) {
      return Error{"", 0, fmt::format("--threshold must be 'auto', a distance D >= 0 or an RMS distance such as "
                                      "'4cm', not {}", mg::quoted(o.threshold))};
    }
    s.threshold_value = *value;
  }
  s.choice = o.choice;
  s.path_check = !o.no_path_check;
  s.path_check_settings = o.path_check;
  s.path_check_settings.mirrored = !o.no_path_check_mirror;
  s.spacing = o.spacing;
  s.bridges = o.bridges;
  s.max_bridge_rms_cm = o.max_bridge_cm;
  s.connect_tags = o.connect_tags;
  s.ignore_tags = o.ignore_tags;
  s.exports = o.exports;
  s.shared = o.shared;
  DatabaseSettings& db = s.database;
  db.fps = o.fps;
  db.prefer_manifest_fps = !o.fps_given;
  if (!o.asf.empty()) db.asf_path = o.asf;
  db.bvh_metres_per_unit = o.scale;
  if (!o.up_axis.empty()) {
    db.up_axis = parse_up_axis(o.up_axis);
    if (!db.up_axis) return Error{"", 0, "--up-axis must be y or z, not " + o.up_axis};
  }
  auto travel = parse_travel_source(o.travel);
  if (!travel) return Error{"", 0, "--travel must be auto, root or feet, not " + o.travel};
  db.travel = *travel;
  db.input_fps = o.input_fps;
  db.keep_rest_frames = o.keep_rest_frames;
  db.cmu_tags = !o.no_cmu_tags;
  db.name_tags = !o.no_name_tags;
  if (o.whole_clip_tags) db.travel_tags.min_speed_mps = 0.0;
  db.loops = !o.no_loops;
  auto mirror = parse_mirroring(o.mirror);
  if (!mirror) return Error{"", 0, "--mirror must be auto, on or off, not " + o.mirror};
  db.mirror = *mirror;
  // A loop goes on past its end as far as a transition's window reaches, and a frame.
  if (o.distance.window_frames > 0) db.loop_overlap_frames = o.distance.window_frames + 1;
  db.cmu_index_path = o.cmu_index;
  if (!o.feet.empty()) {
    auto feet = parse_foot_joint_names(o.feet);
    if (!feet) return Error{"", 0, "--feet: " + feet.error().message};
    db.foot_names = *feet;
  }
  if (auto valid = s.validate(); !valid) return valid.error();
  return s;
}

Status check_graph_output(const std::string& path) {
  if (lower_extension(path) != ".mgraph") return Error{path, 0, "the graph file must end in .mgraph"};
  return Ok{};
}

}  // namespace mg
