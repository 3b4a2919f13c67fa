// A graph file's saved settings: an exact round trip, and the defaults of older files.
#include "motiongraph/pipeline/saved_settings.h"

#include <gtest/gtest.h>

#include "motiongraph/graph/bridges.h"

namespace mg {
namespace {

TEST(SavedSettings, RoundTrip) {
  SavedSettings s;
  s.distance_stage.distance.window_frames = 10;
  s.distance_stage.cloud.joint_weights = {{"head", 2.0}};
  s.fps = 30.0;
  s.threshold_mode = "rms_cm";
  s.transitions.threshold = 0.75;
  s.transitions.threshold_quantile = 0.03;
  s.transitions.locality_radius = 4;
  s.transitions.per_tag_thresholds = false;
  s.transitions.max_threshold = 2.5;
  s.spacing = {12, 2, 8};
  s.bridges.per_tag_pair = 5;
  s.bridges.max_distance = 1.25;
  s.bridges.max_blend_factor = 2.5;
  s.connected_tags = std::vector<std::string>{"walk", "run"};
  const nlohmann::json json = s.to_json();
  auto back = SavedSettings::from_json(json);
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back->to_json(), json);
  EXPECT_EQ(back->transitions.threshold, 0.75);
  EXPECT_EQ(back->transitions.per_tag_thresholds, false);
  EXPECT_EQ(back->spacing.out_window_frames, 12);
  EXPECT_EQ(back->spacing.max_out, 2);
  EXPECT_EQ(back->spacing.min_piece_frames, 8);
  EXPECT_EQ(back->bridges.per_tag_pair, 5);
  EXPECT_EQ(back->bridges.max_distance, 1.25);
  EXPECT_EQ(back->bridges.max_blend_factor, 2.5);
  EXPECT_EQ(back->connected_tags, s.connected_tags);
  EXPECT_EQ(back->distance_stage.distance.window_frames, 10);
}

TEST(SavedSettings, NoCapIsNullAndAnOlderFilesMinusOneReadsAsNone) {
  SavedSettings s;
  s.transitions.max_threshold = -1.0;
  s.bridges.max_distance = -1.0;
  nlohmann::json json = s.to_json();
  EXPECT_TRUE(json.at("max_threshold").is_null()) << json.dump();
  EXPECT_TRUE(json.at("max_bridge_distance").is_null()) << json.dump();
  auto back = SavedSettings::from_json(json);
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back->transitions.max_threshold, -1.0);
  EXPECT_EQ(back->bridges.max_distance, -1.0);
  EXPECT_EQ(back->to_json(), json);

  // What build wrote before: -1 for none.
  json["max_threshold"] = -1.0;
  json["max_bridge_distance"] = -1.0;
  back = SavedSettings::from_json(json);
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back->transitions.max_threshold, -1.0);
  EXPECT_EQ(back->bridges.max_distance, -1.0);

  // A cap of zero is a cap (nothing passes), not none.
  json["max_bridge_distance"] = 0.0;
  back = SavedSettings::from_json(json);
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back->bridges.max_distance, 0.0);
  EXPECT_EQ(back->to_json().at("max_bridge_distance"), 0.0);
}

TEST(SavedSettings, OlderFilesTakeBuildsDefaults) {
  // What build wrote before spacing, bridges and connected tags were recorded.
  const auto json = nlohmann::json::parse(R"({"distance": {"cloud": "rings", "ring_spacing_m": 0.25,
    "ring_radius_m": 0.06, "points_per_ring": 4, "joint_weights": {}, "window": 10, "taper": "uniform"},
    "threshold": 0.5, "threshold_quantile": 0.02, "locality_radius": 5})");
  auto s = SavedSettings::from_json(json);
  ASSERT_TRUE(s) << s.error().to_string();
  EXPECT_FALSE(s->connected_tags);
  EXPECT_EQ(s->spacing.max_out, 0);
  EXPECT_EQ(s->spacing.min_piece_frames, 0);
  EXPECT_EQ(s->spacing.out_window_frames, -1);
  EXPECT_EQ(s->bridges.per_tag_pair, BridgeSettings{}.per_tag_pair);
  EXPECT_EQ(s->bridges.max_distance, -1.0);       // no cap
  EXPECT_EQ(s->bridges.max_blend_factor, 1.0);    // blended as long as a transition
  EXPECT_EQ(s->transitions.max_threshold, -1.0);
  EXPECT_TRUE(s->transitions.per_tag_thresholds);
  EXPECT_EQ(s->distance_stage.continuation_radius, -1);

  nlohmann::json broken = json;
  broken.erase("threshold");
  EXPECT_FALSE(SavedSettings::from_json(broken));
  broken = json;
  broken["distance"]["cloud"] = "spheres";
  EXPECT_FALSE(SavedSettings::from_json(broken));
  broken = json;
  broken["connected_tags"] = "walk";  // not a list
  EXPECT_FALSE(SavedSettings::from_json(broken));
}

}  // namespace
}  // namespace mg
