// build_graph() on the bundled subject 16, in process: the graph it makes is the one its saved
// settings select again (what eval and the studio rely on), the pruned distance stage runs
// where it is exact and gives the exhaustive stage's graph, the cache is used and changes
// nothing, pruning to nothing is an ErrorKind::kEmptyGraph with the report kept, and the
// exports have their promised sizes.
#include "motiongraph/pipeline/build_graph.h"

#include <gtest/gtest.h>

#include <cstring>
#include <algorithm>
#include <map>

#include "motiongraph/core/json_text.h"
#include "motiongraph/evaluation/graph_rebuild.h"
#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/graph/on_demand_candidates.h"
#include "motiongraph/export/bvh_writer.h"
#include "temp_folder.h"
#include "test_data.h"

namespace mg {
namespace {

// A cache in memory that counts what it is asked.
class MemoryCache final : public DistanceCache {
 public:
  Result<std::optional<CandidateSearch>> find(std::uint64_t key) override {
    ++finds;
    const auto it = entries.find(key);
    if (it == entries.end()) return std::optional<CandidateSearch>();
    return std::optional<CandidateSearch>(it->second);
  }
  Status store(std::uint64_t key, const CandidateSearch& candidates) override {
    ++stores;
    entries[key] = candidates;
    entries[key].matrix.clear();
    return Ok{};
  }
  std::string location(std::uint64_t key) const override { return std::to_string(key); }

  std::map<std::uint64_t, CandidateSearch> entries;
  int finds = 0;
  int stores = 0;
};

const std::vector<std::string> kInputs = {test::data_path("cmu/16")};

TEST(BuildGraph, Subject16IsWhatItsSavedSettingsSelectAgain) {
  BuildSettings settings;
  settings.pruned_from_frames = 0;  // subject 16 is small: by default the exhaustive stage runs
  auto built = build_graph(kInputs, settings);
  ASSERT_TRUE(built) << built.error().to_string();
  ASSERT_TRUE(built->graph_status) << built->graph_status.error().to_string();
  const GraphFile& file = built->file;
  ASSERT_FALSE(file.graph.transitions.empty());
  EXPECT_EQ(built->report.at("frames"), file.database.frame_count());
  EXPECT_EQ(built->report.at("threshold_mode"), "auto");
  EXPECT_EQ(built->report.at("distance_cache"), "off");
  // The automatic threshold, one per motion type, searched for under the pruned stage's ceiling.
  EXPECT_EQ(built->report.at("distance_stage").at("stage"), "pruned");
  EXPECT_TRUE(built->report.at("threshold_choice").at("per_type").get<bool>());
  const nlohmann::json& own = built->report.at("tag_thresholds");
  ASSERT_EQ(own.size(), built->report.at("threshold_choice").at("motion_types").size());
  for (const auto& t : own) {
    EXPECT_TRUE(t.at("chosen").get<bool>());
    EXPECT_GE(t.at("threshold").get<double>(), built->report.at("threshold").get<double>());
    EXPECT_LE(t.at("threshold").get<double>(), file.candidates.ceiling);
  }
  EXPECT_EQ(built->report.at("counts").at("transitions_kept"), file.graph.transitions.size());
  EXPECT_EQ(file.report_json, json_text(built->report));
  EXPECT_TRUE(built->matrix_npy.empty() && built->matrix_png.empty() && built->clouds_npy.empty());

  // The reference: eval's rebuild from the saved settings selects the very same graph.
  auto rebuild = prepare_graph_rebuild(file, "s16.mgraph");
  ASSERT_TRUE(rebuild) << rebuild.error().to_string();
  EXPECT_EQ(rebuild->settings.transitions.tag_thresholds.size(), own.size());
  OnDemandCandidates more(rebuild->features, file.candidates);
  auto again = graph_from_candidates(file.database, rebuild->features, file.candidates, rebuild->settings, &more);
  ASSERT_TRUE(again) << again.error().to_string();
  ASSERT_EQ(again->pruned.graph.transitions.size(), file.graph.transitions.size());
  for (size_t i = 0; i < file.graph.transitions.size(); ++i) {
    EXPECT_EQ(again->pruned.graph.transitions[i].from_frame, file.graph.transitions[i].from_frame);
    EXPECT_EQ(again->pruned.graph.transitions[i].to_frame, file.graph.transitions[i].to_frame);
  }
  EXPECT_EQ(again->pruned.graph.nodes.size(), file.graph.nodes.size());
  // With the same blend lengths: bridges blend longer than the window, as saved.
  ASSERT_EQ(again->pruned.graph.edges.size(), file.graph.edges.size());
  int longer = 0;
  for (size_t e = 0; e < file.graph.edges.size(); ++e) {
    EXPECT_EQ(again->pruned.graph.edges[e].frame_count, file.graph.edges[e].frame_count) << e;
    if (file.graph.edges[e].transition && blend_frames(file.graph.edges[e]) > file.graph.window) ++longer;
  }
  EXPECT_GT(longer, 0);
}

// `settings` built by default and with --exhaustive, both in tiles of 64 frames (the pruned
// stage's at 30 fps): where the default runs the pruned stage, the two graphs must be equal.
struct BothStages {
  Result<GraphBuild> pruned;
  Result<GraphBuild> exhaustive;
};

BothStages build_both_stages(BuildSettings settings) {
  settings.pruned_from_frames = 0;
  settings.pruned.tile_frames = 64;
  settings.distance_stage.distance.tile_frames = 64;
  BuildSettings exhaustive = settings;
  exhaustive.exhaustive = true;
  return {build_graph(kInputs, settings), build_graph(kInputs, exhaustive)};
}

class PrunedBuild : public testing::TestWithParam<bool> {};

TEST_P(PrunedBuild, GivesTheExhaustiveGraph) {
  // With one threshold for all motion types, or one per type: the pruned stage runs, its
  // bridges (walk to run, far above the ceiling) found on demand; with the same tiles the
  // exhaustive stage gives the same graph.
  BuildSettings pruned;
  pruned.transitions.per_tag_thresholds = GetParam();
  auto [a, b] = build_both_stages(pruned);
  ASSERT_TRUE(a && b);
  ASSERT_TRUE(a->graph_status && b->graph_status);
  const nlohmann::json& stage = a->report.at("distance_stage");
  EXPECT_EQ(stage.at("stage"), "pruned");
  EXPECT_EQ(stage.at("tile_frames"), 64);
  EXPECT_LT(stage.at("tiles_computed").get<long long>(), stage.at("tiles").get<long long>());
  EXPECT_GT(stage.at("on_demand").at("raises").get<int>(), 0);
  EXPECT_EQ(b->report.at("distance_stage").at("stage"), "exhaustive");
  EXPECT_GE(a->file.candidates.ceiling, 0.0);
  EXPECT_EQ(a->report.at("threshold"), b->report.at("threshold"));
  // The same thresholds (the pruned stage counts a type's candidates below its ceiling only).
  const nlohmann::json& own_a = a->report.at("tag_thresholds");
  const nlohmann::json& own_b = b->report.at("tag_thresholds");
  ASSERT_EQ(own_a.size(), own_b.size());
  EXPECT_EQ(own_a.empty(), !GetParam());
  for (size_t i = 0; i < own_a.size(); ++i) {
    EXPECT_EQ(own_a[i].at("tag"), own_b[i].at("tag"));
    EXPECT_EQ(own_a[i].at("threshold"), own_b[i].at("threshold"));
    EXPECT_LE(own_a[i].at("candidates").get<int>(), own_b[i].at("candidates").get<int>());
  }
  EXPECT_EQ(a->report.at("bridges"), b->report.at("bridges"));
  EXPECT_EQ(a->report.at("graph_after"), b->report.at("graph_after"));
  const auto& x = a->file.graph.transitions;
  const auto& y = b->file.graph.transitions;
  ASSERT_EQ(x.size(), y.size());
  for (size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(x[i].from_frame, y[i].from_frame);
    EXPECT_EQ(x[i].to_frame, y[i].to_frame);
    EXPECT_EQ(x[i].distance, y[i].distance);
  }
  // What eval does with such a file: its saved settings, bridges found on demand again.
  const GraphFile& file = a->file;
  auto rebuild = prepare_graph_rebuild(file, "s16.mgraph");
  ASSERT_TRUE(rebuild) << rebuild.error().to_string();
  EXPECT_FALSE(graph_from_candidates(file.database, rebuild->features, file.candidates, rebuild->settings));
  OnDemandCandidates more(rebuild->features, file.candidates);
  auto again = graph_from_candidates(file.database, rebuild->features, file.candidates, rebuild->settings, &more);
  ASSERT_TRUE(again) << again.error().to_string();
  ASSERT_EQ(again->pruned.graph.transitions.size(), x.size());
  for (size_t i = 0; i < x.size(); ++i) EXPECT_EQ(again->pruned.graph.transitions[i].to_frame, x[i].to_frame);
}

INSTANTIATE_TEST_SUITE_P(BuildGraph, PrunedBuild, testing::Bool(),
                         [](const testing::TestParamInfo<bool>& param) {
                           return param.param ? "ThresholdPerMotionType" : "OneThreshold";
                         });

TEST(BuildGraph, AThresholdGivenByHandRunsThePrunedStageWhereItIsExact) {
  // One threshold for all motion types, given in cm under the ceiling: the pruned stage, the
  // graph of the exhaustive stage with its tiles. A quantile, a threshold above the ceiling,
  // per-tag thresholds by rank or a library under --pruned-from run the exhaustive stage.
  BuildSettings hand;
  hand.threshold_mode = ThresholdMode::kRmsCm;
  hand.threshold_value = 4.0;
  hand.transitions.per_tag_thresholds = false;
  hand.pruned_from_frames = 0;
  auto [a, b] = build_both_stages(hand);
  ASSERT_TRUE(a && b);
  ASSERT_TRUE(a->graph_status && b->graph_status);
  EXPECT_EQ(a->report.at("distance_stage").at("stage"), "pruned");
  EXPECT_EQ(b->report.at("distance_stage").at("stage"), "exhaustive");
  EXPECT_EQ(a->report.at("threshold"), b->report.at("threshold"));
  EXPECT_EQ(a->report.at("bridges"), b->report.at("bridges"));
  EXPECT_EQ(a->report.at("graph_after"), b->report.at("graph_after"));
  ASSERT_EQ(a->file.graph.transitions.size(), b->file.graph.transitions.size());
  for (size_t i = 0; i < a->file.graph.transitions.size(); ++i) {
    EXPECT_EQ(a->file.graph.transitions[i].from_frame, b->file.graph.transitions[i].from_frame);
    EXPECT_EQ(a->file.graph.transitions[i].to_frame, b->file.graph.transitions[i].to_frame);
  }
  for (auto change : {+[](BuildSettings& x) { x.transitions.per_tag_thresholds = true; },
                      +[](BuildSettings& x) { x.pruned_from_frames = 2000; },  // subject 16: 1 235 frames
                      +[](BuildSettings& x) { x.threshold_value = 12.0; },  // above the 10 cm ceiling
                      +[](BuildSettings& x) {
                        x.threshold_mode = ThresholdMode::kQuantile;
                        x.threshold_value = 0.02;
                      }}) {
    BuildSettings other = hand;
    change(other);
    auto built = build_graph(kInputs, other);
    ASSERT_TRUE(built) << built.error().to_string();
    EXPECT_EQ(built->report.at("distance_stage").at("stage"), "exhaustive");
  }
}

TEST(BuildGraph, NoGraphUnderThePrunedStagesCeilingStillSaysWhatWouldMakeOne) {
  BuildSettings settings;
  settings.pruned_from_frames = 0;
  settings.transitions.per_tag_thresholds = false;
  settings.choice.max_rms_cm = 0.6;
  settings.choice.lowest_rms_cm = 0.3;
  auto built = build_graph(kInputs, settings);
  ASSERT_TRUE(built) << built.error().to_string();
  EXPECT_EQ(built->report.at("distance_stage").at("stage"), "pruned");
  ASSERT_FALSE(built->graph_status);
  EXPECT_EQ(built->graph_status.error().kind, ErrorKind::kEmptyGraph);
  // The lowest threshold that makes a graph lies above the ceiling: found on every distance.
  EXPECT_NE(built->graph_status.error().message.find("the lowest threshold that makes one"), std::string::npos);
  ASSERT_TRUE(built->report.contains("lowest_graph_threshold"));
  EXPECT_GT(built->report.at("lowest_graph_threshold").at("rms_cm").get<double>(), 0.6);
}

TEST(BuildGraph, ABridgeCapLeavesPairsUnjoinedAndSaysWhatWouldJoinThem) {
  BuildSettings settings;
  settings.threshold_mode = ThresholdMode::kRmsCm;
  settings.threshold_value = 3.5;
  auto open = build_graph(kInputs, settings);
  ASSERT_TRUE(open && open->graph_status);
  const nlohmann::json& bridges = open->report.at("bridges");
  ASSERT_FALSE(bridges.empty());
  double smallest = 1e9;
  for (const auto& b : bridges) {
    smallest = std::min(smallest, b.at("rms_cm").get<double>());
    // Longer than the window for D above the threshold, never more than 3 windows.
    const int blend = b.at("blend_frames").get<int>();
    EXPECT_GE(blend, open->report.at("window").get<int>());
    EXPECT_LE(blend, 3 * open->report.at("window").get<int>());
  }
  // A cap below the smallest bridge: no bridges, and each ordered pair they joined reported
  // with the best distance that would have joined it.
  settings.max_bridge_rms_cm = smallest - 0.01;
  auto capped = build_graph(kInputs, settings);
  ASSERT_TRUE(capped) << capped.error().to_string();
  const nlohmann::json& kept = capped->report.at("bridges");
  EXPECT_TRUE(kept.empty());
  int above_cap = 0;
  // Whether both keep frames in the pruned graph, which leads from any of its frames to any other.
  auto in_graph = [&](const std::string& name) {
    for (const auto& t : capped->report.at("graph_after").at("tags")) {
      if (t.at("name") == name) return t.at("frames").get<int>() > 0;
    }
    return false;
  };
  for (const auto& u : capped->report.at("unjoined")) {
    EXPECT_EQ(u.at("through_graph").get<bool>(), in_graph(u.at("from")) && in_graph(u.at("to")));
    if (u.at("best_rms_cm").is_null()) continue;
    ++above_cap;
    EXPECT_GT(u.at("best_rms_cm").get<double>(), settings.max_bridge_rms_cm);
    EXPECT_NE(u.at("why").get<std::string>().find("above the bridge cap"), std::string::npos);
  }
  EXPECT_GT(above_cap, 0);
  EXPECT_TRUE(open->report.at("unjoined").empty());

  settings.max_bridge_rms_cm = -1.0;
  EXPECT_FALSE(settings.validate());
}

// Walks and runs, and a clip of no motion type: the first 0.8 s of the first walk raised 6 cm, too
// short to loop and so to be bridged, which joins the graph only where walking's threshold rises
// to it (ThresholdChoice's own test). It is a minor share of the frames: the warning names it as
// holding the types up and says how to give it a type, and the report says so.
TEST(BuildGraph, AMinorClipOfNoTypeHoldingTheTypesUpIsNamedWithHowToTagIt) {
  test::TempFolder folder("minor-untagged");
  Clip raised = test::load_data_clip("cmu/16/16_15.amc");
  raised.motion = raised.motion.slice(0, 100);  // 0.83 s at 120 fps
  const int slot = raised.skeleton.translation_slot(0);
  for (int f = 0; f < raised.motion.frame_count; ++f) raised.motion.translations(f)[slot].y() += 0.06;
  folder.write("take_07.bvh", write_bvh(raised.skeleton, raised.motion, BvhWriteSettings{}));
  std::string manifest = fmt::format("skeleton = \"{}/16.asf\"\n", test::data_path("cmu/16"));
  for (const char* walk : {"16_15", "16_16", "16_17"}) {
    manifest += fmt::format("[[clip]]\nfile = \"{}/{}.amc\"\ntags = [\"walk\"]\n", test::data_path("cmu/16"), walk);
  }
  for (const char* run : {"16_35", "16_37"}) {
    manifest += fmt::format("[[clip]]\nfile = \"{}/{}.amc\"\ntags = [\"run\"]\n", test::data_path("cmu/16"), run);
  }
  manifest += "[[clip]]\nfile = \"take_07.bvh\"\n";
  const std::vector<std::string> inputs = {folder.write("db.toml", manifest)};
  BuildSettings settings;
  settings.database.mirror = DatabaseSettings::Mirroring::kOff;  // its walks turn one way: as read
  auto built = build_graph(inputs, settings);
  ASSERT_TRUE(built) << built.error().to_string();
  ASSERT_TRUE(built->graph_status) << built->graph_status.error().to_string();
  EXPECT_TRUE(built->report.at("threshold_choice").at("untagged_holds").get<bool>());
  const auto& warnings = built->report.at("warnings");
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [](const nlohmann::json& w) {
    const std::string text = w.get<std::string>();
    return text.starts_with("1 clip of no motion type (take_07; ") &&
           text.find("holds them there") != std::string::npos &&
           text.find("a name that says its motion (walk_07.bvh), would let them fall") != std::string::npos;
  })) << warnings.dump(1);
}

TEST(BuildGraph, TheCacheIsUsedAndChangesNothing) {
  BuildSettings settings;
  settings.threshold_mode = ThresholdMode::kRmsCm;
  settings.threshold_value = 5.0;
  MemoryCache cache;
  auto first = build_graph(kInputs, settings, &cache);
  ASSERT_TRUE(first) << first.error().to_string();
  EXPECT_EQ(first->report.at("distance_cache"), "stored");
  EXPECT_EQ(cache.stores, 1);
  auto second = build_graph(kInputs, settings, &cache);
  ASSERT_TRUE(second) << second.error().to_string();
  EXPECT_EQ(second->report.at("distance_cache"), "hit");
  EXPECT_EQ(cache.stores, 1);
  ASSERT_TRUE(first->graph_status && second->graph_status);
  // The same graph from the same candidates.
  const GraphFile& a = first->file;
  const GraphFile& b = second->file;
  EXPECT_EQ(a.settings_json, b.settings_json);
  EXPECT_EQ(a.input_key, b.input_key);
  EXPECT_EQ(a.candidates.minima.size(), b.candidates.minima.size());
  EXPECT_EQ(a.candidates.histogram.counts(), b.candidates.histogram.counts());
  // The picture holds NaN where no pair is defined: compared bit for bit.
  ASSERT_EQ(a.candidates.picture.size(), b.candidates.picture.size());
  EXPECT_EQ(std::memcmp(a.candidates.picture.data(), b.candidates.picture.data(), a.candidates.picture.size() * 4), 0);
  ASSERT_EQ(a.graph.edges.size(), b.graph.edges.size());
  ASSERT_EQ(a.graph.transitions.size(), b.graph.transitions.size());
  for (size_t i = 0; i < a.graph.transitions.size(); ++i) {
    EXPECT_EQ(a.graph.transitions[i].from_frame, b.graph.transitions[i].from_frame);
    EXPECT_EQ(a.graph.transitions[i].to_frame, b.graph.transitions[i].to_frame);
    EXPECT_EQ(a.graph.transitions[i].yaw_rad, b.graph.transitions[i].yaw_rad);
  }

  // Another threshold on the same inputs: the same key, still a hit.
  settings.threshold_value = 4.0;
  auto third = build_graph(kInputs, settings, &cache);
  ASSERT_TRUE(third);
  EXPECT_EQ(third->report.at("distance_cache"), "hit");
  EXPECT_EQ(third->file.input_key, a.input_key);
  // Another window is another key.
  settings.distance_stage.distance.window_frames = 12;
  auto fourth = build_graph(kInputs, settings, &cache);
  ASSERT_TRUE(fourth);
  EXPECT_EQ(fourth->report.at("distance_cache"), "stored");
  EXPECT_NE(fourth->file.input_key, a.input_key);
  EXPECT_EQ(cache.entries.size(), 2u);
}

// A stop asked for at a stage's log line ends the build at its next step with
// ErrorKind::kStopped: after reading, before the distance stage (nothing cached); after the
// distance stage, before the threshold is chosen; after the choice, within the path check's
// searches (its line never comes).
TEST(BuildGraph, StopsWhenAskedAtTheNextStep) {
  struct Case {
    const char* at;              // the line whose logging asks the stop
    const char* never;           // a later line that must not come
    int stores;                  // distance stages cached
  };
  for (const Case& c : {Case{" clips, ", "distance stage", 0}, Case{"distance stage:", "threshold auto", 1},
                        Case{"threshold auto", "path check", 1}}) {
    SCOPED_TRACE(c.at);
    std::stop_source stop;
    std::vector<std::string> lines;
    BuildLog log;
    log.stop = stop.get_token();
    log.info = [&](const std::string& line) {
      lines.push_back(line);
      if (line.find(c.at) != std::string::npos) stop.request_stop();
    };
    MemoryCache cache;
    auto built = build_graph(kInputs, BuildSettings{}, &cache, log);
    ASSERT_FALSE(built);
    EXPECT_EQ(built.error().kind, ErrorKind::kStopped);
    EXPECT_TRUE(std::any_of(lines.begin(), lines.end(),
                            [&](const std::string& l) { return l.find(c.at) != std::string::npos; }));
    for (const std::string& line : lines) EXPECT_EQ(line.find(c.never), std::string::npos) << line;
    EXPECT_EQ(cache.stores, c.stores);
  }
}

TEST(BuildGraph, NothingLeftAfterPruningIsAnEmptyGraphWithItsReport) {
  BuildSettings settings;
  settings.threshold_mode = ThresholdMode::kRmsCm;
  settings.threshold_value = 0.5;
  auto built = build_graph(kInputs, settings);
  ASSERT_TRUE(built) << built.error().to_string();
  ASSERT_FALSE(built->graph_status);
  EXPECT_EQ(built->graph_status.error().kind, ErrorKind::kEmptyGraph);
  EXPECT_NE(built->graph_status.error().message.find("the lowest threshold that makes one"), std::string::npos);
  EXPECT_EQ(built->report.at("error"), "pruning left nothing");
  EXPECT_TRUE(built->report.contains("lowest_graph_threshold"));
  EXPECT_TRUE(built->report.contains("timings"));
}

TEST(BuildGraph, ExportsHaveTheirSizes) {
  BuildSettings settings;
  settings.threshold_mode = ThresholdMode::kQuantile;
  settings.threshold_value = 0.05;
  settings.exports = {true, true, true};
  MemoryCache cache;
  auto built = build_graph(kInputs, settings, &cache);
  ASSERT_TRUE(built) << built.error().to_string();
  const size_t n = static_cast<size_t>(built->file.database.frame_count());
  const size_t points = static_cast<size_t>(built->report.at("points").get<int>());
  // .npy: a header padded to a multiple of 64 bytes, then float32 data.
  ASSERT_GT(built->matrix_npy.size(), n * n * 4);
  EXPECT_EQ((built->matrix_npy.size() - n * n * 4) % 64, 0u);
  EXPECT_EQ((built->clouds_npy.size() - n * points * 3 * 4) % 64, 0u);
  EXPECT_EQ(built->matrix_png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // The matrix is not kept in the graph file, and with the matrix asked for the stage runs.
  EXPECT_TRUE(built->file.candidates.matrix.empty());
  EXPECT_EQ(built->report.at("distance_cache"), "stored");
  EXPECT_EQ(cache.finds, 0);
}

TEST(BuildGraph, FailsOnBadSettingsAndInputs) {
  BuildSettings settings;
  settings.threshold_mode = ThresholdMode::kDistance;
  settings.threshold_value = -1.0;
  EXPECT_FALSE(build_graph(kInputs, settings));
  settings = {};
  settings.threshold_mode = ThresholdMode::kQuantile;
  settings.threshold_value = 1.5;
  EXPECT_FALSE(build_graph(kInputs, settings));
  settings = {};
  settings.connect_tags = {"swim"};
  auto unknown_tag = build_graph(kInputs, settings);
  ASSERT_FALSE(unknown_tag);
  EXPECT_NE(unknown_tag.error().message.find("swim"), std::string::npos);
  const std::vector<std::string> missing = {test::data_path("no-such-folder")};
  EXPECT_FALSE(build_graph(missing, BuildSettings{}));
}

}  // namespace
}  // namespace mg
