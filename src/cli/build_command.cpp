// motiongraph build INPUT... -o GRAPH.mgraph: the motion graph of a database (Kovar et al.
// 2002, section 3): load and resample the clips, point clouds, the tiled distance stage
// (cached on disk by a key of the inputs and distance settings), transitions at local minima
// below a threshold, the graph pruned to its largest strongly connected component per tag;
// then the graph file and what the user asked for (report, matrix, clouds, picture).
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/unit_report.h"
#include "motiongraph/core/json_text.h"
#include "motiongraph/core/progress.h"
#include "motiongraph/core/text.h"
#include "motiongraph/database/database_loader.h"
#include "motiongraph/export/matrix_png.h"
#include "motiongraph/export/npy.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/graph/threshold_choice.h"
#include "motiongraph/synthesis/path_check.h"
#include "motiongraph/io/file.h"
#include "motiongraph/metric/frame_features.h"

namespace mg::cli {

namespace {

namespace fs = std::filesystem;
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
  std::vector<std::string> connect_tags;
};

class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// data/cmu/cmu-mocap-index.tsv beside or above the first input folder, when there is one.
std::string find_cmu_index(const std::vector<std::string>& inputs) {
  for (const std::string& input : inputs) {
    fs::path folder = fs::is_directory(input) ? fs::path(input) : fs::path(input).parent_path();
    for (int up = 0; up < 3 && !folder.empty(); ++up) {
      const fs::path candidate = folder / "cmu-mocap-index.tsv";
      std::error_code ec;
      if (fs::is_regular_file(candidate, ec)) return candidate.string();
      folder = folder.parent_path();
    }
  }
  return "";
}

std::string default_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "motiongraph").string();
  if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "motiongraph").string();
  return ".motiongraph-cache";
}

// Everything that decides the distance stage's result, in a stable text form.
json distance_settings_json(const BuildOptions& o, const FrameFeatures& f) {
  json weights = json::object();
  for (const auto& [name, weight] : o.cloud_settings.joint_weights) weights[name] = weight;
  return {{"cloud", o.cloud},
          {"ring_spacing_m", o.cloud_settings.ring_spacing_m},
          {"ring_radius_m", o.cloud_settings.ring_radius_m},
          {"points_per_ring", o.cloud_settings.points_per_ring},
          {"joint_weights", weights},
          {"window", f.window},
          {"taper", o.taper},
          {"continuation_radius", o.continuation_radius}};
}

std::uint64_t database_key(const MotionDatabase& db, const json& settings) {
  // The key covers the resampled motion itself, so any change of input files, ranges, rate
  // or reading options changes it.
  std::string bytes = json_text(settings);
  bytes += fmt::format("fps={};", db.fps);
  for (const DatabaseClip& clip : db.clips) {
    bytes += fmt::format("{}:{}:{};", clip.skeleton, clip.first_frame, clip.frame_count);
    bytes.append(reinterpret_cast<const char*>(clip.motion.local_rotations.data()),
                 clip.motion.local_rotations.size() * sizeof(Quat));
    bytes.append(reinterpret_cast<const char*>(clip.motion.local_translations_m.data()),
                 clip.motion.local_translations_m.size() * sizeof(Vec3));
  }
  for (const Skeleton& skeleton : db.skeletons) {
    for (const JointDef& joint : skeleton.joints()) {
      bytes += fmt::format("{}/{}/{}/{}/{};", joint.name, joint.parent, joint.rest_offset_m.x(), joint.rest_offset_m.y(),
                           joint.rest_offset_m.z());
    }
  }
  return content_key(bytes);
}

json clips_json(const MotionDatabase& db) {
  json clips = json::array();
  for (const DatabaseClip& clip : db.clips) {
    json tags = json::array();
    for (size_t t = 0; t < db.tag_names.size(); ++t) {
      for (const TagRange& range : db.tag_ranges) {
        if (range.tag == static_cast<int>(t) && range.first_frame < clip.first_frame + clip.frame_count &&
            range.first_frame + range.frame_count > clip.first_frame) {
          tags.push_back(db.tag_names[t]);
          break;
        }
      }
    }
    clips.push_back({{"name", clip.name},
                     {"source", clip.source},
                     {"first_frame", clip.first_frame},
                     {"frames", clip.frame_count},
                     {"tags", tags},
                     {"skeleton", clip.skeleton < static_cast<int>(db.skeleton_names.size())
                                      ? db.skeleton_names[clip.skeleton]
                                      : std::to_string(clip.skeleton)}});
  }
  return clips;
}

Status write_clouds(const MotionDatabase& db, const CloudLayout& layout, const std::string& path) {
  const size_t shape[3] = {static_cast<size_t>(db.frame_count()), static_cast<size_t>(layout.point_count()), 3};
  std::string bytes = npy_header(NpyDtype::kFloat32, shape);
  for (const DatabaseClip& clip : db.clips) {
    npy_append_f32(bytes, compute_clouds(db.skeletons[clip.skeleton], clip.motion, layout));
  }
  return write_file_atomic(path, bytes);
}

json coverage_point_json(const CoveragePoint& p, const MotionDatabase& db, const std::vector<int>& tags) {
  json per_tag = json::object();
  for (size_t i = 0; i < tags.size() && i < p.tag_coverage.size(); ++i) per_tag[db.tag_names[tags[i]]] = p.tag_coverage[i];
  return {{"threshold", p.threshold},     {"rms_cm", p.rms_cm},         {"quantile", p.quantile},
          {"graph", p.graph},             {"coverage", p.coverage},     {"tag_coverage", per_tag},
          {"kept_frames", p.kept_frames}, {"transitions", p.transitions}};
}

// The report's record of the automatic threshold: the target, the ceiling, and the curve of
// coverage against threshold it was chosen on.
json threshold_choice_json(const ThresholdChoice& choice, const MotionDatabase& db,
                           const ThresholdChoiceSettings& settings) {
  json curve = json::array();
  for (const CoveragePoint& p : choice.curve) curve.push_back(coverage_point_json(p, db, choice.tags));
  std::vector<std::string> names;
  json targets = json::object();
  for (size_t i = 0; i < choice.tags.size(); ++i) {
    names.push_back(db.tag_names[choice.tags[i]]);
    targets[names.back()] = choice.targets[i];
  }
  if (choice.tags.empty() && !choice.targets.empty()) targets["all"] = choice.targets[0];
  return {{"coverage_target", settings.coverage},
          {"reachable_share", settings.reachable_share},
          {"min_transition_rate", settings.min_transition_rate},
          {"target_rate", choice.target_rate},
          {"targets", targets},
          {"max_rms_cm", settings.max_rms_cm},
          {"reached", choice.reached},
          {"threshold", choice.threshold},
          {"rms_cm", choice.rms_cm},
          {"motion_types", names},
          {"curve", curve}};
}

json path_check_to_json(const PathCheck& check, const PathCheckSettings& settings) {
  json points = json::array();
  for (const PathCheckPoint& p : check.points) {
    points.push_back({{"threshold", p.threshold},
                      {"rms_cm", p.rms_cm},
                      {"graph", p.graph},
                      {"mean_deviation_m", p.mean_deviation_m},
                      {"max_deviation_m", p.max_deviation_m},
                      {"reached_end", p.reached_end},
                      {"transitions", p.transitions},
                      {"seconds", p.seconds}});
  }
  return {{"tolerance_m", settings.tolerance_m},
          {"probe_length_m", check.probe_length_m},
          {"skipped", check.skipped},
          {"travel_share", check.travel_share},
          {"passed", check.passed},
          {"threshold", check.threshold},
          {"rms_cm", check.rms_cm},
          {"points", points}};
}

// ": walk 64 % of 70 %, run 12 % of 36 %" for the motion types short of their targets.
std::string short_tags_text(const ThresholdChoice& choice, const MotionDatabase& db) {
  const CoveragePoint& p = choice.chosen();
  std::vector<std::string> parts;
  for (size_t i = 0; i < choice.tags.size() && i < p.tag_coverage.size(); ++i) {
    if (p.tag_coverage[i] < choice.targets[i]) {
      parts.push_back(fmt::format("{} {:.0f} % of {:.0f} %", db.tag_names[choice.tags[i]], 100.0 * p.tag_coverage[i],
                                  100.0 * choice.targets[i]));
    }
  }
  return parts.empty() ? std::string() : ": " + fmt::format("{}", fmt::join(parts, ", "));
}

int run_build(BuildOptions o) {
  Stopwatch watch;
  json timings = json::object();
  auto log = [&](const std::string& line) {
    if (!o.quiet) spdlog::info("{}", line);
  };

  // Settings, checked before any work.
  if (o.cloud == "joints") {
    o.cloud_settings.kind = PointCloudSettings::Kind::kJoints;
  } else if (o.cloud != "rings") {
    return fail(Error{"", 0, fmt::format("--cloud must be 'rings' or 'joints', not '{}'", o.cloud)});
  }
  for (const std::string& item : o.joint_weights) {
    const size_t eq = item.find('=');
    char* end = nullptr;
    const double weight = eq == std::string::npos ? -1.0 : std::strtod(item.c_str() + eq + 1, &end);
    if (eq == std::string::npos || end == item.c_str() + eq + 1 || *end != '\0') {
      return fail(Error{"", 0, fmt::format("--joint-weight '{}' is not NAME=WEIGHT", item)});
    }
    o.cloud_settings.joint_weights.emplace_back(item.substr(0, eq), weight);
  }
  if (o.taper == "hann") {
    o.distance.taper = DistanceSettings::Taper::kHann;
  } else if (o.taper != "uniform") {
    return fail(Error{"", 0, fmt::format("--taper must be 'uniform' or 'hann', not '{}'", o.taper)});
  }
  // The threshold: chosen from the data (auto), a quantile of all pairs, D, or an RMS in cm.
  enum class ThresholdMode { kAuto, kQuantile, kDistance, kRmsCm } mode = ThresholdMode::kAuto;
  double threshold_value = 0.0;
  if (o.quantile >= 0.0) {
    if (o.threshold != "auto") return fail(Error{"", 0, "give --threshold or --threshold-quantile, not both"});
    mode = ThresholdMode::kQuantile;
    o.transitions.threshold = -1.0;
    o.transitions.threshold_quantile = o.quantile;
  } else if (o.threshold != "auto") {
    std::string text = o.threshold;
    mode = ThresholdMode::kDistance;
    if (text.size() > 2 && text.compare(text.size() - 2, 2, "cm") == 0) {
      mode = ThresholdMode::kRmsCm;
      text.resize(text.size() - 2);
    }
    const std::optional<double> value = parse_finite(text);
    if (!value || *value < 0.0) {
      return fail(Error{"", 0, fmt::format("--threshold must be 'auto', a distance D >= 0 or an RMS distance such as "
                                           "'4cm', not {}", mg::quoted(o.threshold))});
    }
    threshold_value = *value;
  }
  CandidateSettings candidate_settings;
  candidate_settings.continuation_radius = o.continuation_radius;
  candidate_settings.keep_matrix = !o.export_matrix.empty();
  for (const Status& s : {o.cloud_settings.validate(), o.distance.validate(), o.transitions.validate(),
                          candidate_settings.validate(), o.bridges.validate(), o.choice.validate(), o.path_check.validate(),
                          o.spacing.validate()}) {
    if (!s) return fail(s.error());
  }
  if (fs::path(o.output).extension() != ".mgraph") return fail(Error{o.output, 0, "the graph file must end in .mgraph"});

  // 1. The database.
  DatabaseSettings db_settings;
  db_settings.fps = o.fps;
  db_settings.prefer_manifest_fps = !o.fps_given;
  if (!o.asf.empty()) db_settings.asf_path = o.asf;
  db_settings.bvh_metres_per_unit = o.scale;
  db_settings.input_fps = o.input_fps;
  db_settings.cmu_tags = !o.no_cmu_tags;
  db_settings.cmu_index_path = o.cmu_index.empty() ? find_cmu_index(o.inputs) : o.cmu_index;
  DatabaseLoadNotes load_notes;
  auto db = load_database(o.inputs, db_settings, &load_notes);
  if (!db) return fail(db.error());
  report_units(load_notes, o.quiet);
  timings["load"] = watch.lap();
  log(fmt::format("{} clips, {} frames at {:g} fps ({:.1f} s), {} tags", db->clips.size(), db->frame_count(), db->fps,
                  db->frame_count() / db->fps, db->tag_names.size()));

  // 2. Point clouds and per-frame features.
  auto layout = make_cloud_layout(db->skeletons.front(), o.cloud_settings);
  if (!layout) return fail(layout.error());
  auto features = make_frame_features(*db, *layout, o.distance);
  if (!features) return fail(features.error());
  if (features->window < 2) return fail(Error{"", 0, "the window must be at least 2 frames (raise --fps or --window)"});
  timings["clouds"] = watch.lap();

  // 3. The distance stage, from the cache when the same inputs and settings were seen.
  const json distance_json = distance_settings_json(o, *features);
  const std::uint64_t key = database_key(*db, distance_json);
  const std::string cache_dir = o.cache_dir.empty() ? default_cache_dir() : o.cache_dir;
  const std::string cache_path = (fs::path(cache_dir) / fmt::format("{:016x}.mgcache", key)).string();
  // The cache holds no matrix: with --export-matrix the stage runs (and refreshes the cache).
  const bool use_cache = !o.no_cache;
  std::optional<CandidateSearch> candidates;
  bool cache_hit = false;
  if (use_cache && o.export_matrix.empty() && fs::exists(cache_path)) {
    auto bytes = read_text_file(cache_path);
    if (bytes) {
      auto cached = parse_distance_cache(*bytes, cache_path, key);
      if (cached) {
        candidates = std::move(*cached);
        cache_hit = true;
        log(fmt::format("distance stage: from the cache {}", cache_path));
      } else {
        spdlog::warn("{} (computing again)", cached.error().to_string());
      }
    }
  }
  if (!candidates) {
    const long long tiles_per_side = (features->frames + o.distance.tile_frames - 1) / o.distance.tile_frames;
    ProgressBar progress("distance", static_cast<std::uint64_t>(tiles_per_side * tiles_per_side), o.quiet);
    auto search = find_candidates(*features, o.distance, candidate_settings,
                                  [&](long long, long long) { progress.advance(1); });
    progress.finish();
    if (!search) return fail(search.error());
    candidates = std::move(*search);
    log(fmt::format("distance stage: {} x {} pairs in {:.2f} s, {} local minima", features->frames, features->frames,
                    candidates->tiles.seconds, candidates->minima.size()));
    if (use_cache) {
      std::error_code ec;
      fs::create_directories(cache_dir, ec);
      if (auto s = write_file_atomic(cache_path, serialize_distance_cache(key, *candidates)); !s) {
        spdlog::warn("cannot cache the distance stage: {}", s.error().to_string());
      }
    }
  }
  timings["distance"] = watch.lap();

  // 4. Transitions.
  // Motion types: the tags whose regions must stay connected, with their own thresholds.
  TagMask connected = motion_type_tags(*db);
  if (!o.connect_tags.empty()) {
    auto mask = tag_mask_of(*db, o.connect_tags);
    if (!mask) return fail(Error{"", 0, "--connect-tags: " + mask.error().message});
    connected = *mask;
  }
  GraphFromCandidatesSettings graph_settings;
  graph_settings.transitions = o.transitions;
  graph_settings.spacing = o.spacing;
  graph_settings.bridges = o.bridges;
  graph_settings.connected_tags = o.ignore_tags ? 0 : connected;
  json choice_json = nullptr;
  json path_check_json = nullptr;
  const char* mode_name = "quantile";
  if (mode == ThresholdMode::kAuto) {
    mode_name = "auto";
    auto choice = choose_threshold(*db, *features, *candidates, graph_settings, o.choice);
    if (!choice) return fail(choice.error());
    graph_settings.transitions.threshold = choice->threshold;
    graph_settings.transitions.max_threshold = distance_of_rms_cm(o.choice.max_rms_cm, *features);
    choice_json = threshold_choice_json(*choice, *db, o.choice);
    const CoveragePoint& chosen = choice->chosen();
    std::vector<std::string> kept;
    for (size_t i = 0; i < choice->tags.size(); ++i) {
      kept.push_back(fmt::format("{} {:.0f} %", db->tag_names[choice->tags[i]], 100.0 * chosen.tag_coverage[i]));
    }
    if (choice->tags.empty()) kept.push_back(fmt::format("{:.0f} % of the frames", 100.0 * chosen.coverage));
    log(fmt::format("threshold auto: RMS {:.2f} cm keeps {} ({} thresholds tried)", choice->rms_cm,
                    fmt::join(kept, ", "), choice->curve.size()));
    if (!choice->reached) {
      spdlog::warn("no threshold up to --max-threshold {:g} cm reaches the coverage wanted{}", o.choice.max_rms_cm,
                   short_tags_text(*choice, *db));
    }
    if (!o.no_path_check) {
      auto check = check_path_following(*db, *features, *candidates, graph_settings, choice->threshold,
                                        graph_settings.transitions.max_threshold, o.path_check);
      if (!check) return fail(check.error());
      path_check_json = path_check_to_json(*check, o.path_check);
      const PathCheckPoint& first = check->points.front();
      const PathCheckPoint* picked = check->chosen();
      if (check->skipped) {
        log(fmt::format("path check: skipped, the library hardly travels ({:.0f} % of its frames at {:g} m/s or more)",
                        100.0 * check->travel_share, o.path_check.travel_speed_mps));
      } else if (check->passed && check->points.size() == 1) {
        log(fmt::format("path check: a {:.0f} m test path is followed at {:.3f} m mean deviation", check->probe_length_m,
                        first.mean_deviation_m));
      } else if (check->passed) {
        log(fmt::format("path check: the test path is followed {:.3f} m off at RMS {:.2f} cm; raised to RMS {:.2f} cm, "
                        "where it is followed at {:.3f} m",
                        first.mean_deviation_m, first.rms_cm, check->rms_cm, picked->mean_deviation_m));
      } else {
        spdlog::warn("path check: no threshold up to --max-threshold {:g} cm follows the test path within {:g} m; the "
                     "best, RMS {:.2f} cm, follows it {:.3f} m off{} (the clips may hold few turns)",
                     o.choice.max_rms_cm, o.path_check.tolerance_m, check->rms_cm, picked->mean_deviation_m,
                     picked->reached_end ? "" : " and does not reach its end");
      }
      graph_settings.transitions.threshold = check->threshold;
    }
  } else if (mode == ThresholdMode::kDistance) {
    mode_name = "distance";
    graph_settings.transitions.threshold = threshold_value;
  } else if (mode == ThresholdMode::kRmsCm) {
    mode_name = "rms_cm";
    graph_settings.transitions.threshold = distance_of_rms_cm(threshold_value, *features);
  }
  auto selected = select_transitions_with_bridges(*db, *features, *candidates, graph_settings);
  if (!selected) return fail(selected.error());
  const TransitionSelection& selection = selected->selection;
  const std::vector<Transition>& bridges = selected->bridges;
  const std::vector<Transition>& all_transitions = selected->all_transitions;
  json tag_thresholds_json = json::array();
  for (const TagThreshold& t : selection.tag_thresholds) {
    tag_thresholds_json.push_back({{"tag", db->tag_names[t.tag]},
                                   {"candidates", t.candidates},
                                   {"threshold", t.threshold},
                                   {"rms_cm", rms_cm_of_distance(t.threshold, *features)}});
  }
  json bridges_json = json::array();
  for (const Transition& t : bridges) {
    bridges_json.push_back({{"from_frame", t.from_frame},
                            {"to_frame", t.to_frame},
                            {"distance", t.distance},
                            {"rms_cm", rms_cm_of_distance(t.distance, *features)}});
  }
  if (!bridges.empty()) log(fmt::format("{} bridges between motion types", bridges.size()));
  timings["transitions"] = watch.lap();
  const double threshold_rms_cm = rms_cm_of_distance(selection.threshold, *features);
  log(fmt::format("threshold {:.4g} (RMS {:.2f} cm; {:.3f} % of pairs below): {} transitions",
                  selection.threshold, threshold_rms_cm, 100.0 * selection.threshold_quantile,
                  selection.transitions.size()));

  // 5. The graph, pruned.
  auto built = build_spaced_graph(*db, *selected, *features, graph_settings);
  if (!built && built.error().kind != ErrorKind::kEmptyGraph) return fail(built.error());
  timings["graph"] = watch.lap();
  if (built) {
    const PruneReport& pruned = built->prune;
    log(fmt::format("graph: {} nodes, {} edges ({} transitions) after pruning and spacing; {} transitions survived "
                    "a first pruning, spaced to {}",
                    pruned.after.nodes, pruned.after.edges, pruned.after.transitions, built->survived_first_pruning,
                    pruned.before.transitions));
  }

  // 6. Outputs: the exports and the report are written even when no graph can be made, so that
  // the user can see why.
  std::vector<double> point_weights(layout->weight.begin(), layout->weight.end());
  json report = {
      {"frames", db->frame_count()},
      {"fps", db->fps},
      {"window", features->window},
      {"points", layout->point_count()},
      {"point_weights", point_weights},
      {"window_weights", features->taper},
      {"window_weight", features->window_weight},
      {"clips", clips_json(*db)},
      {"tags", db->tag_names},
      {"distance_settings", distance_json},
      {"threshold_mode", mode_name},
      {"threshold", selection.threshold},
      {"threshold_rms_cm", threshold_rms_cm},
      {"threshold_quantile", selection.threshold_quantile},
      {"threshold_choice", choice_json},
      {"path_check", path_check_json},
      {"locality_radius", selection.locality_radius},
      {"spacing",
       {{"out_window_frames", o.spacing.out_window_for(features->window)},
        {"min_piece_frames", o.spacing.min_piece_frames},
        {"max_out", o.spacing.max_out}}},
      {"tag_thresholds", tag_thresholds_json},
      {"counts",
       {{"pairs", static_cast<long long>(features->frames) * features->frames},
        {"finite_pairs", candidates->histogram.total()},
        {"local_minima", candidates->minima.size()},
        {"below_threshold", selection.candidates_below_threshold},
        {"transitions", selection.transitions.size()},
        {"survived_first_pruning", built ? built->survived_first_pruning : 0},
        {"spaced", built ? built->prune.before.transitions : 0},
        {"bridges", bridges.size()},
        {"transitions_kept", built ? built->prune.after.transitions : 0}}},
      {"graph_before", built ? json::parse(to_json(built->prune.before, db->tag_names)) : json(nullptr)},
      {"graph_after", built ? json::parse(to_json(built->prune.after, db->tag_names)) : json(nullptr)},
      {"bridges", bridges_json},
      {"distance_cache", cache_hit ? "hit" : (use_cache ? "stored" : "off")},
  };
  std::vector<int> clip_starts;
  for (const DatabaseClip& clip : db->clips) clip_starts.push_back(clip.first_frame);
  if (!o.matrix_png.empty()) {
    MatrixPngSettings png;
    auto bytes = candidates->matrix.empty()
                     ? matrix_png(MinMatrixView{candidates->picture, candidates->picture_side, candidates->picture_block},
                                  clip_starts, all_transitions, png)
                     : matrix_png(candidates->matrix, features->frames, clip_starts, all_transitions, png);
    if (!bytes) return fail(Error{o.matrix_png, 0, bytes.error().message});
    if (auto s = write_file_atomic(o.matrix_png, *bytes); !s) return fail(s.error());
  }
  if (!o.export_matrix.empty()) {
    const size_t shape[2] = {static_cast<size_t>(features->frames), static_cast<size_t>(features->frames)};
    if (auto s = write_file_atomic(o.export_matrix, npy_bytes_f32(shape, candidates->matrix)); !s) return fail(s.error());
  }
  if (!o.export_clouds.empty()) {
    if (auto s = write_clouds(*db, *layout, o.export_clouds); !s) return fail(s.error());
  }
  candidates->matrix.clear();
  timings["exports"] = watch.lap();

  if (!built) {
    // No graph: say which threshold would make one, and what it would keep.
    auto lowest = lowest_graph_threshold(*db, *features, *candidates, graph_settings, selection.threshold);
    if (!lowest) return fail(lowest.error());
    std::string advice = "no threshold makes a graph: the clips hold no loop of transitions at all";
    if (*lowest) {
      const CoveragePoint& p = **lowest;
      advice = fmt::format("the lowest threshold that makes one is RMS {:.2f} cm (--threshold {:.2f}cm, D {:.4g}, "
                           "{:.3f} % of pairs); it keeps {:.0f} % of {}",
                           p.rms_cm, std::ceil(p.rms_cm * 100.0) / 100.0, p.threshold, 100.0 * p.quantile,
                           100.0 * p.coverage, graph_settings.connected_tags ? "each motion type's frames" : "the frames");
      report["lowest_graph_threshold"] = coverage_point_json(p, *db, coverage_tags(graph_settings));
    }
    report["error"] = "pruning left nothing";
    report["timings"] = timings;
    if (!o.report.empty()) {
      if (auto s = write_file_atomic(o.report, json_text(report, 2) + "\n"); !s) return fail(s.error());
    }
    return fail(Error{"", 0, fmt::format("no graph at threshold RMS {:.2f} cm: pruning left nothing (the transitions "
                                         "form no loop); {}", threshold_rms_cm, advice)});
  }

  // What eval needs to select transitions again as this build did.
  const std::vector<std::string> connected_names = db->tag_names_of(graph_settings.connected_tags);
  GraphFile file;
  file.settings_json = json_text(json({{"distance", distance_json},
                                       {"threshold", selection.threshold},
                                       {"threshold_quantile", selection.threshold_quantile},
                                       {"threshold_mode", mode_name},
                                       {"max_threshold", graph_settings.transitions.max_threshold},
                                       {"locality_radius", selection.locality_radius},
                                       {"per_tag_thresholds", o.transitions.per_tag_thresholds},
                                       {"min_piece_frames", o.spacing.min_piece_frames},
                                       {"out_window_frames", o.spacing.out_window_frames},
                                       {"max_out", o.spacing.max_out},
                                       {"connected_tags", connected_names},
                                       {"bridges_per_tag_pair", o.bridges.per_tag_pair},
                                       {"fps", db->fps}}));
  file.input_key = key;
  file.threshold = selection.threshold;
  file.threshold_quantile = selection.threshold_quantile;
  file.locality_radius = selection.locality_radius;
  file.graph = std::move(built->graph);
  file.candidates = std::move(*candidates);
  file.database = std::move(*db);
  report["timings"] = timings;
  file.report_json = json_text(report);
  if (auto s = write_file_atomic(o.output, serialize_graph_file(file)); !s) return fail(s.error());
  if (!o.report.empty()) {
    report["timings"]["write"] = watch.lap();
    if (auto s = write_file_atomic(o.report, json_text(report, 2) + "\n"); !s) return fail(s.error());
  }
  log(fmt::format("wrote {}", o.output));
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
  sub->add_flag("--ignore-tags", o->ignore_tags, "Prune to the largest strongly connected component only, ignoring tags");
  sub->add_option("--bridges", o->bridges.per_tag_pair,
                  "Bridges per ordered pair of tags that no transition below the threshold joins: their best candidates "
                  "(0: none)")
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
