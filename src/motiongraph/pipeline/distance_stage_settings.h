// What decides the distance stage's result (Kovar et al. 2002, section 3.1; DESIGN.md 3): the
// point clouds, the window and its taper, and the pairs of a clip simply continuing that are
// left out. Its JSON form is the one definition the distance cache key, the build report's
// "distance_settings" and the graph file's saved settings all use; reading it back fails on an
// unknown cloud or taper, or a missing key.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "motiongraph/core/error.h"
#include "motiongraph/metric/frame_features.h"
#include "motiongraph/metric/point_cloud.h"

namespace mg {

struct DistanceStageSettings {
  PointCloudSettings cloud;
  DistanceSettings distance;     // window_frames 0: a third of a second at the database's rate
  int continuation_radius = -1;  // frames; -1: the window

  Status validate() const;

  // {"cloud", "ring_spacing_m", "ring_radius_m", "points_per_ring", "joint_weights", "window",
  // "taper", "continuation_radius"}, with the window as resolved for the database (`window`
  // frames). Tiles and threads do not change the result and are left out.
  nlohmann::json to_json(int window) const;
  // The settings to_json() wrote; distance.window_frames is the window it recorded.
  static Result<DistanceStageSettings> from_json(const nlohmann::json& json);
  // A 64-bit hash of to_json(window)'s text.
  std::uint64_t hash(int window) const;
};

// "rings" / "joints" and "uniform" / "hann": the names the CLI takes and the JSON form holds.
const char* cloud_kind_name(PointCloudSettings::Kind kind);
Result<PointCloudSettings::Kind> parse_cloud_kind(const std::string& name);
const char* taper_name(DistanceSettings::Taper taper);
Result<DistanceSettings::Taper> parse_taper(const std::string& name);

}  // namespace mg
