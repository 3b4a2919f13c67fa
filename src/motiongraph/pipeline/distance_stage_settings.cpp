// The distance stage's settings and their JSON form.
#include "motiongraph/pipeline/distance_stage_settings.h"

#include <fmt/format.h>

#include "motiongraph/core/json_text.h"
#include "motiongraph/core/text.h"
#include "motiongraph/graph/graph_file.h"

namespace mg {

Status DistanceStageSettings::validate() const {
  if (auto s = cloud.validate(); !s) return s;
  if (auto s = distance.validate(); !s) return s;
  if (continuation_radius < -1) return Error{"", 0, "continuation radius must be >= 0 (or -1 for the window)"};
  return Ok{};
}

nlohmann::json DistanceStageSettings::to_json(int window) const {
  nlohmann::json weights = nlohmann::json::object();
  for (const auto& [name, weight] : cloud.joint_weights) weights[name] = weight;
  return {{"cloud", cloud_kind_name(cloud.kind)},
          {"ring_spacing_m", cloud.ring_spacing_m},
          {"ring_radius_m", cloud.ring_radius_m},
          {"points_per_ring", cloud.points_per_ring},
          {"joint_weights", weights},
          {"window", window},
          {"taper", taper_name(distance.taper)},
          {"continuation_radius", continuation_radius}};
}

Result<DistanceStageSettings> DistanceStageSettings::from_json(const nlohmann::json& json) {
  DistanceStageSettings out;
  try {
    auto kind = parse_cloud_kind(json.at("cloud").get<std::string>());
    if (!kind) return kind.error();
    out.cloud.kind = *kind;
    out.cloud.ring_spacing_m = json.at("ring_spacing_m").get<double>();
    out.cloud.ring_radius_m = json.at("ring_radius_m").get<double>();
    out.cloud.points_per_ring = json.at("points_per_ring").get<int>();
    for (const auto& [name, weight] : json.at("joint_weights").items()) {
      out.cloud.joint_weights.emplace_back(name, weight.get<double>());
    }
    out.distance.window_frames = json.at("window").get<int>();
    auto taper = parse_taper(json.at("taper").get<std::string>());
    if (!taper) return taper.error();
    out.distance.taper = *taper;
    out.continuation_radius = json.value("continuation_radius", -1);
  } catch (const nlohmann::json::exception& e) {
    return Error{"", 0, fmt::format("the distance settings are not what build writes: {}", e.what())};
  }
  return out;
}

std::uint64_t DistanceStageSettings::hash(int window) const { return content_key(json_text(to_json(window))); }

const char* cloud_kind_name(PointCloudSettings::Kind kind) {
  return kind == PointCloudSettings::Kind::kJoints ? "joints" : "rings";
}

Result<PointCloudSettings::Kind> parse_cloud_kind(const std::string& name) {
  if (name == "rings") return PointCloudSettings::Kind::kBoneRings;
  if (name == "joints") return PointCloudSettings::Kind::kJoints;
  return Error{"", 0, fmt::format("the point cloud must be 'rings' or 'joints', not {}", mg::quoted(name))};
}

const char* taper_name(DistanceSettings::Taper taper) {
  return taper == DistanceSettings::Taper::kHann ? "hann" : "uniform";
}

Result<DistanceSettings::Taper> parse_taper(const std::string& name) {
  if (name == "uniform") return DistanceSettings::Taper::kUniform;
  if (name == "hann") return DistanceSettings::Taper::kHann;
  return Error{"", 0, fmt::format("the taper must be 'uniform' or 'hann', not {}", mg::quoted(name))};
}

}  // namespace mg
