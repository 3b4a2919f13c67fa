// build_graph(): the build pipeline, stage by stage, with its timings.
#include "motiongraph/pipeline/build_graph.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "motiongraph/core/counted.h"
#include "motiongraph/core/json_text.h"
#include "motiongraph/core/progress.h"
#include "motiongraph/core/stop.h"
#include "motiongraph/core/transition_rate.h"
#include "motiongraph/database/database_loader.h"
#include "motiongraph/export/matrix_png.h"
#include "motiongraph/export/npy.h"
#include "motiongraph/graph/clip_coverage.h"
#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/graph/on_demand_candidates.h"
#include "motiongraph/graph/pruned_candidates.h"
#include "motiongraph/metric/frame_features.h"
#include "motiongraph/pipeline/build_report.h"
#include "motiongraph/pipeline/saved_settings.h"
#include "motiongraph/synthesis/walk.h"

namespace mg {

namespace {

using nlohmann::json;

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

// ": walk 64 % of 70 %, run 12 % of 36 %" for the motion types short of their targets.
std::string short_tags_text(const ThresholdChoice& choice, const MotionDatabase& db) {
  const CoveragePoint& p = choice.chosen();
  std::vector<std::string> parts;
  for (size_t i = 0; i < choice.tags.size() && i < p.tag_coverage.size(); ++i) {
    if (p.tag_coverage[i] < choice.targets[i]) {
      parts.push_back(fmt::format("{} {:.0f} % of {:.0f} %", motion_class_name(db, choice.tags[i]),
                                  100.0 * p.tag_coverage[i], 100.0 * choice.targets[i]));
    }
  }
  return parts.empty() ? std::string() : ": " + fmt::format("{}", fmt::join(parts, ", "));
}

// The warning for the clips of no motion type that hold every type's threshold up
// (ThresholdChoice::untagged_holds): which they are, and how to make them a type's.
// name_tags: whether clips are tagged by their names (DatabaseSettings::name_tags).
std::string untagged_holds_text(const MotionDatabase& db, TagMask connected, double rest_rms_cm, bool name_tags) {
  const std::vector<char> in_class = untagged_class_frames(db, connected);
  std::vector<std::string> clips;
  long long frames = 0;
  for (const DatabaseClip& clip : db.clips) {
    if (clip.frame_count > 0 && in_class[static_cast<size_t>(clip.first_frame)] != 0) {
      clips.push_back(clip.name);
      frames += clip.frame_count;
    }
  }
  const bool one = clips.size() == 1;
  const std::string named = name_tags ? fmt::format(", or {} that {} {} motion (walk_07.bvh),",
                                                    one ? "a name" : "names", one ? "says" : "say",
                                                    one ? "its" : "their")
                                      : std::string(",");
  return fmt::format("{} of no motion type ({}{}; {:.0f} % of the frames) {} the graph only where every type's "
                     "threshold rises to let {} in, and {} them there (RMS {:.2f} cm for the rest): tags in a "
                     "manifest{} would let them fall",
                     counted(static_cast<long long>(clips.size()), "clip"), clips.empty() ? "" : clips.front(),
                     clips.size() > 1 ? fmt::format(" and {} more", clips.size() - 1) : "",
                     100.0 * static_cast<double>(frames) / std::max(1, db.frame_count()), one ? "joins" : "join",
                     one ? "it" : "them", one ? "holds" : "hold", rest_rms_cm, named);
}

// The log's two voices, silent where the caller gave none; the warnings are also kept for the
// report's "warnings".
struct Say {
  const BuildLog& log;
  std::vector<std::string>* warnings = nullptr;
  void info(const std::string& line) const {
    if (log.info) log.info(line);
  }
  void warning(const std::string& line) const {
    if (warnings != nullptr) warnings->push_back(line);
    if (log.warning) log.warning(line);
  }
};

// The distance stage's candidates, from the cache when it holds `key` (rank 0's cache: the
// team follows its answer), else found by the team.
struct Candidates {
  CandidateSearch search;
  const char* cache = "off";  // "hit", "stored" or "off"
  PrunedSearchStatistics pruned;  // the pruned stage's plan, when it ran (not from the cache)
  int processes = 1;
  std::vector<double> peak_memory_mb, share_seconds;
  long long restored_tiles = 0;
  PrunedStageWork work;  // what the pruned stage made beyond its result, when it ran
};

// The pruned stage's settings for the build: the distance stage's threads.
PrunedSearchSettings pruned_settings(const BuildSettings& settings) {
  PrunedSearchSettings pruned = settings.pruned;
  pruned.threads = settings.distance_stage.distance.threads;
  return pruned;
}

CandidateSettings candidate_settings_of(const BuildSettings& settings) {
  CandidateSettings candidates;
  candidates.continuation_radius = settings.distance_stage.continuation_radius;
  candidates.keep_matrix = settings.exports.matrix_npy;
  return candidates;
}

// The pruned stage's ceiling: the upper edge of the histogram bin of the quality ceiling's D, so
// that every pair of that bin is computed and the histograms' fractions are exact up to it.
double pruned_ceiling(const BuildSettings& settings, const FrameFeatures& features) {
  return DistanceHistogram::bin_upper_edge(
      DistanceHistogram::bin_of(distance_of_rms_cm(settings.choice.max_rms_cm, features)));
}

// What decides the distance stage's result besides the settings' JSON form: which stage, its
// ceiling and the tile side (ties between local minima depend on it). Part of the cache key.
json distance_key_json(const BuildSettings& settings, bool pruned, const FrameFeatures& features,
                       json distance_json) {
  if (pruned) {
    distance_json["stage"] = "pruned";
    distance_json["ceiling"] = pruned_ceiling(settings, features);
    distance_json["tile"] = pruned_settings(settings).tile_for(features.window);
  } else {
    distance_json["stage"] = "exhaustive";
    distance_json["tile"] = settings.distance_stage.distance.tile_frames;
  }
  return distance_json;
}

// `log`: this process's (rank 0's bars, progress lines and stop; the others' are silent).
Result<Candidates> distance_stage(bool pruned, const FrameFeatures& features, const BuildSettings& settings,
                                  DistanceCache* cache, std::uint64_t key, const Say& say, const BuildLog& log,
                                  ProcessTeam& team) {
  // The cache holds no matrix: with the matrix export the stage runs (and refreshes the cache).
  const bool keep_matrix = settings.exports.matrix_npy;
  std::optional<CandidateSearch> hit;
  if (team.rank() == 0 && cache != nullptr && !keep_matrix) {
    auto cached = cache->find(key);
    if (!cached) {
      say.warning(fmt::format("{} (computing again)", cached.error().to_string()));
    } else if (*cached) {
      say.info(fmt::format("distance stage: from the cache {}", cache->location(key)));
      hit = std::move(**cached);
    }
  }
  if (team.broadcast(hit.has_value())) {
    Candidates out;
    if (hit) out.search = std::move(*hit);
    out.cache = "hit";
    out.processes = team.size();
    return out;
  }
  const CandidateSettings candidate_settings = candidate_settings_of(settings);
  SharedSearchSettings shared = settings.shared;
  shared.progress_bar = log.progress_bar;
  shared.progress_lines = log.progress;
  shared.stop = log.stop;
  // The pruned stage: the plan (the same on every process), its items shared as the
  // exhaustive stage's are, then what lies above the ceiling set aside.
  const auto start = std::chrono::steady_clock::now();
  const double ceiling = pruned_ceiling(settings, features);
  PrunedSearchStatistics plan_statistics;
  std::optional<PrunedPlan> plan;
  if (pruned) {
    auto made = plan_pruned_search(features, ceiling, pruned_settings(settings), &plan_statistics);
    if (!made) return made.error();
    plan = std::move(*made);
  }
  if (auto s = team.agree(check_stop(log.stop)); !s) return s.error();
  auto found = find_candidates_shared(features, plan ? plan->distance : settings.distance_stage.distance,
                                      candidate_settings, key, team, shared, plan ? &plan->items : nullptr,
                                      plan ? &plan->sides : nullptr);
  if (!found) return found.error();
  Candidates out{std::move(found->search), "off", plan_statistics, found->processes, std::move(found->peak_memory_mb),
                 std::move(found->share_seconds), found->restored_tiles, {}};
  if (team.rank() != 0) return out;
  if (pruned) {
    out.pruned.computed_pairs = out.search.tiles.pairs;
    out.pruned.exact_seconds = out.search.tiles.seconds;
    out.work.embedding = std::move(plan->embedding);
    out.work.tiles = std::move(plan->tiles);
    for (const Transition& t : out.search.minima) {
      if (t.distance > ceiling) out.work.above.push_back(t);
    }
    finish_pruned_search(features, ceiling, out.search);
    out.search.tiles.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const std::string restored =
      out.restored_tiles > 0 ? fmt::format(" ({} tiles from the checkpoint)", out.restored_tiles) : "";
  const std::string processes = team.size() > 1 ? fmt::format(" on {} processes", team.size()) : "";
  if (pruned) {
    const PrunedSearchStatistics& p = out.pruned;
    say.info(fmt::format("distance stage (pruned below RMS {:g} cm): {} of {} tiles of {} frames ({:.1f} %) in "
                         "{:.2f} s{}{}, {} local minima below the ceiling",
                         settings.choice.max_rms_cm, p.tiles_computed, p.tiles, p.tile_frames,
                         p.tiles > 0 ? 100.0 * static_cast<double>(p.tiles_computed) / static_cast<double>(p.tiles)
                                     : 0.0,
                         out.search.tiles.seconds, processes, restored, out.search.minima.size()));
  } else {
    say.info(fmt::format("distance stage: {} x {} pairs in {:.2f} s{}{}, {} local minima", features.frames,
                         features.frames, out.search.tiles.seconds, processes, restored, out.search.minima.size()));
  }
  if (cache == nullptr) return out;
  if (auto s = cache->store(key, out.search); !s) {
    say.warning(fmt::format("cannot cache the distance stage: {}", s.error().to_string()));
  }
  out.cache = "stored";
  return out;
}

// A motion type the automatic threshold did not rise for: the ceiling keeps too little of it
// (kMinServedShare). Warned of once the graph is made, with what the graph keeps of it (the path
// check may raise the threshold after the choice).
struct NotChased {
  int tag = 0;
  double ceiling_share = 0.0;
};

// The transition settings with the threshold the settings ask for; for kAuto, chosen from the
// data and path-checked (their report parts in choice_json and check_json; the motion types it
// did not rise for in not_chased).
Result<GraphFromCandidatesSettings> threshold_settings(const MotionDatabase& db, const FrameFeatures& features,
                                                       const CandidateSearch& candidates, const BuildSettings& settings,
                                                       OnDemandCandidates* more, const Say& say,
                                                       const std::stop_token& stop, json& choice_json,
                                                       json& check_json, std::vector<NotChased>& not_chased) {
  auto connected = settings.connected_tags(db);
  if (!connected) return connected.error();
  GraphFromCandidatesSettings graph_settings;
  graph_settings.transitions = settings.transitions;
  graph_settings.spacing = settings.spacing;
  graph_settings.bridges = settings.bridges;
  graph_settings.bridges.max_distance =
      settings.max_bridge_rms_cm > 0.0 ? distance_of_rms_cm(settings.max_bridge_rms_cm, features) : -1.0;
  graph_settings.connected_tags = *connected;
  switch (settings.threshold_mode) {
    case ThresholdMode::kQuantile:
      graph_settings.transitions.threshold = -1.0;
      graph_settings.transitions.threshold_quantile = settings.threshold_value;
      return graph_settings;
    case ThresholdMode::kDistance:
      graph_settings.transitions.threshold = settings.threshold_value;
      return graph_settings;
    case ThresholdMode::kRmsCm:
      graph_settings.transitions.threshold = distance_of_rms_cm(settings.threshold_value, features);
      return graph_settings;
    case ThresholdMode::kAuto:
      break;
  }
  ThresholdChoiceSettings choice_settings = settings.choice;
  choice_settings.stop = stop;
  if (say.log.progress) {
    choice_settings.tried = [&say, clock = ProgressLineClock()](const CoveragePoint& point, int tried) mutable {
      if (!clock.due()) return;
      say.log.progress(fmt::format("threshold choice: {} tried in {:.1f} s (RMS {:.2f} cm keeps {:.0f} % of the worst "
                                   "type's frames)",
                                   counted(tried, "threshold"), clock.elapsed_s(), point.rms_cm,
                                   100.0 * point.coverage));
    };
  }
  auto choice = choose_threshold(db, features, candidates, graph_settings, choice_settings, more);
  if (!choice) return choice.error();
  if (auto s = check_stop(stop); !s) return s.error();
  graph_settings = with_chosen_thresholds(graph_settings, *choice);
  graph_settings.transitions.max_threshold = distance_of_rms_cm(choice_settings.max_rms_cm, features);
  choice_json = threshold_choice_json(*choice, db, choice_settings);
  const CoveragePoint& chosen = choice->chosen();
  std::vector<std::string> kept;
  for (size_t i = 0; i < choice->tags.size(); ++i) {
    if (choice->tag_thresholds.empty()) {
      kept.push_back(
          fmt::format("{} {:.0f} %", motion_class_name(db, choice->tags[i]), 100.0 * chosen.tag_coverage[i]));
    } else if (choice->targets[i] <= 0.0) {
      // The ceiling (the highest point tried) kept none, or too few to chase (kMinServedShare).
      const double top = choice->curve.empty() ? 0.0 : choice->curve.back().tag_coverage[i];
      const std::string name = motion_class_name(db, choice->tags[i]);
      if (top <= 0.0) {
        kept.push_back(fmt::format("{} none at any threshold", name));
      } else {
        kept.push_back(fmt::format("{} {:.1f} % (the ceiling keeps {:.1f} %: not chased)", name,
                                   100.0 * chosen.tag_coverage[i], 100.0 * top));
        if (choice->tags[i] != kUntaggedClass) not_chased.push_back({choice->tags[i], top});
      }
    } else {
      kept.push_back(fmt::format("{} {:.0f} % at {:.2f} cm", motion_class_name(db, choice->tags[i]),
                                 100.0 * chosen.tag_coverage[i],
                                 rms_cm_of_distance(choice->tag_thresholds[i], features)));
    }
  }
  if (choice->tags.empty()) kept.push_back(fmt::format("{:.0f} % of the frames", 100.0 * chosen.coverage));
  if (choice->tag_thresholds.empty()) {
    say.info(fmt::format("threshold auto: RMS {:.2f} cm keeps {} ({} thresholds tried)", choice->rms_cm,
                         fmt::join(kept, ", "), choice->curve.size()));
  } else {
    say.info(fmt::format("threshold auto, one per motion type: {}; RMS {:.2f} cm for the rest ({} points tried)",
                         fmt::join(kept, ", "), choice->rms_cm, choice->curve.size()));
  }
  if (choice->untagged_holds) {
    say.warning(
        untagged_holds_text(db, graph_settings.connected_tags, choice->rms_cm, settings.database.name_tags));
  }
  if (!choice->reached) {
    say.warning(fmt::format("no threshold up to --max-threshold {:g} cm reaches the coverage wanted{}",
                            choice_settings.max_rms_cm, short_tags_text(*choice, db)));
  }
  if (choice->target_rate < choice_settings.min_transition_rate) {
    // The rate asked is out of reach: the search aimed for what the ceiling's graph offers (said;
    // a graph too poor in transitions is warned of as such once built).
    say.info(fmt::format("even the ceiling's graph (--max-threshold {:g} cm) offers only {:.2f} transitions a "
                         "second of the motion it keeps, under the {:g} asked (--min-transition-rate): the "
                         "threshold aims for {:.2f}",
                         choice_settings.max_rms_cm, choice->target_rate, choice_settings.min_transition_rate,
                         choice->target_rate));
  }
  if (!settings.path_check) return graph_settings;
  PathCheckSettings check_settings = settings.path_check_settings;
  check_settings.synthesis.stop = stop;
  ProgressLineClock check_clock;  // one line every 2 s, whether a threshold is done or a probe on its way
  if (say.log.progress) {
    check_settings.tried = [&say, &check_clock](const PathCheckPoint& point, int tried) {
      if (!check_clock.due()) return;
      say.log.progress(fmt::format("path check: {} tried in {:.1f} s (at RMS {:.2f} cm the probe {})",
                                   counted(tried, "threshold"), check_clock.elapsed_s(), point.rms_cm,
                                   point.graph ? fmt::format("followed {:.3f} m off", point.mean_deviation_m)
                                               : std::string("has no graph")));
    };
    const double probe_m = path_check_probe().length_m();
    check_settings.searching = [&say, &check_clock, probe_m](double rms_cm, int probe, double arc_m) {
      if (!check_clock.due()) return;
      say.log.progress(fmt::format("path check: at RMS {:.2f} cm, {} {:.1f} m of {:.1f} m along in {:.1f} s", rms_cm,
                                   probe == 0 ? "the test path" : "its mirror", arc_m, probe_m,
                                   check_clock.elapsed_s()));
    };
  }
  auto check = check_path_following(db, features, candidates, graph_settings, choice->threshold,
                                    graph_settings.transitions.max_threshold, check_settings, more);
  if (!check) return check.error();
  check_json = path_check_json(*check, check_settings);
  const PathCheckPoint& first = check->points.front();
  const PathCheckPoint* picked = check->chosen();
  // With the mirror, each figure is the worse of the probe and its mirror.
  const bool both = check_settings.mirrored;
  const std::string probes = both ? "the test path and its mirror" : "the test path";
  const std::string worse = both ? ", the worse of the two" : "";
  const std::string them = both ? "them" : "it";
  if (check->skipped) {
    say.info(fmt::format("path check: skipped, the library hardly travels ({:.0f} % of its frames at {:g} m/s or more)",
                         100.0 * check->travel_share, check_settings.travel_speed_mps));
  } else if (check->passed && check->points.size() == 1) {
    say.info(fmt::format("path check: {} ({:.0f} m) followed at {:.3f} m mean deviation{}", probes,
                         check->probe_length_m, first.mean_deviation_m, worse));
  } else if (check->passed) {
    say.info(fmt::format("path check: {} followed {:.3f} m off at RMS {:.2f} cm{}; raised to RMS {:.2f} cm, where "
                         "followed at {:.3f} m",
                         probes, first.mean_deviation_m, first.rms_cm, worse, check->rms_cm, picked->mean_deviation_m));
  } else {
    const PathCheckPoint* delivered = check->delivered ? &*check->delivered : nullptr;
    // Both probes' deviations when both were walked: the worse is judged by the way it covered
    // first, so that it need not be the one further off.
    auto off = [&](const PathCheckPoint& p) {
      const auto& d = p.probe_deviations_m;
      return both && std::isfinite(d[0]) && std::isfinite(d[1])
                 ? fmt::format("the test path {:.3f} m off and its mirror {:.3f} m off", d[0], d[1])
                 : fmt::format("{} {:.3f} m off{}", them, p.mean_deviation_m, worse);
    };
    const std::string covered =
        picked->reached_end ? ""
                            : fmt::format(", {} {:.0f} m of its {:.0f} m", both ? "the worse covering" : "covering",
                                          picked->arc_covered_m, check->probe_length_m);
    say.warning(fmt::format(
        "path check: no threshold up to --max-threshold {:g} cm lets the graph's own walks follow {} within {:g} m; "
        "the best, RMS {:.2f} cm, follows {}{} (the clips may hold few turns){}",
        choice_settings.max_rms_cm, probes, check_settings.tolerance_m, check->rms_cm, off(*picked), covered,
        delivered == nullptr ? ""
                             : fmt::format("; `path`, bending the motion onto the path, follows {}{}", off(*delivered),
                                           delivered->reached_end ? "" : ", short of its end")));
  }
  graph_settings.transitions.threshold = check->threshold;
  return graph_settings;
}

// The report's "distance_stage": which stage ran and, for the pruned one, what it computed:
// {"stage", "tile_frames", "seconds"} and {"ceiling", "ceiling_rms_cm", "tiles", "tiles_computed",
// "computed_pairs", "embedding_seconds", "search_seconds", "on_demand": {"raises", "tiles",
// "pairs", "seconds", "search_seconds", "tile_seconds", "minima"}} (the plan's figures are null
// when the stage came from the cache).
json distance_stage_json(const CandidateSearch& search, const PrunedSearchStatistics& plan,
                         const OnDemandCandidates* more, const char* cache, const FrameFeatures& features) {
  json out = {{"stage", search.ceiling >= 0.0 ? "pruned" : "exhaustive"},
              {"tile_frames", search.tile_frames},
              {"seconds", search.tiles.seconds}};
  if (search.ceiling < 0.0) return out;
  const bool planned = std::string(cache) != "hit";
  out["ceiling"] = search.ceiling;
  out["ceiling_rms_cm"] = rms_cm_of_distance(search.ceiling, features);
  out["tiles"] = planned ? json(plan.tiles) : json(nullptr);
  out["tiles_computed"] = planned ? json(plan.tiles_computed) : json(nullptr);
  out["computed_pairs"] = search.tiles.pairs;
  out["embedding_seconds"] = planned ? json(plan.embedding_seconds) : json(nullptr);
  out["search_seconds"] = planned ? json(plan.search_seconds) : json(nullptr);
  if (more != nullptr) {
    const OnDemandStatistics& s = more->statistics();
    out["on_demand"] = {{"raises", s.raises},
                        {"tiles", s.tiles},
                        {"pairs", s.pairs},
                        {"seconds", s.seconds},
                        {"search_seconds", s.search_seconds},
                        {"tile_seconds", s.tile_seconds},
                        {"minima", more->above().size()}};
  }
  return out;
}

// The exports asked for, as bytes.
Status make_exports(const BuildSettings& settings, const MotionDatabase& db, const CloudLayout& layout,
                    const FrameFeatures& features, const CandidateSearch& candidates,
                    std::span<const Transition> all_transitions, GraphBuild& out) {
  if (settings.exports.matrix_png) {
    std::vector<int> clip_starts;
    for (const DatabaseClip& clip : db.clips) clip_starts.push_back(clip.first_frame);
    MatrixPngSettings png;
    auto bytes = candidates.matrix.empty()
                     ? matrix_png(MinMatrixView{candidates.picture, candidates.picture_side, candidates.picture_block},
                                  clip_starts, all_transitions, png)
                     : matrix_png(candidates.matrix, features.frames, clip_starts, all_transitions, png);
    if (!bytes) return bytes.error();
    out.matrix_png = std::move(*bytes);
  }
  if (settings.exports.matrix_npy) {
    const size_t shape[2] = {static_cast<size_t>(features.frames), static_cast<size_t>(features.frames)};
    out.matrix_npy = npy_bytes_f32(shape, candidates.matrix);
  }
  if (settings.exports.clouds_npy) {
    const size_t shape[3] = {static_cast<size_t>(db.frame_count()), static_cast<size_t>(layout.point_count()), 3};
    out.clouds_npy = npy_header(NpyDtype::kFloat32, shape);
    for (const DatabaseClip& clip : db.clips) {
      npy_append_f32(out.clouds_npy, compute_clouds(db.skeletons[clip.skeleton], clip.motion, layout));
    }
  }
  return Ok{};
}

// Stages 1 and 2: the database, its point clouds and per-frame features.
struct Prepared {
  MotionDatabase db;
  CloudLayout layout;
  FrameFeatures features;
  DatabaseLoadNotes notes;  // loading's: the doubts and the mirroring, for the report
};

Result<Prepared> prepare(std::span<const std::string> inputs, const BuildSettings& settings, const BuildLog& log,
                         const Say& say, Stopwatch& watch, json& timings) {
  if (auto s = settings.validate(); !s) return s.error();
  // 1. The database.
  DatabaseLoadNotes load_notes;
  const std::vector<std::string> input_list(inputs.begin(), inputs.end());
  DatabaseSettings database = settings.database;
  database.progress_bar = log.progress_bar;
  database.progress_lines = log.progress;
  database.stop = log.stop;
  auto db = load_database(input_list, database, &load_notes);
  if (!db) return db.error();
  if (log.loaded) log.loaded(load_notes);
  for (const std::string& line : load_warnings(load_notes)) say.warning(line);
  timings["load"] = watch.lap();
  say.info(fmt::format("{}, {} frames at {:g} fps ({:.1f} s), {}", counted(std::ssize(db->clips), "clip"),
                       db->frame_count(), db->fps, db->frame_count() / db->fps,
                       counted(std::ssize(db->tag_names), "tag")));
  if (!db->contacts_error.empty()) {
    say.warning(fmt::format("no foot contacts, so no foot clean-up in synthesis: {} (name the feet with --feet or a "
                            "manifest's [feet])",
                            db->contacts_error));
  }

  // 2. Point clouds and per-frame features.
  auto layout = make_cloud_layout(db->skeletons.front(), settings.distance_stage.cloud);
  if (!layout) {
    // Named by the file whose skeleton the clouds stand on (a BVH whose OFFSETs are all zero).
    const auto first = std::find_if(db->clips.begin(), db->clips.end(),
                                    [](const DatabaseClip& clip) { return clip.skeleton == 0; });
    return Error{first != db->clips.end() ? first->source : "", 0, layout.error().message};
  }
  auto features = make_frame_features(*db, *layout, settings.distance_stage.distance);
  if (!features) return features.error();
  if (auto s = check_stop(log.stop); !s) return s.error();
  if (features->window < 2) return Error{"", 0, "the window must be at least 2 frames (raise --fps or --window)"};
  timings["clouds"] = watch.lap();
  return Prepared{std::move(*db), std::move(*layout), std::move(*features), std::move(load_notes)};
}

// Where the threshold comes from, for a warning that a higher one would keep more.
std::string threshold_hint(const BuildSettings& settings) {
  return settings.threshold_mode == ThresholdMode::kAuto
             ? fmt::format("--max-threshold {:g} cm bounds the automatic one", settings.choice.max_rms_cm)
             : std::string("--threshold sets it");
}

// The warning for a graph that keeps less than half of the library's frames (nothing when it
// keeps more): the share, and the clips it loses most of, with the threshold from which
// candidates could join a clip it keeps nothing of (the pruned stage's reach its ceiling only).
std::string coverage_warning(const MotionDatabase& db, const FrameFeatures& features,
                             std::span<const ClipCoverage> coverage, const CandidateSearch& candidates,
                             const BuildSettings& settings, double threshold_rms_cm) {
  long long kept = 0;
  for (const ClipCoverage& c : coverage) kept += c.kept_frames;
  const long long frames = db.frame_count();
  if (2 * kept >= frames) return {};
  std::vector<ClipCoverage> lost(coverage.begin(), coverage.end());
  std::stable_sort(lost.begin(), lost.end(), [](const ClipCoverage& a, const ClipCoverage& b) {
    return a.frames - a.kept_frames > b.frames - b.kept_frames;
  });
  const std::string searched =
      candidates.ceiling >= 0.0 ? fmt::format(" under RMS {:.2f} cm", rms_cm_of_distance(candidates.ceiling, features))
                                : std::string();
  std::vector<std::string> named;
  bool joins_higher = false;  // a clip lost whole that candidates above the threshold would join
  for (size_t i = 0; i < lost.size() && named.size() < 5 && lost[i].kept_frames < lost[i].frames; ++i) {
    const ClipCoverage& c = lost[i];
    std::string line = fmt::format("{} ({} of {} frames", db.clips[c.clip].name, c.kept_frames, c.frames);
    if (c.kept_frames == 0) {
      const double join_cm = rms_cm_of_distance(c.best_join, features);
      if (c.best_join < 0.0f) {
        line += fmt::format("; no candidates lead into it and out again{}", searched);
      } else if (join_cm <= threshold_rms_cm) {
        line += fmt::format("; candidates from RMS {:.2f} cm would join it, but pruning by motion type or the "
                            "spacing dropped them", join_cm);
      } else {
        line += fmt::format("; candidates would join it from RMS {:.2f} cm", join_cm);
        joins_higher = true;
      }
    }
    named.push_back(line + ")");
  }
  // Where the clips lost are partly kept, what is lost is their ends: the frames after the last
  // transition out of a clip (and before the first into it) lead nowhere, and a short clip cut
  // mid-stride keeps little at any threshold (CMU 16_45, a 1.1 s run: 35 % at 4 cm and at 30).
  const std::string why =
      joins_higher
          ? fmt::format("A clip joins the graph only through transitions under the threshold (here RMS {:.2f} cm; "
                        "{}): a higher one keeps more, with rougher blends",
                        threshold_rms_cm, threshold_hint(settings))
          : fmt::format("A clip keeps the frames between transitions into it and out of it under the threshold (here "
                        "RMS {:.2f} cm; {}): the frames before the first and after the last lead nowhere, and short "
                        "clips lose the most",
                        threshold_rms_cm, threshold_hint(settings));
  return fmt::format("the graph keeps {:.0f} % of the frames ({} of {}); it loses most of {}. {}",
                     100.0 * static_cast<double>(kept) / static_cast<double>(frames), kept, frames,
                     fmt::join(named, ", "), why);
}

// The warning for a graph offering under kFewTransitionsPerSecond transitions a second of the
// motion it plays (nothing otherwise): a walk, a path or steering can seldom turn or change
// motion on it (131_01 alone: one transition in 4.4 s of walking, a loop).
constexpr double kFewTransitionsPerSecond = 1.0;
std::string few_transitions_warning(const GraphStatistics& after, double fps) {
  if (after.clip_frames <= 0 || !(fps > 0.0)) return {};
  const double rate = transitions_per_second(after.transitions, after.clip_frames, fps);
  if (rate >= kFewTransitionsPerSecond) return {};
  // Three decimals where two would round up to the bound ("1.00 ... under 1").
  const std::string shown = rate < kFewTransitionsPerSecond - 0.005 ? fmt::format("{:.2f}", rate)
                                                                     : fmt::format("{:.3f}", rate);
  return fmt::format("the graph offers {} transitions a second of the motion it plays ({} in {:.1f} s), under "
                     "{:g}: walks, paths and steering can seldom turn or change motion on it; more clips of the "
                     "same motion give more",
                     shown, counted(after.transitions, "transition"), static_cast<double>(after.clip_frames) / fps,
                     kFewTransitionsPerSecond);
}

// A warning for each motion type (not a modifier) the clips carry and the pruned graph plays in
// no frame: `path` and `steer` cannot play it (CMU 49 keeps none of its 104 running frames).
std::vector<std::string> lost_type_warnings(const MotionDatabase& db, const GraphStatistics& after,
                                            const BuildSettings& settings, double threshold_rms_cm) {
  std::vector<std::string> lines;
  for (const TagStatistics& t : after.tags) {
    const std::string& name = db.tag_names[static_cast<size_t>(t.tag)];
    if (t.frames > 0 || t.database_frames == 0 || is_modifier_tag(name)) continue;
    lines.push_back(fmt::format("the graph keeps none of the {} frames of '{}' in its clips: a path or steering asking "
                                "for it cannot play it. A motion type is kept where transitions under the threshold "
                                "(here RMS {:.2f} cm; {}) make its frames loop",
                                t.database_frames, name, threshold_rms_cm, threshold_hint(settings)));
  }
  return lines;
}

}  // namespace

Result<GraphBuild> build_graph(std::span<const std::string> inputs, const BuildSettings& settings, DistanceCache* cache,
                               const BuildLog& log, ProcessTeam* team) {
  OneProcess alone;
  ProcessTeam& processes = team != nullptr ? *team : alone;
  // Only rank 0 speaks: the others load the same clips and would say the same.
  const BuildLog silent{};
  std::vector<std::string> warnings;
  const Say say{processes.rank() == 0 ? log : silent, &warnings};
  Stopwatch watch;
  json timings = json::object();
  auto prepared = prepare(inputs, settings, processes.rank() == 0 ? log : silent, say, watch, timings);
  if (auto s = processes.agree(prepared ? Status(Ok{}) : Status(prepared.error())); !s) return s.error();
  MotionDatabase* db = &prepared->db;
  const CloudLayout* layout = &prepared->layout;
  const FrameFeatures* features = &prepared->features;

  // 3. The distance stage, from the cache when the same inputs and settings were seen.
  const json distance_json = settings.distance_stage.to_json(features->window);
  const bool pruned_stage = settings.pruned_stage(*db, *features);
  const std::uint64_t key =
      distance_cache_key(*db, json_text(distance_key_json(settings, pruned_stage, *features,
                                                          distance_json)));
  const BuildLog& own_log = processes.rank() == 0 ? log : silent;
  auto candidates = distance_stage(pruned_stage, *features, settings, cache, key, say, own_log, processes);
  if (!candidates) return candidates.error();
  timings["distance"] = watch.lap();
  if (processes.rank() != 0) {
    GraphBuild worker;
    worker.worker = true;
    return worker;
  }

  // 4. Transitions, at the threshold asked for or chosen. Bridges on the pruned stage's
  // candidates find the minima above its ceiling they need on demand.
  std::optional<OnDemandCandidates> more;
  if (candidates->search.ceiling >= 0.0) {
    more.emplace(*features, candidates->search, settings.pruned.embedding, settings.distance_stage.distance.threads,
                 std::move(candidates->work));
  }
  OnDemandCandidates* on_demand = more ? &*more : nullptr;
  json choice_json = nullptr;
  json check_json = nullptr;
  std::vector<NotChased> not_chased;
  auto graph_settings = threshold_settings(*db, *features, candidates->search, settings, on_demand, say, log.stop,
                                           choice_json, check_json, not_chased);
  if (!graph_settings) return graph_settings.error();
  if (auto s = check_stop(log.stop); !s) return s.error();
  auto selected = select_transitions_with_bridges(*db, *features, candidates->search, *graph_settings, on_demand);
  if (!selected) return selected.error();
  const TransitionSelection& selection = selected->selection;
  if (!selected->bridges.empty()) say.info(fmt::format("{} bridges between motion types", selected->bridges.size()));
  timings["transitions"] = watch.lap();
  const double threshold_rms_cm = rms_cm_of_distance(selection.threshold, *features);
  say.info(fmt::format("threshold {:.4g} (RMS {:.2f} cm; {:.3f} % of pairs below): {}", selection.threshold,
                       threshold_rms_cm, 100.0 * selection.threshold_quantile,
                       counted(std::ssize(selection.transitions), "transition")));

  // 5. The graph, pruned.
  auto built = build_spaced_graph(*db, *selected, *features, *graph_settings);
  if (!built && built.error().kind != ErrorKind::kEmptyGraph) return built.error();
  if (auto s = check_stop(log.stop); !s) return s.error();
  timings["graph"] = watch.lap();
  std::vector<ClipCoverage> coverage;
  for (const NotChased& n : not_chased) {
    long long kept = 0, frames = 0;
    if (built) {
      for (const TagStatistics& t : built->prune.after.tags) {
        if (t.tag == n.tag) kept = t.frames, frames = t.database_frames;
      }
    }
    const double share = frames > 0 ? static_cast<double>(kept) / static_cast<double>(frames) : 0.0;
    // The graph built keeps more of it than the ceiling's did (pruning is not monotonic: 131_01
    // alone, 7.6 % at the ceiling, 46.6 % at the path check's 8.19 cm): served, nothing to warn of.
    if (share >= kMinServedShare) continue;
    // (to a tenth of a per cent: 9.6 % is under 10 %, as "10 %" would not say)
    say.warning(fmt::format("motion type '{}': even the ceiling (--max-threshold {:g} cm) keeps only {:.1f} % of its "
                            "frames, under {:.0f} %, so the threshold does not rise for it; the graph keeps {:.1f} %",
                            db->tag_names[static_cast<size_t>(n.tag)], settings.choice.max_rms_cm,
                            100.0 * n.ceiling_share, 100.0 * kMinServedShare, 100.0 * share));
  }
  if (built) {
    const PruneReport& pruned = built->prune;
    if (!built->bridge_blends_placed) {
      say.warning("bridges blend over the window: centring their longer blends on their measured windows would have "
                  "cost the graph a transition");
    }
    coverage = clip_coverage(built->graph, *db, candidates->search.minima);
    say.info(fmt::format("graph: {}, {} ({}) after pruning and spacing, playing {} of the {} "
                         "frames ({:.0f} %); {} survived a first pruning, spaced to {}",
                         counted(pruned.after.nodes, "node"), counted(pruned.after.edges, "edge"),
                         counted(pruned.after.transitions, "transition"), pruned.after.clip_frames,
                         db->frame_count(),
                         100.0 * static_cast<double>(pruned.after.clip_frames) / db->frame_count(),
                         counted(built->survived_first_pruning, "transition"), pruned.before.transitions));
    if (const std::string warning =
            coverage_warning(*db, *features, coverage, candidates->search, settings, threshold_rms_cm);
        !warning.empty()) {
      say.warning(warning);
    }
    if (const std::string warning = few_transitions_warning(pruned.after, db->fps);
        !warning.empty()) {
      say.warning(warning);
    }
    for (const std::string& warning : lost_type_warnings(*db, pruned.after, settings, threshold_rms_cm)) {
      say.warning(warning);
    }
    // Motion types that both loop but that nothing joins (the report lists them all): a warning
    // when the graph lost one of them, else the graph leads from one to the other through
    // other frames.
    std::vector<UnjoinedPair> unjoined;
    for (const UnjoinedPair& u : selected->unjoined) {
      if (u.reason != UnjoinedReason::kNoCore) unjoined.push_back(u);
    }
    for (const json& u : unjoined_json(unjoined, *db, *features, &pruned.after)) {
      const std::string from = u["from"].get<std::string>(), to = u["to"].get<std::string>();
      if (u["through_graph"].get<bool>()) {
        say.info(fmt::format("'{}' leads to '{}' only through other frames of the graph: no transition or bridge "
                             "between them ({})",
                             from, to, u["why"].get<std::string>()));
      } else {
        say.warning(fmt::format("no transition or bridge leads from '{}' to '{}': {}", from, to,
                                u["why"].get<std::string>()));
      }
    }
  }

  // 6. The report and the exports, made even when no graph can be, so that the user can see why.
  GraphBuild out;
  const char* mode_name = threshold_mode_name(settings.threshold_mode);
  out.report = build_report(BuildReportParts{*db, *features, *layout, candidates->search, *selected,
                                             built ? &*built : nullptr, coverage, distance_json, mode_name, choice_json,
                                             check_json, settings.spacing, graph_settings->bridges,
                                             candidates->cache, candidates->processes, candidates->peak_memory_mb,
                                             candidates->share_seconds, candidates->restored_tiles});
  out.report["distance_stage"] = distance_stage_json(candidates->search, candidates->pruned, more ? &*more : nullptr,
                                                    candidates->cache, *features);
  add_clip_doubts(out.report["clips"], *db, prepared->notes.clip_doubts);
  add_mirroring(out.report, *db, prepared->notes);
  out.report["warnings"] = warnings;  // every warning said up to here (none is said after)
  if (auto s = make_exports(settings, *db, *layout, *features, candidates->search, selected->all_transitions, out);
      !s) {
    return s.error();
  }
  candidates->search.matrix.clear();
  timings["exports"] = watch.lap();

  if (!built) {
    // No graph: say which threshold would make one, and what it would keep.
    // It may lie above the pruned stage's ceiling: looked for on every distance.
    const CandidateSearch* every = &candidates->search;
    CandidateSearch exhaustive;
    if (every->ceiling >= 0.0) {
      say.info("no graph: the exhaustive distance stage runs to find the lowest threshold that makes one");
      auto found = find_candidates(*features, settings.distance_stage.distance, candidate_settings_of(settings), {},
                                   {}, {}, log.stop);
      if (!found) return found.error();
      exhaustive = std::move(*found);
      every = &exhaustive;
    }
    auto lowest = lowest_graph_threshold(*db, *features, *every, *graph_settings, selection.threshold);
    if (!lowest) return lowest.error();
    std::string advice = "no threshold makes a graph: the clips hold no loop of transitions at all";
    if (*lowest) {
      const CoveragePoint& p = **lowest;
      // What it keeps of each motion type (the worst alone read "0 % of each motion type's").
      const std::vector<int> tags = coverage_tags(*db, *graph_settings);
      std::string kept = fmt::format("{:.0f} % of the frames", 100.0 * p.coverage);
      if (!tags.empty() && p.tag_coverage.size() == tags.size()) {
        kept.clear();
        for (size_t t = 0; t < tags.size(); ++t) {
          kept += fmt::format("{}{:.0f} % of the {} frames", t == 0 ? "" : t + 1 == tags.size() ? " and " : ", ",
                              100.0 * p.tag_coverage[t],
                              tags[t] == kUntaggedClass ? "untagged clips'" : motion_class_name(*db, tags[t]));
        }
      }
      advice = fmt::format(
          "the lowest threshold that makes one is RMS {:.2f} cm (--threshold {:.2f}cm, D {:.4g}, "
          "{:.3f} % of pairs); it keeps {}",
          p.rms_cm, std::ceil(p.rms_cm * 100.0) / 100.0, p.threshold, 100.0 * p.quantile, kept);
      out.report["lowest_graph_threshold"] = coverage_point_json(p, *db, coverage_tags(*db, *graph_settings));
    }
    out.report["error"] = "pruning left nothing";
    out.report["timings"] = timings;
    out.graph_status = Error{"", 0,
                             fmt::format("no graph at threshold RMS {:.2f} cm: pruning left nothing (the transitions "
                                         "form no loop); {}",
                                         threshold_rms_cm, advice),
                             ErrorKind::kEmptyGraph};
    out.file.database = std::move(*db);
    out.file.candidates = std::move(candidates->search);
    return out;
  }

  // What eval needs to select transitions again as this build did.
  SavedSettings saved;
  saved.distance_stage = settings.distance_stage;
  saved.distance_stage.distance.window_frames = features->window;
  saved.fps = db->fps;
  saved.threshold_mode = mode_name;
  saved.transitions = settings.transitions;
  saved.transitions.threshold = selection.threshold;
  saved.transitions.threshold_quantile = selection.threshold_quantile;
  saved.transitions.locality_radius = selection.locality_radius;
  saved.transitions.max_threshold = graph_settings->transitions.max_threshold;
  saved.transitions.tag_thresholds = graph_settings->transitions.tag_thresholds;
  saved.spacing = settings.spacing;
  saved.bridges = graph_settings->bridges;
  saved.connected_tags = db->tag_names_of(graph_settings->connected_tags);
  GraphFile& file = out.file;
  file.settings_json = json_text(saved.to_json());
  file.input_key = key;
  file.threshold = selection.threshold;
  file.threshold_quantile = selection.threshold_quantile;
  file.locality_radius = selection.locality_radius;
  file.graph = std::move(built->graph);
  file.candidates = std::move(candidates->search);
  file.database = std::move(*db);
  out.report["timings"] = timings;
  file.report_json = json_text(out.report);
  return out;
}

}  // namespace mg
