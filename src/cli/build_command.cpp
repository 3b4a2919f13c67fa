// motiongraph build INPUT... -o GRAPH.mgraph: the motion graph of a database (Kovar et al.
// 2002, section 3) through the library's build_graph() (pipeline/build_graph.h): the options
// become BuildSettings, the distance cache is a folder of files, and the graph file, the report
// and the exports it returns are written here (atomically).
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/unit_report.h"
#include "motiongraph/core/json_text.h"
#include "motiongraph/core/text.h"
#include "motiongraph/io/file.h"
#include "motiongraph/pipeline/build_graph.h"

namespace mg::cli {

namespace {

using nlohmann::json;

struct BuildOptions {
  std::vector<std::string> inputs;
  std::string output;
  double fps = 30.0;
  bool fps_given = false;
  std::string asf;
  std::optional<double> scale;
  double input_fps = 0.0;
  std::string cmu_index;
  bool no_cmu_tags = false;
  std::string feet;  // LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,RIGHT_TOE
  std::string cloud = "rings";
  PointCloudSettings cloud_settings;
  std::vector<std::string> joint_weights;  // NAME=WEIGHT
  DistanceSettings distance;
  std::string taper = "uniform";
  TransitionSettings transitions;
  std::string threshold = "auto";  // auto, D, or an RMS distance with "cm"
  double quantile = -1.0;          // given: the threshold is this quantile of all pairs
  ThresholdChoiceSettings choice;
  PathCheckSettings path_check;
  bool no_path_check = false;
  TransitionSpacing spacing;
  int continuation_radius = -1;
  std::string cache_dir;
  bool no_cache = false;
  std::string report, export_matrix, export_clouds, matrix_png;
  bool quiet = false;
  bool ignore_tags = false;
  BridgeSettings bridges;
  double max_bridge_cm = 0.0;  // RMS point distance above which no bridge is made; 0: no cap
  std::vector<std::string> connect_tags;
};

// The settings the options give, or the first option that is not understood.
Result<BuildSettings> build_settings(const BuildOptions& o) {
  BuildSettings s;
  s.distance_stage.cloud = o.cloud_settings;
  s.distance_stage.distance = o.distance;
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
  if (o.quantile >= 0.0) {
    if (o.threshold != "auto") return Error{"", 0, "give --threshold or --threshold-quantile, not both"};
    s.threshold_mode = ThresholdMode::kQuantile;
    s.threshold_value = o.quantile;
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
  s.spacing = o.spacing;
  s.bridges = o.bridges;
  s.max_bridge_rms_cm = o.max_bridge_cm;
  s.connect_tags = o.connect_tags;
  s.ignore_tags = o.ignore_tags;
  s.exports = {!o.export_matrix.empty(), !o.matrix_png.empty(), !o.export_clouds.empty()};
  DatabaseSettings& db = s.database;
  db.fps = o.fps;
  db.prefer_manifest_fps = !o.fps_given;
  if (!o.asf.empty()) db.asf_path = o.asf;
  db.bvh_metres_per_unit = o.scale;
  db.input_fps = o.input_fps;
  db.cmu_tags = !o.no_cmu_tags;
  if (!o.feet.empty()) {
    auto feet = parse_foot_joint_names(o.feet);
    if (!feet) return Error{"", 0, "--feet: " + feet.error().message};
    db.foot_names = *feet;
  }
  db.cmu_index_path = o.cmu_index;
  if (auto valid = s.validate(); !valid) return valid.error();
  return s;
}

int run_build(const BuildOptions& o) {
  auto settings = build_settings(o);
  if (!settings) return fail(settings.error());
  if (std::filesystem::path(o.output).extension() != ".mgraph") {
    return fail(Error{o.output, 0, "the graph file must end in .mgraph"});
  }
  std::unique_ptr<DistanceCache> cache;
  if (!o.no_cache) {
    cache = std::make_unique<FileDistanceCache>(o.cache_dir.empty() ? default_distance_cache_folder() : o.cache_dir);
  }
  BuildLog log;
  if (!o.quiet) log.info = [](const std::string& line) { spdlog::info("{}", line); };
  log.warning = [](const std::string& line) { spdlog::warn("{}", line); };
  log.loaded = [&](const DatabaseLoadNotes& notes) { report_units(notes, o.quiet); };
  log.progress_bar = !o.quiet;
  auto built = build_graph(o.inputs, *settings, cache.get(), log);
  if (!built) return fail(built.error());

  // The exports and the report are written even when no graph can be made, so that the user
  // can see why.
  for (const auto& [path, bytes] :
       {std::pair{&o.matrix_png, &built->matrix_png}, std::pair{&o.export_matrix, &built->matrix_npy},
        std::pair{&o.export_clouds, &built->clouds_npy}}) {
    if (path->empty()) continue;
    if (auto s = write_file_atomic(*path, *bytes); !s) return fail(s.error());
  }
  json& report = built->report;
  if (!built->graph_status) {
    if (!o.report.empty()) {
      if (auto s = write_file_atomic(o.report, json_text(report, 2) + "\n"); !s) return fail(s.error());
    }
    return fail(built->graph_status.error());
  }
  const auto write_start = std::chrono::steady_clock::now();
  if (auto s = write_file_atomic(o.output, serialize_graph_file(built->file)); !s) return fail(s.error());
  if (!o.report.empty()) {
    report["timings"]["write"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - write_start).count();
    if (auto s = write_file_atomic(o.report, json_text(report, 2) + "\n"); !s) return fail(s.error());
  }
  if (!o.quiet) spdlog::info("wrote {}", o.output);
  return 0;
}

}  // namespace

Command add_build_command(CLI::App& app) {
  auto o = std::make_shared<BuildOptions>();
  CLI::App* sub = app.add_subcommand(
      "build", "Build a motion graph (Kovar et al. 2002): transitions at local minima of the windowed, floor-aligned "
               "point-cloud distance below a threshold; pruned to the largest strongly connected component per tag.");
  sub->add_option("INPUT", o->inputs, "Folders (an .asf and its .amc files, or .bvh files), clip files, or .toml "
                                      "manifests (see docs/manifest.md)")
      ->required();
  sub->add_option("-o,--output", o->output, "The graph file to write (.mgraph)")->required();
  sub->add_option("--fps", o->fps, "Database frame rate: every clip is resampled to it")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str()
      ->each([o](const std::string&) { o->fps_given = true; });
  sub->add_option("--asf", o->asf, "ASF skeleton of AMC files given one by one")->check(CLI::ExistingFile);
  sub->add_option("--scale", o->scale,
                  "Metres per BVH length unit (default: m, cm, mm, inch or CMU's 1/0.45 inch per file, whichever makes "
                  "the figure human-sized)");
  sub->add_option("--input-fps", o->input_fps, "Capture rate of the inputs, overriding the files' (AMC: 120)");
  sub->add_option("--cmu-index", o->cmu_index,
                  "CMU's motion index (cmu-mocap-index.tsv) for tags from descriptions; default: one beside or above the "
                  "inputs, else the index the project ships (built in)");
  sub->add_flag("--no-cmu-tags", o->no_cmu_tags, "Do not tag clips from CMU's descriptions");
  sub->add_option("--feet", o->feet,
                  "Foot joints as LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,RIGHT_TOE, any left empty to find it by name "
                  "(default: found by name; a manifest's [feet] otherwise)");
  sub->add_flag("--ignore-tags", o->ignore_tags, "Prune to the largest strongly connected component only, ignoring tags");
  sub->add_option("--bridges", o->bridges.per_tag_pair,
                  "Bridges per ordered pair of tags that no transition below the threshold joins: their best candidates "
                  "(0: none)")
      ->capture_default_str();
  sub->add_option("--max-bridge", o->max_bridge_cm,
                  "No bridge above this RMS point distance in cm (0: no cap); the report names the motion types left "
                  "unjoined and the distance that would join them")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  sub->add_option("--bridge-blend", o->bridges.max_blend_factor,
                  "A bridge blends over k sqrt(D / threshold) frames, k the window, at most this many windows (1: as "
                  "long as a transition)")
      ->check(CLI::Range(1.0, 20.0))
      ->capture_default_str();
  sub->add_option("--connect-tags", o->connect_tags,
                  "Motion types whose frames must form a strongly connected region each, and between which bridges "
                  "are added (default: every tag but turn, stop, start, backward)")
      ->delimiter(',');
  sub->add_option("--cloud", o->cloud, "Point cloud: 'rings' (points around each bone) or 'joints'")->capture_default_str();
  sub->add_option("--ring-spacing", o->cloud_settings.ring_spacing_m, "Metres between rings along a bone")
      ->capture_default_str();
  sub->add_option("--ring-radius", o->cloud_settings.ring_radius_m, "Metres from a bone to its ring's points")
      ->capture_default_str();
  sub->add_option("--ring-points", o->cloud_settings.points_per_ring, "Points per ring")->capture_default_str();
  sub->add_option("--joint-weight", o->joint_weights, "Weight of the points on the bone ending at a joint, NAME=WEIGHT "
                                                      "(repeatable; others weigh 1)");
  sub->add_option("--window", o->distance.window_frames, "Window and blend length k in frames (0: a third of a second)")
      ->capture_default_str();
  sub->add_option("--taper", o->taper, "Weights over the window: 'uniform' or 'hann'")->capture_default_str();
  sub->add_option("--threshold", o->threshold,
                  "'auto': the lowest threshold at which the pruned graph keeps --coverage of each motion type's "
                  "frames, at most --max-threshold; or an RMS point distance over the window such as '4cm'; or an "
                  "absolute distance D")
      ->capture_default_str();
  sub->add_option("--threshold-quantile", o->quantile,
                  "Instead of --threshold: the fraction of all defined pairs below the threshold (e.g. 0.02)");
  sub->add_option("--coverage", o->choice.coverage,
                  "--threshold auto: the share of each motion type's frames (of all frames without tags) the pruned "
                  "graph keeps")
      ->capture_default_str();
  sub->add_option("--min-transition-rate", o->choice.min_transition_rate,
                  "--threshold auto: transitions per second of kept motion the graph must offer (to be steerable)")
      ->capture_default_str();
  sub->add_option("--max-threshold", o->choice.max_rms_cm,
                  "--threshold auto: the highest threshold it may choose, as RMS point distance in cm (quality ceiling)")
      ->capture_default_str();
  sub->add_option("--path-check", o->path_check.tolerance_m,
                  "--threshold auto: raise the threshold (up to --max-threshold) until a test path of half circles of "
                  "4 m is followed within this mean deviation in metres")
      ->capture_default_str();
  sub->add_flag("--no-path-check", o->no_path_check, "--threshold auto: keep the coverage threshold, untested");
  sub->add_option("--max-out", o->spacing.max_out,
                  "Transitions leaving any --out-window consecutive frames of a clip, the best kept (0: no limit)")
      ->capture_default_str();
  sub->add_option("--out-window", o->spacing.out_window_frames,
                  "The stretch of frames --max-out counts over (-1: the window)")
      ->capture_default_str();
  sub->add_option("--min-piece", o->spacing.min_piece_frames,
                  "Frames of captured motion between arriving by a transition and leaving by the next (0: off)")
      ->capture_default_str();
  sub->add_flag("!--no-tag-thresholds", o->transitions.per_tag_thresholds,
                "One threshold for everything: no motion type gets its own (by default each keeps the same share of "
                "its own candidates as the database keeps of all)");
  sub->add_option("--locality", o->transitions.locality_radius,
                  "Keep the best transition within this many frames (-1: half the window)")
      ->capture_default_str();
  sub->add_option("--continuation-radius", o->continuation_radius,
                  "Ignore pairs of a clip simply continuing within this many frames of b = a + k - 1 (-1: the window)")
      ->capture_default_str();
  sub->add_option("--tile", o->distance.tile_frames, "Tile side in frames for the distance stage")->capture_default_str();
  sub->add_option("--threads", o->distance.threads, "Worker threads (0: one per core)")->capture_default_str();
  sub->add_option("--cache-dir", o->cache_dir, "Where the distance stage is cached (default: $XDG_CACHE_HOME/motiongraph)");
  sub->add_flag("--no-cache", o->no_cache, "Neither read nor write the distance cache");
  sub->add_option("--report", o->report, "Write a JSON report (clips, settings, counts, graph statistics, timings)");
  sub->add_option("--export-matrix", o->export_matrix, "Write the N x N distance matrix (.npy float32, NaN undefined; "
                                                       "row = frame we leave, column = frame we arrive at)");
  sub->add_option("--export-clouds", o->export_clouds, "Write the point clouds (.npy float32, N x P x 3, metres)");
  sub->add_option("--matrix-png", o->matrix_png, "Write the distance picture with clip boundaries and transitions (PNG)");
  sub->add_flag("-q,--quiet", o->quiet, "No progress or summary on stderr");
  return {sub, [o] { return run_build(*o); }};
}

}  // namespace mg::cli
