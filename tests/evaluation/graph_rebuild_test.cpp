// Features and settings read back from a graph file's settings: the window checked against
// the candidates', and one failing input per rule.
#include "motiongraph/evaluation/graph_rebuild.h"

#include <gtest/gtest.h>

#include "test_data.h"

namespace mg {
namespace {

// The settings JSON as build writes it (pipeline/saved_settings.h), window 10 at 30 fps.
const char* kSettings = R"({"distance": {"cloud": "rings", "ring_spacing_m": 0.25, "ring_radius_m": 0.06,
  "points_per_ring": 4, "joint_weights": {"head": 2.0}, "window": 10, "taper": "uniform",
  "continuation_radius": -1}, "threshold": -1.0, "threshold_quantile": 0.02, "locality_radius": 5,
  "per_tag_thresholds": true, "fps": 30.0})";

GraphFile graph_file(const std::string& settings) {
  GraphFile file;
  file.settings_json = settings;
  file.database = test::small_database({"cmu/16/16_15.amc"});
  file.database.tag_names = {"walk", "turn"};
  file.candidates.window = 10;
  return file;
}

TEST(GraphRebuild, SettingsAndFeaturesAsBuilt) {
  auto rebuild = prepare_graph_rebuild(graph_file(kSettings), "g.mgraph");
  ASSERT_TRUE(rebuild) << rebuild.error().to_string();
  EXPECT_EQ(rebuild->features.window, 10);
  EXPECT_EQ(rebuild->features.frames, graph_file(kSettings).database.frame_count());
  EXPECT_EQ(rebuild->settings.transitions.threshold_quantile, 0.02);
  EXPECT_EQ(rebuild->settings.transitions.locality_radius, 5);
  EXPECT_EQ(rebuild->settings.connected_tags, TagMask{1});  // walk; turn is a modifier
  // The head's points weigh 2: some point weights are not 1.
  bool weighted = false;
  for (double w : rebuild->features.point_weights) weighted |= w == 2.0;
  EXPECT_TRUE(weighted);
}

TEST(GraphRebuild, FailingInputs) {
  const std::string settings = kSettings;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"not JSON", "{"},
      {"a missing key", test::replace_once(settings, "\"ring_radius_m\"", "\"radius\"")},
      {"an unknown cloud", test::replace_once(settings, "\"rings\"", "\"spheres\"")},
      {"an unknown connected tag", test::replace_once(settings, "\"fps\"", "\"connected_tags\": [\"swim\"], \"fps\"")},
      {"another window than the candidates'", test::replace_once(settings, "\"window\": 10", "\"window\": 12")},
  };
  for (const auto& [rule, text] : cases) {
    auto rebuild = prepare_graph_rebuild(graph_file(text), "g.mgraph");
    ASSERT_FALSE(rebuild) << rule;
    EXPECT_EQ(rebuild.error().file, "g.mgraph") << rule;
  }
}

}  // namespace
}  // namespace mg
