// The distance stage's settings: an exact JSON round trip, a hash that follows every setting
// that changes the distances (and no other), and one failing input per reading rule.
#include "motiongraph/pipeline/distance_stage_settings.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

DistanceStageSettings sample() {
  DistanceStageSettings s;
  s.cloud.kind = PointCloudSettings::Kind::kJoints;
  s.cloud.ring_spacing_m = 0.2;
  s.cloud.ring_radius_m = 0.05;
  s.cloud.points_per_ring = 6;
  s.cloud.joint_weights = {{"head", 2.0}, {"lfoot", 0.5}};
  s.distance.window_frames = 12;
  s.distance.taper = DistanceSettings::Taper::kHann;
  s.continuation_radius = 7;
  return s;
}

TEST(DistanceStageSettings, JsonRoundTrip) {
  const DistanceStageSettings s = sample();
  const nlohmann::json json = s.to_json(12);
  EXPECT_EQ(json.at("cloud"), "joints");
  EXPECT_EQ(json.at("taper"), "hann");
  EXPECT_EQ(json.at("window"), 12);
  auto back = DistanceStageSettings::from_json(json);
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back->cloud.kind, s.cloud.kind);
  EXPECT_EQ(back->cloud.ring_spacing_m, s.cloud.ring_spacing_m);
  EXPECT_EQ(back->cloud.ring_radius_m, s.cloud.ring_radius_m);
  EXPECT_EQ(back->cloud.points_per_ring, s.cloud.points_per_ring);
  EXPECT_EQ(back->cloud.joint_weights, s.cloud.joint_weights);
  EXPECT_EQ(back->distance.window_frames, 12);
  EXPECT_EQ(back->distance.taper, s.distance.taper);
  EXPECT_EQ(back->continuation_radius, s.continuation_radius);
  EXPECT_EQ(back->to_json(12), json);
}

TEST(DistanceStageSettings, HashFollowsWhatChangesTheDistances) {
  const DistanceStageSettings s = sample();
  const std::uint64_t base = s.hash(12);
  EXPECT_EQ(base, sample().hash(12));
  EXPECT_NE(base, s.hash(13));
  DistanceStageSettings other = sample();
  other.cloud.joint_weights[0].second = 3.0;
  EXPECT_NE(base, other.hash(12));
  other = sample();
  other.distance.taper = DistanceSettings::Taper::kUniform;
  EXPECT_NE(base, other.hash(12));
  other = sample();
  other.continuation_radius = 8;
  EXPECT_NE(base, other.hash(12));
  // Tiles and threads change how the distances are computed, not what they are.
  other = sample();
  other.distance.tile_frames = 256;
  other.distance.threads = 3;
  EXPECT_EQ(base, other.hash(12));
}

TEST(DistanceStageSettings, FailingInputs) {
  const nlohmann::json json = sample().to_json(12);
  auto with = [&](const char* key, nlohmann::json value) {
    nlohmann::json changed = json;
    changed[key] = std::move(value);
    return changed;
  };
  nlohmann::json missing = json;
  missing.erase("ring_radius_m");
  const std::vector<std::pair<const char*, nlohmann::json>> cases = {
      {"an unknown cloud", with("cloud", "spheres")},
      {"an unknown taper", with("taper", "gauss")},
      {"a missing key", missing},
      {"a number of another type", with("window", "twelve")},
  };
  for (const auto& [rule, text] : cases) EXPECT_FALSE(DistanceStageSettings::from_json(text)) << rule;
}

TEST(DistanceStageSettings, Validate) {
  EXPECT_TRUE(DistanceStageSettings{}.validate());
  DistanceStageSettings s;
  s.continuation_radius = -2;
  EXPECT_FALSE(s.validate());
  s = {};
  s.cloud.points_per_ring = 0;
  EXPECT_FALSE(s.validate());
  s = {};
  s.distance.tile_frames = 0;
  EXPECT_FALSE(s.validate());
}

}  // namespace
}  // namespace mg
