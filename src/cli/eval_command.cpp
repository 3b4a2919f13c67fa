// motiongraph eval GRAPH --out-dir DIR: the evaluations of the seed report on a graph file,
// each as a CSV file (with a header row) and a PNG plot drawn by gnuplot:
//   threshold    graph nodes and largest strongly connected component against the threshold
//                (figure 2.12), transitions selected again on the stored candidates
//   consistency  RMS angle between facing and travel around transitions against the
//                threshold, with the captured data's value (figure 3.2)
//   walks        lengths of walks between random node pairs per cost function (figure 3.3)
//   paths        path-following error on the built-in shapes
//   footslide    foot slide in contact, as played and cleaned, times the source clips' and times
//                the capture's on the frames played, on the built-in shapes against the
//                threshold; with the largest joint step
#include <chrono>
#include <cmath>
#include <filesystem>
#include <algorithm>
#include <functional>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/gnuplot.h"
#include "motiongraph/evaluation/consistency_sweep.h"
#include "motiongraph/evaluation/foot_slide_sweep.h"
#include "motiongraph/evaluation/graph_rebuild.h"
#include "motiongraph/evaluation/path_errors.h"
#include "motiongraph/evaluation/threshold_sweep.h"
#include "motiongraph/evaluation/walk_lengths.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/graph/threshold_choice.h"
#include "motiongraph/io/file.h"

namespace mg::cli {

namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kEvaluations = {"threshold", "consistency", "walks", "paths", "footslide"};

struct EvalOptions {
  std::string graph;
  std::string out_dir;
  std::vector<std::string> what = kEvaluations;
  int thresholds = 12;
  double lowest_quantile = 0.001;
  double highest_quantile = 0.1;
  int walks = 100;
  std::uint64_t seed = 1;
  long long max_expansions = 2000000;
  std::vector<std::string> shapes = default_evaluation_shapes();
  bool no_plots = false;
  bool quiet = false;
};

// Shortest text that reads back to the same double.
std::string num(double value) { return std::isfinite(value) ? fmt::format("{}", value) : ""; }

struct Outputs {
  fs::path dir;
  bool plots = true;
  std::vector<std::string> written;

  Status write_csv(const std::string& name, const std::string& text) {
    const std::string path = (dir / name).string();
    if (auto s = write_file_atomic(path, text); !s) return s;
    written.push_back(path);
    return Ok{};
  }
  Status plot(const std::string& name, const std::string& commands) {
    if (!plots) return Ok{};
    const std::string path = (dir / name).string();
    if (auto s = plot_png(commands, path); !s) return s;
    written.push_back(path);
    return Ok{};
  }
  std::string csv(const std::string& name) const { return gnuplot_quote((dir / name).string()); }
};

constexpr const char* kCsvSettings = "set datafile separator ','\nset grid\n";
// Every plot against the threshold has it in the units the build reports it in.
constexpr const char* kThresholdAxis = "transition threshold, RMS point distance (cm, log scale)";

Status evaluate_thresholds(const GraphFile& file, const GraphRebuild& rebuild, std::span<const double> quantiles,
                           OnDemandCandidates* more, Outputs& out) {
  auto rows = sweep_thresholds(file.database, rebuild.features, file.candidates, rebuild.settings, quantiles, more);
  if (!rows) return rows.error();
  std::string csv =
      "quantile,threshold,rms_cm,transitions,bridges,nodes,largest_component_nodes,kept_nodes,kept_transitions,"
      "kept_clip_frames\n";
  for (const ThresholdSweepRow& r : *rows) {
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", num(r.quantile), num(r.threshold),
                       num(rms_cm_of_distance(r.threshold, rebuild.features)), r.transitions, r.bridges, r.nodes,
                       r.largest_component_nodes, r.kept_nodes, r.kept_transitions, r.kept_clip_frames);
  }
  if (auto s = out.write_csv("threshold.csv", csv); !s) return s;
  return out.plot("threshold.png",
                  fmt::format("{}set logscale x\nset xlabel '{}'\nset ylabel 'nodes'\n"
                              "set key top left\nset title 'Graph size against the threshold'\n"
                              "plot {} skip 1 using 3:6 with linespoints title 'graph nodes', "
                              "'' skip 1 using 3:7 with linespoints title 'largest strongly connected component', "
                              "'' skip 1 using 3:8 with linespoints title 'nodes after pruning per tag'",
                              kCsvSettings, kThresholdAxis, out.csv("threshold.csv")));
}

Status evaluate_consistency(const GraphFile& file, const GraphRebuild& rebuild, std::span<const double> quantiles,
                            OnDemandCandidates* more, Outputs& out) {
  const ConsistencySum captured = database_consistency(file.database, learn_travel_axes(file.database));
  auto rows = sweep_consistency(file.database, rebuild.features, file.candidates, rebuild.settings, quantiles, more);
  if (!rows) return rows.error();
  std::string csv = "quantile,threshold,rms_cm,transitions,frames,rms_deg,database_frames,database_rms_deg\n";
  for (const ConsistencyRow& r : *rows) {
    csv += fmt::format("{},{},{},{},{},{},{},{}\n", num(r.quantile), num(r.threshold),
                       num(rms_cm_of_distance(r.threshold, rebuild.features)), r.transitions, r.transition.frames,
                       num(r.transition.rms_deg()), captured.frames, num(captured.rms_deg()));
  }
  if (auto s = out.write_csv("consistency.csv", csv); !s) return s;
  // No frame around any transition travels (a library that stands): no curve to draw.
  if (std::none_of(rows->begin(), rows->end(),
                   [](const ConsistencyRow& r) { return std::isfinite(r.transition.rms_deg()); })) {
    if (out.plots) {
      spdlog::warn("consistency.png not drawn: no frame around a transition travels, so its facing and travel "
                   "cannot be compared (consistency.csv has no angle)");
    }
    return Ok{};
  }
  // The captured data's value as a line (none when no captured frame moves).
  const std::string captured_line =
      std::isfinite(captured.rms_deg())
          ? fmt::format(", {} with lines dashtype 2 title 'captured data'", num(captured.rms_deg()))
          : "";
  return out.plot("consistency.png",
                  fmt::format("{}set logscale x\nset xlabel '{}'\n"
                              "set ylabel 'RMS angle, facing vs. travel (degrees)'\nset yrange [0:*]\n"
                              "set key bottom right\nset title 'Self-consistency around transitions'\n"
                              "plot {} skip 1 using 3:6 with linespoints title 'around transitions'{}",
                              kCsvSettings, kThresholdAxis, out.csv("consistency.csv"), captured_line));
}

Status evaluate_walks(const GraphFile& file, const EvalOptions& o, Outputs& out) {
  const std::vector<WalkCost> costs = {WalkCost::kConstant, WalkCost::kQuality, WalkCost::kRandom, WalkCost::kHybrid};
  WalkLengthSettings settings;
  settings.walks = o.walks;
  settings.seed = o.seed;
  settings.max_expansions = o.max_expansions;
  auto samples = sample_walk_lengths(file.graph, costs, settings);
  if (!samples) return samples.error();
  std::string csv = "cost,walk,from,to,found,frames,edges,transitions,cost_value,expansions\n";
  for (const WalkLengthSample& s : *samples) {
    if (!s.found) spdlog::warn("walk {} ({}): {}", s.index, walk_cost_name(s.cost), s.failure);
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", walk_cost_name(s.cost), s.index, s.from, s.to,
                       s.found ? 1 : 0, s.found ? std::to_string(s.frames) : "",
                       s.found ? std::to_string(s.walk.edges.size()) : "",
                       s.found ? std::to_string(s.transitions) : "", s.found ? num(s.cost_value) : "", s.expansions);
  }
  if (auto s = out.write_csv("walks.csv", csv); !s) return s;
  std::string plots;
  for (size_t c = 0; c < costs.size(); ++c) {
    plots += fmt::format("{}{} skip 1 using ({}):(strcol(1) eq '{}' ? $6 : NaN) notitle", c ? ", " : "",
                         c ? "''" : out.csv("walks.csv"), c + 1, walk_cost_name(costs[c]));
  }
  return out.plot("walks.png",
                  fmt::format("{}set style data boxplot\nset style boxplot outliers pointtype 7\n"
                              "set style fill solid 0.3\nset boxwidth 0.5\nset xrange [0.3:{}.7]\nset yrange [0:*]\n"
                              "set xtics ('constant' 1, 'quality' 2, 'random' 3, 'hybrid' 4)\n"
                              "set xlabel 'edge cost'\nset ylabel 'walk length (frames at {:g} fps)'\n"
                              "set title '{} walks between random node pairs per cost'\nplot {}",
                              kCsvSettings, costs.size(), file.database.fps, o.walks, plots));
}

Status evaluate_paths(const GraphFile& file, const EvalOptions& o, Outputs& out) {
  auto context = make_synthesis_context(file.database, file.graph);
  if (!context) return context.error();
  auto rows = measure_path_errors(*context, o.shapes);
  if (!rows) return rows.error();
  std::string csv =
      "shape,path_length_m,arc_covered_m,mean_deviation_m,max_deviation_m,reached_end,frames,searches,"
      "budget_exhausted,graph_mean_deviation_m,graph_max_deviation_m,end_distance_m\n";
  for (const PathErrorRow& r : *rows) {
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", r.shape, num(r.path_length_m), num(r.arc_covered_m),
                       num(r.mean_deviation_m), num(r.max_deviation_m), r.reached_end ? 1 : 0, r.frames, r.searches,
                       r.budget_exhausted, num(r.graph_mean_deviation_m), num(r.graph_max_deviation_m),
                       num(r.end_distance_m));
  }
  if (auto s = out.write_csv("paths.csv", csv); !s) return s;
  return out.plot("paths.png",
                  fmt::format("{}set style data histograms\nset style histogram clustered gap 1\n"
                              "set style fill solid 0.6 border -1\nset yrange [0:*]\nset key top left\n"
                              "set ylabel 'distance from the path (m)'\nset title 'Path-following error'\n"
                              "plot {} skip 1 using 10:xtic(1) title 'mean, as the graph played it', '' skip 1 "
                              "using 11 title 'max, as played', '' skip 1 using 4 title 'mean, edited onto the path', "
                              "'' skip 1 using 5 title 'max, edited'",
                              kCsvSettings, out.csv("paths.csv")));
}

Status evaluate_foot_slide(const GraphFile& file, const GraphRebuild& rebuild, std::span<const double> quantiles,
                           OnDemandCandidates* more, const EvalOptions& o, Outputs& out) {
  auto rows = sweep_foot_slide(file.database, rebuild.features, file.candidates, rebuild.settings, quantiles, o.shapes,
                               {}, more);
  if (!rows) return rows.error();
  std::string csv =
      "quantile,threshold,rms_cm,shape,graph,frames,transitions,mean_deviation_m,played_mps,cleaned_mps,source_mps,"
      "played_ratio,cleaned_ratio,step_over_source_p999,same_frames_steps,same_frames_source_mps,played_same_ratio,"
      "cleaned_same_ratio\n";
  for (const FootSlideSweepRow& r : *rows) {
    const bool g = r.graph;
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", num(r.quantile), num(r.threshold),
                       num(rms_cm_of_distance(r.threshold, rebuild.features)), r.shape, g ? 1 : 0, r.frames,
                       r.transitions, g ? num(r.mean_deviation_m) : "", g ? num(r.played_mps) : "",
                       g ? num(r.cleaned_mps) : "", g ? num(r.source_mps) : "", g ? num(r.played_ratio) : "",
                       g ? num(r.cleaned_ratio) : "", g ? num(r.step_over_source_p999) : "",
                       g ? std::to_string(r.same_frames_steps) : "", g ? num(r.same_frames_source_mps) : "",
                       g ? num(r.played_same_ratio) : "",
                       g ? num(r.cleaned_same_ratio) : "");
  }
  if (auto s = out.write_csv("footslide.csv", csv); !s) return s;
  // The clips' own feet never slide (a library that stands): no ratio to the capture to draw.
  if (std::none_of(rows->begin(), rows->end(), [](const FootSlideSweepRow& r) {
        return r.graph && (std::isfinite(r.played_same_ratio) || std::isfinite(r.cleaned_same_ratio));
      })) {
    if (out.plots) {
      spdlog::warn("footslide.png not drawn: the clips' feet do not slide on the frames played, so there is no "
                   "ratio to the capture (footslide.csv has the slide in m/s)");
    }
    return Ok{};
  }
  std::string plots;
  for (size_t i = 0; i < o.shapes.size(); ++i) {
    const std::string& shape = o.shapes[i];
    const std::string pick = fmt::format("(strcol(4) eq '{}' ? ${{}} : NaN)", shape);
    plots += fmt::format("{}{} skip 1 using 3:{} with linespoints lc {} pt 7 title '{} cleaned', "
                         "'' skip 1 using 3:{} with linespoints lc {} dt 2 pt 6 title '{} as played'",
                         i ? ", " : "", out.csv("footslide.csv"), fmt::format(fmt::runtime(pick), 18), i + 1, shape,
                         fmt::format(fmt::runtime(pick), 17), i + 1, shape);
  }
  return out.plot("footslide.png",
                  fmt::format("{}set logscale x\nset xlabel '{}'\n"
                              "set ylabel 'foot slide in contact, x the capture on the frames played'\n"
                              "set yrange [0:*]\n"
                              "set key outside right top\n"
                              "set title 'Foot slide of path synthesis against the threshold'\n"
                              "set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 3\nplot {}",
                              kCsvSettings, kThresholdAxis, plots));
}

int run_eval(const EvalOptions& o) {
  const auto begin = std::chrono::steady_clock::now();
  for (const std::string& what : o.what) {
    if (std::find(kEvaluations.begin(), kEvaluations.end(), what) == kEvaluations.end()) {
      return fail(Error{"", 0, fmt::format("--what: unknown evaluation '{}' (threshold, consistency, walks, paths, "
                                           "footslide)", what)});
    }
  }
  if (!(o.lowest_quantile > 0.0 && o.lowest_quantile < o.highest_quantile && o.highest_quantile <= 1.0)) {
    return fail_usage(Error{"", 0, "the threshold quantiles must satisfy 0 < --lowest < --highest <= 1"});
  }
  // The shapes before any evaluation runs: a bad one would fail after others were written.
  for (const std::string& shape : o.shapes) {
    if (auto made = make_shape(shape); !made) return fail(Error{"", 0, "--shapes: " + made.error().message});
  }
  if (!o.no_plots) {
    if (auto s = gnuplot_available(); !s) return fail(s.error());
  }
  auto file = load_graph_file(o.graph);
  if (!file) return fail(file.error());
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (ec) return fail(Error{o.out_dir, 0, fmt::format("cannot create the folder: {}", ec.message())});
  Outputs out{o.out_dir, !o.no_plots, {}};
  auto wants = [&](const char* name) { return std::find(o.what.begin(), o.what.end(), name) != o.what.end(); };
  auto log = [&](const std::string& line) {
    if (!o.quiet) spdlog::info("{}", line);
  };

  std::vector<double> quantiles = log_spaced(o.lowest_quantile, o.highest_quantile, o.thresholds);
  std::optional<GraphRebuild> rebuild;
  std::optional<OnDemandCandidates> more;  // for a graph built by the pruned distance stage
  if (wants("threshold") || wants("consistency") || wants("footslide")) {
    auto prepared = prepare_graph_rebuild(*file, o.graph);
    if (!prepared) return fail(prepared.error());
    rebuild = std::move(*prepared);
    const CandidateSearch& c = file->candidates;
    if (c.ceiling >= 0.0) {
      more.emplace(rebuild->features, c);
      const std::vector<double> below = quantiles_below_ceiling(c, quantiles);
      if (below.size() < quantiles.size()) {
        spdlog::warn("{} of the {} thresholds lie above the ceiling of the pruned distance stage that built the "
                     "graph (RMS {:.2f} cm) and are left out: build it with --exhaustive to sweep them",
                     quantiles.size() - below.size(), quantiles.size(),
                     rms_cm_of_distance(c.ceiling, rebuild->features));
      }
      if (below.empty()) {
        return fail(Error{o.graph, 0, "every threshold asked for lies above the pruned distance stage's ceiling: "
                                      "lower --highest or build the graph with --exhaustive"});
      }
      quantiles = below;
      if (rebuild->settings.transitions.per_tag_thresholds && rebuild->settings.connected_tags != 0) {
        spdlog::info("the sweeps give every motion type the same threshold: per-tag thresholds by rank need the "
                     "exhaustive distance stage (build with --exhaustive to sweep them)");
      }
    }
  }
  OnDemandCandidates* on_demand = more ? &*more : nullptr;
  struct Step {
    const char* name;
    std::function<Status()> run;
  };
  const std::vector<Step> steps = {
      {"threshold", [&] { return evaluate_thresholds(*file, *rebuild, quantiles, on_demand, out); }},
      {"consistency", [&] { return evaluate_consistency(*file, *rebuild, quantiles, on_demand, out); }},
      {"walks", [&] { return evaluate_walks(*file, o, out); }},
      {"paths", [&] { return evaluate_paths(*file, o, out); }},
      {"footslide", [&] { return evaluate_foot_slide(*file, *rebuild, quantiles, on_demand, o, out); }},
  };
  for (const Step& step : steps) {
    if (!wants(step.name)) continue;
    log(fmt::format("evaluating {}", step.name));
    if (auto s = step.run(); !s) {
      const Error& e = s.error();
      return fail(e.file.empty() ? Error{o.graph, e.line, fmt::format("{}: {}", step.name, e.message)} : e);
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  for (const std::string& path : out.written) fmt::print("{}\n", path);
  log(fmt::format("{} files in {:.1f} s", out.written.size(), seconds));
  return 0;
}

}  // namespace

Command add_eval_command(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* sub = app.add_subcommand(
      "eval", "Evaluate a graph as the seed report does; each evaluation writes a CSV file and a PNG plot (gnuplot):\n"
              "  threshold    graph nodes and largest strongly connected component against the threshold\n"
              "               (transitions selected again on the graph's stored candidates)\n"
              "  consistency  RMS angle between facing and the direction of travel over the next 10 frames\n"
              "               around transitions, against the threshold, with the captured data's value\n"
              "  walks        lengths of walks between random node pairs for each cost function\n"
              "  paths        path-following error on built-in shapes\n"
              "  footslide    foot slide in contact of path synthesis on the shapes, as played and cleaned,\n"
              "               times the capture's on the frames played (and the source clips' whole),\n"
              "               against the threshold");
  sub->add_option("GRAPH", o->graph, "A .mgraph file written by 'motiongraph build'")->required();
  sub->add_option("--out-dir", o->out_dir, "Folder for the CSV and PNG files (created)")->required();
  sub->add_option("--what", o->what, "Evaluations to run, comma separated")->delimiter(',')->capture_default_str();
  sub->add_option("--thresholds", o->thresholds, "Thresholds tried, log-spaced quantiles of all defined pairs")
      ->check(CLI::Range(2, 200))
      ->capture_default_str();
  sub->add_option("--lowest", o->lowest_quantile, "Lowest threshold quantile")->capture_default_str();
  sub->add_option("--highest", o->highest_quantile, "Highest threshold quantile")->capture_default_str();
  sub->add_option("--walks", o->walks, "Walks per cost function")->check(CLI::Range(1, 100000))->capture_default_str();
  sub->add_option("--seed", o->seed, "Seed of the node pairs and random costs")
      ->check(not_negative())
      ->capture_default_str();
  sub->add_option("--max-expansions", o->max_expansions, "Search budget of each walk")->capture_default_str();
  sub->add_option("--shapes", o->shapes, "Built-in paths to follow (line:L, circle:R, figure8:R, s-curve:L, square:S, zigzag:L)")
      ->delimiter(',')
      ->capture_default_str();
  sub->add_flag("--no-plots", o->no_plots, "Write the CSV files only (no gnuplot needed)");
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");
  return {sub, [o] { return run_eval(*o); }};
}

}  // namespace mg::cli
