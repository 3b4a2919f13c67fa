// motiongraph bench synthesis GRAPH.mgraph, measured in one run and printed with ratios:
//  - loading the graph as the synthesis commands load it and setting up synthesis (what every
//    command pays once);
//  - path synthesis on the built-in shapes: seconds of motion per second of computing
//    (loading included, so the figure a user of `path` gets), and the same search without its
//    lower bound, warm start and beam (the plain depth-first branch and bound) for the ratio;
//  - the foot clean-up of each path's motion (its seconds beside the search's);
//  - a figure 8 asking for the graph's two commonest motion types, one after the other: the
//    search looking past its horizon for the type asked (tag_lookahead, the default) against
//    the horizon only, as `path` searches (retries included): their tag match, deviation and
//    seconds;
//  - the controller on a 60 s scripted run (heading every 2 s, walk/run every 10 s): decision
//    latency percentiles, the clean-up of each decision's frames, and both together.
// Speed is measured here, never asserted in tests.
#include "cli/bench_synthesis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/synthesis/controller.h"
#include "motiongraph/synthesis/loaded_graph.h"
#include "motiongraph/synthesis/path_synthesis.h"

namespace mg::cli {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double percentile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const size_t i = std::min(values.size() - 1, static_cast<size_t>(std::ceil(q * values.size())) - 1);
  return values[i];
}

}  // namespace

int run_synthesis_bench(const std::string& graph_path) {
  auto start = std::chrono::steady_clock::now();
  // Read as walk, path and steer read it (without the candidate minima).
  auto file = load_graph_file(graph_path, GraphReadOptions{.candidate_minima = false});
  if (!file) return fail(file.error());
  const double load_s = seconds_since(start);
  start = std::chrono::steady_clock::now();
  auto loaded = LoadedGraph::create(std::move(*file), graph_path);
  if (!loaded) return fail(loaded.error());
  const double setup_s = seconds_since(start);
  const SynthesisContext* context = &(*loaded)->context();
  const MotionGraph& graph = (*loaded)->file().graph;
  const MotionDatabase& db = (*loaded)->file().database;
  fmt::print("synthesis benchmark: {} ({} nodes, {} edges, {} frames at {:g} fps)\n", graph_path, graph.node_count(),
             graph.edge_count(), db.frame_count(), db.fps);
  fmt::print("load graph {:.3f} s, set up synthesis {:.3f} s\n", load_s, setup_s);

  fmt::print("{:<12} {:>8} {:>9} {:>10} {:>9} {:>12} {:>10} | {:>10} {:>9} {:>8}\n", "path", "motion s", "search s",
             "x realtime", "mean dev", "expansions", "clean-up s", "plain s", "plain dev", "speedup");
  for (const char* spec : {"line:20", "circle:5", "figure8:4", "s-curve:100"}) {
    auto path = make_shape(spec);
    if (!path) return fail(path.error());
    // One search of the whole path each, so that both stages search the same path once; the
    // deviations are the walks' as the graph plays them (before the edit onto the path).
    PathSynthesisSettings settings;
    settings.progress_retries = 0;
    start = std::chrono::steady_clock::now();
    auto fast = synthesize_path(*context, *path, settings);
    const double fast_s = seconds_since(start);
    if (!fast) return fail(fast.error());
    // The foot clean-up of the motion found (what `path` adds unless --no-cleanup).
    double cleanup_s = 0.0;
    if (auto cleanup = context->foot_cleanup({}); cleanup) {
      start = std::chrono::steady_clock::now();
      if (auto s = context->clean_up_walk(fast->walk, *cleanup, fast->motion); !s) return fail(s.error());
      cleanup_s = seconds_since(start);
    }
    settings.lower_bound = false;
    settings.warm_start = false;
    settings.beam_width = 0;
    start = std::chrono::steady_clock::now();
    auto plain = synthesize_path(*context, *path, settings);
    const double plain_s = seconds_since(start);
    if (!plain) return fail(plain.error());
    const double motion_s = fast->motion.frame_count / fast->motion.fps;
    fmt::print("{:<12} {:8.1f} {:9.3f} {:10.0f} {:8.3f}m {:12} {:10.4f} | {:10.3f} {:8.3f}m {:7.1f}x\n", spec, motion_s,
               fast_s, motion_s / (load_s + setup_s + fast_s), fast->graph_mean_deviation_m, fast->expansions,
               cleanup_s, plain_s, plain->graph_mean_deviation_m, plain_s / fast_s);
  }
  fmt::print("(x realtime: seconds of motion per second of loading, set-up and search)\n");

  // The two motion types most nodes carry (modifiers such as turn ride on them), asked for over
  // the two halves of a figure 8, searched as `path` searches (retries included).
  std::vector<std::pair<int, std::string>> types;
  const TagMask type_mask = motion_type_tags(db);
  for (size_t t = 0; t < db.tag_names.size() && t < 64; ++t) {
    const TagMask bit = TagMask{1} << t;
    if ((type_mask & bit) == 0) continue;
    int nodes = 0;
    for (const GraphNode& node : graph.nodes) {
      nodes += !context->frame_tags.empty() && (context->frame_tags[node.frame] & bit) != 0 ? 1 : 0;
    }
    types.emplace_back(nodes, db.tag_names[t]);
  }
  std::sort(types.begin(), types.end(), std::greater<>());
  if (types.size() < 2 || types[1].first == 0) {
    fmt::print("tag lookahead: the graph has fewer than two motion types; not measured\n");
  } else {
    auto shape = make_shape("figure8:4");
    if (!shape) return fail(shape.error());
    const double half = shape->length_m() / 2.0;
    auto path = FloorPath::create(shape->points(), {{0.0, half, types[0].second},
                                                    {half, shape->length_m() + 1.0, types[1].second}});
    if (!path) return fail(path.error());
    PathSynthesisSettings settings;  // as `path` searches, retries included
    start = std::chrono::steady_clock::now();
    auto ahead = synthesize_path(*context, *path, settings);
    const double ahead_s = seconds_since(start);
    if (!ahead) return fail(ahead.error());
    settings.tag_lookahead = 0.0;
    start = std::chrono::steady_clock::now();
    auto blind = synthesize_path(*context, *path, settings);
    const double blind_s = seconds_since(start);
    if (!blind) return fail(blind.error());
    auto end = [](const PathSynthesisResult& r) { return r.reached_end ? "end reached" : "end not reached"; };
    fmt::print("figure8:4, {} then {}: looking past the horizon (--tag-lookahead {:g}) tag match {:.0f} %, mean dev "
               "{:.3f} m, {}, {:.3f} s; the horizon only {:.0f} %, {:.3f} m, {}, {:.3f} s (looking ahead {:.2f}x its time)\n",
               types[0].second, types[1].second, PathSynthesisSettings{}.tag_lookahead, 100.0 * ahead->tag_match,
               ahead->mean_deviation_m, end(*ahead), ahead_s, 100.0 * blind->tag_match, blind->mean_deviation_m,
               end(*blind), blind_s, ahead_s / blind_s);
  }

  auto walk = context->tag_mask("walk");
  auto run = context->tag_mask("run");
  const TagMask walk_tag = walk ? *walk : 0, run_tag = run ? *run : 0;
  auto controller = Controller::create(*context, {}, {bearing_direction(0.0), walk_tag});
  if (!controller) return fail(controller.error());
  Motion motion = context->assembler.empty_motion();
  auto cleanup = context->foot_cleanup({});
  std::vector<double> latencies, cleanup_latencies;
  int exhausted = 0;
  const double fps = db.fps;
  while (motion.frame_count < 60.0 * fps) {
    const double t = motion.frame_count / fps;
    const int heading = static_cast<int>(t / 2.0) % 4;
    const bool running = static_cast<int>(t / 10.0) % 2 == 1;
    controller->set_input({bearing_direction(90.0 * heading), running ? run_tag : walk_tag});
    const int first_new = motion.frame_count;
    const ControllerDecision d = controller->step(motion);
    latencies.push_back(d.search_seconds);
    if (cleanup) {
      start = std::chrono::steady_clock::now();
      if (auto s = cleanup->clean(motion, first_new, context->edges_contacts(d.edges)); !s) return fail(s.error());
      cleanup_latencies.push_back(seconds_since(start));
    }
    exhausted += d.budget_exhausted ? 1 : 0;
  }
  fmt::print("controller, 60 s scripted: {} decisions, latency p50 {:.3f} ms, p99 {:.3f} ms, max {:.3f} ms; "
             "{} ran out of budget\n",
             latencies.size(), 1e3 * percentile(latencies, 0.5), 1e3 * percentile(latencies, 0.99),
             1e3 * percentile(latencies, 1.0), exhausted);
  if (cleanup) {
    std::vector<double> both(latencies.size());
    for (size_t i = 0; i < both.size(); ++i) both[i] = latencies[i] + cleanup_latencies[i];
    fmt::print("foot clean-up of each decision's frames: p50 {:.3f} ms, p99 {:.3f} ms; search and clean-up p99 {:.3f} ms\n",
               1e3 * percentile(cleanup_latencies, 0.5), 1e3 * percentile(cleanup_latencies, 0.99),
               1e3 * percentile(both, 0.99));
  } else {
    fmt::print("no foot clean-up: {}\n", context->feet_error);
  }
  return 0;
}

}  // namespace mg::cli
