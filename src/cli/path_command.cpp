// motiongraph path GRAPH (--path PATH.json | --shape SPEC) -o OUT: path synthesis
// (synthesis/path_synthesis.h).
#include <chrono>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/synthesis_options.h"
#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/path_check.h"
#include "motiongraph/synthesis/path_synthesis.h"

namespace mg::cli {

namespace {

struct PathOptions {
  SynthesisOptions common;
  std::string path_file;
  std::string shape;
  std::vector<std::string> segments;
  PathSynthesisSettings settings;
};

int run_path(const PathOptions& o) {
  const auto begin = std::chrono::steady_clock::now();
  if (auto s = o.settings.validate(); !s) return fail_usage(s.error());
  if (auto s = check_output_options(o.common); !s) return fail_usage(s.error());
  auto path = make_floor_path({o.path_file, o.shape, {}, o.segments});
  // The command line's --shape and --segment (and giving one path): usage; the file's, its own.
  if (!path) return path.error().file.empty() ? fail_usage(path.error()) : fail(path.error());
  auto loaded = load_for_synthesis(o.common, {o.path_file});
  if (!loaded) return fail(loaded.error());
  const SynthesisContext& context = (*loaded)->context();
  if (auto s = check_segment_tags(context, *path, o.path_file); !s) return fail(s.error());
  auto result = run_path_synthesis(context, *path, o.settings, run_settings(o.common, begin));
  if (!result) return fail(result.error());
  const nlohmann::json& r = result->report;
  if (auto s = write_synthesis_outputs(o.common, **loaded, result->motion, result->walk, r); !s) return fail(s.error());
  const nlohmann::json& edit = r["path_edit"];
  const std::string edited =
      edit["edited"].get<bool>()
          ? fmt::format(" (as the graph played it {:.3f} m, {:.3f} m; bent onto the path, turning at the limit "
                        "over {:.0f} % of it)",
                        r["graph_mean_deviation_m"].get<double>(), r["graph_max_deviation_m"].get<double>(),
                        100.0 * edit["limited_share"].get<double>())
      : edit.value("undone", false) ? std::string(" (as the graph played it: bent onto the path, it went further off)")
                                    : std::string();
  const int attempts = r["attempts"].get<int>();
  const std::string pushed =
      attempts > 1 ? fmt::format(" after {} searches of the whole path (kept: {:g} s ahead, behind penalty {:g}, tag "
                                 "penalty {:g}{}{})",
                                 attempts, r["horizon_s"].get<double>(), r["behind_penalty_m"].get<double>(),
                                 r["tag_penalty_m2"].get<double>(),
                                 r["anchor_arc"].get<bool>() ? ", its arc corrected as it went" : "",
                                 r["edit_in_search"].get<bool>() ? ", the edit in the search" : "")
                   : std::string();
  fmt::print("path {:.1f} m: {} frames ({:.1f} s), {:.1f} m along it, ending {:.2f} m from its end{}{}, deviation mean "
             "{:.3f} m max {:.3f} m{}, {:.1f} s taken ({:.1f} s searching)\n",
             r["path_length_m"].get<double>(), result->motion.frame_count, r["duration_s"].get<double>(),
             r["arc_covered_m"].get<double>(), r["end_distance_m"].get<double>(),
             r["reached_end"].get<bool>() ? "" : " (end not reached)", pushed,
             r["mean_deviation_m"].get<double>(), r["max_deviation_m"].get<double>(), edited,
             r["seconds"].get<double>(), r["search_seconds"].get<double>());
  // Said apart from the summary: the motion is written, but it is not all that was asked (the
  // segments' types the graph can hardly play, the clean-up not made, the shortfalls).
  print_warnings(result->warnings);
  // Each segment's motion type: how much of the motion in it carries it.
  std::string segments;
  for (const nlohmann::json& s : r["segments"]) {
    segments += fmt::format("{}{} {:g}-{:g} m: ", segments.empty() ? "" : "; ", s["tag"].get<std::string>(),
                            s["from_m"].get<double>(), s["to_m"].get<double>());
    segments += s["tag_match"].is_null()
                    ? std::string("no frames")
                    : fmt::format("{:.0f} % of {} frames", 100.0 * s["tag_match"].get<double>(), s["frames"].get<int>());
  }
  if (!segments.empty()) fmt::print("segments (frames carrying the type asked): {}\n", segments);
  if (const nlohmann::json& rest = r["rest"]; !rest.is_null()) {
    fmt::print("at rest from {:.2f} s at the end of {}, {:.2f} m from the path's end\n", rest["at_s"].get<double>(),
               rest["clip"].get<std::string>(), r["end_distance_m"].get<double>());
  }
  return 0;
}

}  // namespace

Command add_path_command(CLI::App& app) {
  auto o = std::make_shared<PathOptions>();
  CLI::App* sub = app.add_subcommand(
      "path", "Synthesize motion whose root follows a path on the floor (x east, z south, metres), starting at\n"
              "its first point heading along it (the skeleton's mean direction of travel). PATH.json:\n"
              "{\"points\": [[x, z], ...], \"segments\": [{\"from_m\": 0, \"to_m\": 20, \"tag\": \"walk\"}, ...]}.\n"
              "Shapes start at the origin heading north (-z): line:L (metres), circle:R (radius, turning\n"
              "right), figure8:R (right loop then left), s-curve:L (metres of a sine wave), square:S (side,\n"
              "turning right at its corners), zigzag:L (eight legs, 45 degrees right and left of north).");
  o->common.add_to(*sub);
  sub->add_option("--path", o->path_file, "PATH.json")->check(CLI::ExistingFile);
  sub->add_option("--shape", o->shape,
                  "A built-in shape: line:20, circle:5, figure8:4, s-curve:100, square:10, zigzag:6");
  sub->add_option("--segment", o->segments,
                  "TAG:FROM-TO: ask for a motion type along that arc-length range (metres); repeatable (where "
                  "two overlap, the later one is asked for), replaces the file's segments");
  sub->add_option("--horizon", o->settings.horizon_s, "Seconds of motion each search looks ahead")
      ->capture_default_str();
  sub->add_option("--commit", o->settings.commit_s, "Seconds of each search's walk kept before searching again")
      ->capture_default_str();
  sub->add_option("--tag-penalty", o->settings.tag_penalty_m2,
                  "Cost (squared metres) of a frame without the tag its segment asks for")
      ->capture_default_str();
  sub->add_option("--tag-lookahead", o->settings.tag_lookahead,
                  "Weight (0 to 1) of what a walk that reaches the horizon inside a segment still pays before its tag "
                  "(its frames without it, the transitions and bridges on the way), so that a motion type no walk "
                  "within the horizon reaches is headed for (0: the horizon only)")
      ->capture_default_str();
  sub->add_option("--max-expansions", o->settings.max_expansions, "Search budget per search (edges evaluated)")
      ->capture_default_str();
  sub->add_option("--beam", o->settings.beam_width,
                  "Beam width of the search's first pass (0: depth-first branch and bound alone)")
      ->capture_default_str();
  sub->add_option("--min-speed", o->settings.min_speed_mps,
                  "Slowest speed (m/s) before falling behind costs --behind-penalty per metre per frame; a motion "
                  "slower than it (or than the type a segment asks for moves) over a segment dawdled (0: neither)")
      ->capture_default_str();
  sub->add_option("--transition-penalty", o->settings.transition_penalty_m2,
                  "Cost (m^2) of each transition taken: keeps captured motion between blends (0: Kovar's cost alone)")
      ->capture_default_str();
  sub->add_option("--bridge-penalty", o->settings.bridge_penalty_m2,
                  "Cost (m^2) of each bridge (a blend between motion types above the threshold) taken, on top of "
                  "--transition-penalty, unless it leads into the motion type a --segment asks for there (0: as any "
                  "transition)")
      ->capture_default_str();
  sub->add_option("--behind-penalty", o->settings.behind_penalty_m, "Cost (m^2 per metre behind) of dawdling")
      ->capture_default_str();
  sub->add_option("--start-node", o->settings.start_node,
                  "Start at this node (default: the best of about 16 spread over the graph and over its sets of tags)")
      ->check(CLI::Range(0, 100000000));
  sub->add_option("--progress-retries", o->settings.progress_retries,
                  "When the motion does not reach the path's end, or takes longer over a segment (or over the "
                  "stretches no segment holds) than --min-speed (or the median speed of the type it asks for, where "
                  "slower) would, a second more (it dawdled), or "
                  "follows it more than --retry-deviation off, or misses a segment's motion type (--retry-tag-match), "
                  "search again up to this many times, looking --retry-horizon ahead: the "
                  "same search; with the search's arc corrected to the way along the path the walk has come; "
                  "--behind-penalty 4x; then the search sees where the path edit puts the walk, at 1x and 4x; then "
                  "16x, 64x, ...; where a missed type is all that is wrong with the best so far, --tag-penalty 4x "
                  "the last raised one too; the "
                  "first to reach the end without dawdling within --retry-deviation, missing no type, is "
                  "kept, else the one reaching it (without dawdling if any does; then within --retry-deviation, and "
                  "among those missing the fewest types) with the least deviation")
      ->capture_default_str();
  sub->add_option("--retry-horizon", o->settings.retry_horizon_s,
                  "Seconds of motion each search of the retries looks ahead (0: --horizon): at a sharp corner a "
                  "longer look finds a turn that pays off later")
      ->capture_default_str();
  sub->add_option("--retry-deviation", o->settings.retry_deviation_m,
                  "Mean deviation (m) above which --progress-retries searches again (0: only when the end is not "
                  "reached or the motion dawdled)")
      ->capture_default_str();
  sub->add_option("--retry-tag-match", o->settings.retry_tag_match,
                  "A segment of 2 s or more of motion whose frames carry the motion type it asks for (one the graph "
                  "plays; not a modifier such as stop or turn) less than this share of them missed it, and "
                  "--progress-retries searches again (0, or --tag-penalty 0: never for that)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  sub->add_flag("--rest-at-end", o->settings.rest_at_end,
                "Come to rest at the path's end: from the walk's nodes near the end, the way on that stands nearest "
                "it, to the end of a clip that ends standing still; the whole motion bent onto the path (the graph "
                "needs such a clip)");
  sub->add_flag_callback(
      "--no-path-edit", [o] { o->settings.edit_path = false; },
      "Keep the motion as the graph plays it; by default it is bent onto the path (Gleicher's motion path editing), "
      "adding at most --edit-max-turn of turning");
  sub->add_option("--edit-max-turn", o->settings.path_edit.max_turn_deg_per_m,
                  "Turning (degrees per metre travelled) the path edit may add; where bending the motion onto the "
                  "path would take more, it is bent less and follows the path less closely")
      ->capture_default_str();
  sub->add_option("--edit-round-corners", o->settings.path_edit.round_corners_m,
                  "The path edit steers for the path with its corners rounded over +- this many metres of arc, "
                  "cutting them evenly where it cannot turn as sharply (0: the path as drawn)")
      ->capture_default_str();
  return {sub, [o] { return run_path(*o); }};
}

}  // namespace mg::cli
