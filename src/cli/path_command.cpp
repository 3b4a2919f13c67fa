// motiongraph path GRAPH (--path PATH.json | --shape SPEC) -o OUT: path synthesis
// (synthesis/path_synthesis.h).
#include <chrono>
#include <ctime>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/synthesis_options.h"
#include "motiongraph/io/file.h"
#include "motiongraph/synthesis/path_synthesis.h"
#include "motiongraph/synthesis/walk.h"

namespace mg::cli {

namespace {

// CPU seconds this thread has run (the search runs on one thread).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct PathOptions {
  SynthesisOptions common;
  std::string path_file;
  std::string shape;
  std::vector<std::string> segments;
  PathSynthesisSettings settings;
};

// "TAG:FROM-TO" in metres of arc length.
Result<PathSegment> parse_segment(const std::string& text) {
  const size_t colon = text.rfind(':');
  const size_t dash = text.find('-', colon == std::string::npos ? 0 : colon);
  PathSegment s;
  try {
    if (colon == std::string::npos || dash == std::string::npos) throw std::invalid_argument(text);
    s.tag = text.substr(0, colon);
    size_t used = 0;
    s.from_m = std::stod(text.substr(colon + 1, dash - colon - 1), &used);
    s.to_m = std::stod(text.substr(dash + 1), &used);
    if (used != text.size() - dash - 1) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    return Error{"", 0, fmt::format("--segment '{}': expected TAG:FROM-TO in metres, e.g. run:20-40", text)};
  }
  return s;
}

Result<FloorPath> read_path(const PathOptions& o) {
  if (o.path_file.empty() == o.shape.empty()) return Error{"", 0, "give exactly one of --path and --shape"};
  std::vector<PathSegment> segments;
  for (const std::string& text : o.segments) {
    auto s = parse_segment(text);
    if (!s) return s.error();
    segments.push_back(*s);
  }
  if (!o.shape.empty()) {
    auto shape = make_shape(o.shape);
    if (!shape) return shape.error();
    return FloorPath::create(shape->points(), segments);
  }
  auto text = read_text_file(o.path_file);
  if (!text) return text.error();
  auto path = parse_path_json(*text, o.path_file);
  if (!path || segments.empty()) return path;
  return FloorPath::create(path->points(), segments);
}

int run_path(const PathOptions& o) {
  const auto begin = std::chrono::steady_clock::now();
  if (auto s = o.settings.validate(); !s) return fail(s.error());
  auto path = read_path(o);
  if (!path) return fail(path.error());
  auto loaded = load_for_synthesis(o.common);
  if (!loaded) return fail(loaded.error());
  const SynthesisContext& context = (*loaded)->context();
  const auto search_begin = std::chrono::steady_clock::now();
  const double search_cpu_begin = thread_cpu_seconds();
  auto result = synthesize_path(context, *path, o.settings);
  const double search_cpu_seconds = thread_cpu_seconds() - search_cpu_begin;
  const double search_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - search_begin).count();
  if (!result) return fail(Error{o.common.graph, 0, result.error().message});
  Motion& motion = result->motion;
  auto cleanup = cleanup_for(o.common, context);
  if (cleanup) {
    if (auto s = context.clean_up_walk(result->walk, *cleanup, motion); !s) return fail(s.error());
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  nlohmann::json segments = nlohmann::json::array();
  for (const PathSegment& s : path->segments()) segments.push_back({{"from_m", s.from_m}, {"to_m", s.to_m}, {"tag", s.tag}});
  nlohmann::json points = nlohmann::json::array();
  for (const Vec2& p : path->points()) points.push_back({p.x(), p.y()});
  nlohmann::json roots = nlohmann::json::array();
  for (const Vec2& p : result->roots) roots.push_back({std::round(p.x() * 1e4) / 1e4, std::round(p.y() * 1e4) / 1e4});
  const int transitions = result->walk.transition_count(*context.graph);
  const nlohmann::json report = {{"path_length_m", result->path_length_m},
                                 {"arc_covered_m", result->arc_covered_m},
                                 {"reached_end", result->reached_end},
                                 {"mean_deviation_m", result->mean_deviation_m},
                                 {"max_deviation_m", result->max_deviation_m},
                                 {"tag_match", result->tag_match},
                                 {"frames", motion.frame_count},
                                 {"fps", motion.fps},
                                 {"duration_s", motion.frame_count / motion.fps},
                                 {"seconds", seconds},
                                 {"realtime_factor", seconds > 0.0 ? motion.frame_count / motion.fps / seconds : 0.0},
                                 {"search_seconds", search_seconds},
                                 {"search_realtime_factor",
                                  search_seconds > 0.0 ? motion.frame_count / motion.fps / search_seconds : 0.0},
                                 // CPU time of the search: on a shared machine it varies less than the wall time.
                                 {"search_cpu_seconds", search_cpu_seconds},
                                 {"search_cpu_realtime_factor",
                                  search_cpu_seconds > 0.0 ? motion.frame_count / motion.fps / search_cpu_seconds : 0.0},
                                 {"searches", result->searches},
                                 {"expansions", result->expansions},
                                 {"budget_exhausted_searches", result->budget_exhausted},
                                 {"start_node", result->walk.start_node},
                                 {"edges", result->walk.edges},
                                 {"transitions", transitions},
                                 {"transitions_per_second", transitions_per_second(transitions, motion.frame_count, motion.fps)},
                                 {"segments", segments},
                                 {"path", points},
                                 {"roots", roots},
                                 {"cleanup", cleanup_report(o.common, context, cleanup)}};
  if (auto s = write_synthesis_outputs(o.common, **loaded, motion, result->walk, report); !s) return fail(s.error());
  fmt::print("path {:.1f} m: {} frames ({:.1f} s), covered {:.1f} m{}, deviation mean {:.3f} m max {:.3f} m, "
             "{:.1f} s taken ({:.1f} s searching)\n",
             result->path_length_m, motion.frame_count, motion.frame_count / motion.fps, result->arc_covered_m,
             result->reached_end ? "" : " (end not reached)", result->mean_deviation_m, result->max_deviation_m,
             seconds, search_seconds);
  return 0;
}

}  // namespace

Command add_path_command(CLI::App& app) {
  auto o = std::make_shared<PathOptions>();
  CLI::App* sub = app.add_subcommand(
      "path", "Synthesize motion whose root follows a path on the floor (x east, z south, metres), starting at\n"
              "its first point facing along it. PATH.json: {\"points\": [[x, z], ...], \"segments\":\n"
              "[{\"from_m\": 0, \"to_m\": 20, \"tag\": \"walk\"}, ...]}. Shapes start at the origin heading north\n"
              "(-z): line:L (metres), circle:R (radius, turning right), figure8:R (right loop then left),\n"
              "s-curve:L (metres of a sine wave).");
  o->common.add_to(*sub);
  sub->add_option("--path", o->path_file, "PATH.json")->check(CLI::ExistingFile);
  sub->add_option("--shape", o->shape, "A built-in shape: line:20, circle:5, figure8:4, s-curve:100");
  sub->add_option("--segment", o->segments,
                  "TAG:FROM-TO: ask for a motion type along that arc-length range (metres); repeatable, "
                  "replaces the file's segments");
  sub->add_option("--horizon", o->settings.horizon_s, "Seconds of motion each search looks ahead")
      ->capture_default_str();
  sub->add_option("--commit", o->settings.commit_s, "Seconds of each search's walk kept before searching again")
      ->capture_default_str();
  sub->add_option("--tag-penalty", o->settings.tag_penalty_m2,
                  "Cost (squared metres) of a frame without the tag its segment asks for")
      ->capture_default_str();
  sub->add_option("--max-expansions", o->settings.max_expansions, "Search budget per search (edges evaluated)")
      ->capture_default_str();
  sub->add_option("--beam", o->settings.beam_width,
                  "Beam width of the search's first pass (0: depth-first branch and bound alone)")
      ->capture_default_str();
  sub->add_option("--min-speed", o->settings.min_speed_mps,
                  "Slowest speed (m/s) before falling behind costs --behind-penalty per metre per frame")
      ->capture_default_str();
  sub->add_option("--transition-penalty", o->settings.transition_penalty_m2,
                  "Cost (m^2) of each transition taken: keeps captured motion between blends (0: Kovar's cost alone)")
      ->capture_default_str();
  sub->add_option("--behind-penalty", o->settings.behind_penalty_m, "Cost (m^2 per metre behind) of dawdling")
      ->capture_default_str();
  sub->add_option("--start-node", o->settings.start_node, "Start at this node (default: the best of a sample)");
  return {sub, [o] { return run_path(*o); }};
}

}  // namespace mg::cli
