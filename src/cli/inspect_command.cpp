// motiongraph inspect GRAPH.mgraph: what a graph file holds, from its stored report.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "motiongraph/core/json_text.h"
#include "motiongraph/graph/clip_coverage.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/graph/threshold_choice.h"
#include "motiongraph/io/file.h"
#include "motiongraph/synthesis/facing.h"

namespace mg::cli {

namespace {

struct InspectOptions {
  std::string graph;
  bool json = false;
  bool nodes = false;
  bool clips = false;
};

// One line per skeleton: which way it faces (synthesis/facing.h), so that a rig whose hips were
// not found, or whose facing was turned about by its travel, shows it.
void print_facings(const MotionDatabase& db) {
  const std::vector<Vec3> travel = learn_travel_axes(db);
  for (size_t s = 0; s < db.skeletons.size(); ++s) {
    const ForwardAxisChoice c = choose_forward_axis(db, static_cast<int>(s), travel[s]);
    const Skeleton& skeleton = db.skeletons[s];
    const std::string who = db.skeletons.size() > 1 ? fmt::format(" ({})", db.skeleton_names[s]) : "";
    const std::string axis = fmt::format("{:+.2f} {:+.2f} {:+.2f} in the root's frame", c.axis.x(), c.axis.y(),
                                         c.axis.z());
    if (c.left_hip < 0) {
      fmt::print("facing{}: {}, the way its clips travel ({})\n", who, axis, c.why_not_hips);
      continue;
    }
    const double off = std::acos(std::clamp(c.axis.normalized().dot(c.travel_axis.normalized()), -1.0, 1.0)) * 180.0 /
                       std::numbers::pi;
    fmt::print("facing{}: {}, square to the hips {} and {}{}; its clips travel {:.1f} degrees off it\n", who, axis,
               skeleton.joint(c.left_hip).name, skeleton.joint(c.right_hip).name,
               c.turned_about ? " (turned about: its clips travel the other way from up x (right - left))" : "", off);
  }
}

// The clip column's width: the longest clip name, at least `least`.
size_t clip_column_width(const MotionDatabase& db, size_t least) {
  size_t width = least;
  for (const DatabaseClip& clip : db.clips) width = std::max(width, clip.name.size());
  return width;
}

// One line per node: its index (what `walk --from/--to` take), frame, clip, tags, edges out.
void print_nodes(const GraphFile& file) {
  const MotionDatabase& db = file.database;
  const MotionGraph& graph = file.graph;
  const std::vector<TagMask> tags = db.frame_tags();
  const size_t width = clip_column_width(db, 10);
  fmt::print("{:>6} {:>7} {:<{}} {:>6} {:>4} {:>11}  {}\n", "node", "frame", "clip", width, "at", "out", "transitions",
             "tags");
  for (int n = 0; n < graph.node_count(); ++n) {
    const GraphNode& node = graph.nodes[n];
    const DatabaseClip& clip = db.clips[node.clip];
    int transitions = 0;
    for (const GraphEdge& e : graph.out_edges(n)) transitions += e.transition ? 1 : 0;
    const std::vector<std::string> names = db.tag_names_of(tags.empty() ? 0 : tags[node.frame]);
    fmt::print("{:>6} {:>7} {:<{}} {:>5.2f}s {:>4} {:>11}  {}\n", n, node.frame, clip.name, width,
               (node.frame - clip.first_frame) / db.fps, graph.out_edges(n).size(), transitions, fmt::join(names, ","));
  }
}

// One line per clip: its frames, the rate its file was read at, how many the pruned graph plays,
// its tags, and for a clip the graph keeps nothing of, the threshold from which the stored
// candidates could join it.
void print_clips(const GraphFile& file, const nlohmann::json& report) {
  const MotionDatabase& db = file.database;
  const std::vector<TagMask> tags = db.frame_tags();
  const double window_weight = report.is_object() ? report.value("window_weight", 0.0) : 0.0;
  const std::vector<ClipCoverage> coverage = clip_coverage(file.graph, db, file.candidates.minima);
  const size_t width = clip_column_width(db, 12);
  fmt::print("{:<{}} {:>7} {:>8} {:>8} {:>7} {:>5}  {:<24} {}\n", "clip", width, "frames", "seconds", "read fps",
             "kept", "%", "tags", "joins from");
  long long kept = 0;
  for (const ClipCoverage& c : coverage) {
    const DatabaseClip& clip = db.clips[c.clip];
    TagMask mask = 0;
    for (int f = clip.first_frame; f < clip.first_frame + clip.frame_count && !tags.empty(); ++f) mask |= tags[f];
    std::string joins;
    if (c.kept_frames == 0) {
      joins = c.best_join < 0.0f || !(window_weight > 0.0)
                  ? std::string("no candidates")
                  : fmt::format("RMS {:.2f} cm", rms_cm_of_distance(c.best_join, window_weight));
    }
    const std::string read_fps = clip.read_fps > 0.0 ? fmt::format("{:g}", clip.read_fps) : std::string("-");
    // Seconds from its first frame to its last, as info says them.
    fmt::print("{:<{}} {:>7} {:>8.2f} {:>8} {:>7} {:>5.0f}  {:<24} {}\n", clip.name, width, c.frames,
               std::max(0, c.frames - 1) / db.fps,
               read_fps, c.kept_frames, 100.0 * c.kept_frames / std::max(1, c.frames),
               fmt::format("{}", fmt::join(db.tag_names_of(mask), ",")), joins);
    kept += c.kept_frames;
  }
  fmt::print("{:<{}} {:>7} {:>8.1f} {:>8} {:>7} {:>5.0f}\n", "all", width, db.frame_count(),
             db.frame_count() / db.fps, "-",
             kept, 100.0 * static_cast<double>(kept) / std::max(1, db.frame_count()));
}

void print_statistics(const char* title, const nlohmann::json& s) {
  const int bridges = s.value("bridges", 0);
  fmt::print("{}: {} nodes, {} edges ({} clip pieces, {} transitions{}), {} clip frames, largest SCC {} nodes\n", title,
             s.value("nodes", 0), s.value("edges", 0), s.value("clip_edges", 0), s.value("transitions", 0),
             bridges > 0 ? fmt::format(" of which {} bridges", bridges) : std::string(),
             s.value("clip_frames", 0), s.value("largest_component_nodes", 0));
  if (s.contains("tags")) {
    bool any_modifier = false;
    for (const auto& tag : s["tags"]) {
      const std::string name = tag.value("name", std::to_string(tag.value("tag", 0)));
      const bool modifier = tag.value("modifier", false);  // every graph file this version reads has it
      any_modifier = any_modifier || modifier;
      fmt::print("  {:<10} {:>6} frames of {:>6}, {:>5} nodes, {:>5} edges, largest SCC {} nodes{}\n", name,
                 tag.value("frames", 0), tag.value("database_frames", 0), tag.value("nodes", 0),
                 tag.value("edges", 0), tag.value("largest_component_nodes", 0), modifier ? " (modifier*)" : "");
    }
    if (any_modifier) {
      fmt::print("  * a modifier tag (turn, stop, start, backward, veer) says how a motion goes, not what it is:\n"
                 "    its frames live in the motion types' regions and need no connected region of their own\n");
    }
  }
}

int run_inspect(const InspectOptions& o) {
  auto file = load_graph_file(o.graph);
  if (!file) return fail(file.error());
  const auto report = nlohmann::json::parse(file->report_json, nullptr, false);
  if (o.nodes) {
    print_nodes(*file);
    return 0;
  }
  if (o.clips) {
    print_clips(*file, report);
    return 0;
  }
  if (o.json) {
    fmt::print("{}\n", json_text(report, 2));
    return 0;
  }
  const MotionDatabase& db = file->database;
  fmt::print("{}: motion graph, format version {}\n", o.graph, kGraphFileVersion);
  fmt::print("database: {} clips, {} frames at {:g} fps ({:.1f} s), {} skeleton(s), tags: {}\n", db.clips.size(),
             db.frame_count(), db.fps, db.frame_count() / db.fps, db.skeletons.size(), fmt::join(db.tag_names, ", "));
  if (report.is_object() && report.contains("mirroring") && report["mirroring"].value("mirrored", 0) > 0) {
    const nlohmann::json& m = report["mirroring"];
    const nlohmann::json& t = m["turning"];
    fmt::print("mirrored: {} clips (NAME_mirrored, --mirror {}; the clips as read turn {:.0f} degrees left and {:.0f} "
               "right)\n",
               m["mirrored"].get<int>(), m.value("mode", std::string("auto")), t.value("left_deg", 0.0),
               t.value("right_deg", 0.0));
  }
  print_facings(db);
  const std::string rms = report.is_object() && report.contains("threshold_rms_cm")
                              ? fmt::format("RMS {:.2f} cm, ", report["threshold_rms_cm"].get<double>())
                              : std::string();
  const std::string mode = report.is_object() ? report.value("threshold_mode", std::string("quantile")) : "quantile";
  fmt::print("window {} frames; threshold {:.4g} ({}{:.3f} % of pairs below; {}); locality {} frames\n",
             file->graph.window, file->threshold, rms, 100.0 * file->threshold_quantile,
             mode == "auto" ? "chosen from the data" : "given", file->locality_radius);
  fmt::print("candidates: {} local minima; {} transitions selected\n", file->candidates.minima.size(),
             report.is_object() ? report["counts"].value("transitions", 0) : 0);
  // The path check build ran on the automatic threshold (synthesis/path_check.h).
  if (report.is_object() && report.contains("path_check") && report["path_check"].is_object()) {
    const auto& check = report["path_check"];
    const auto& points = check["points"];
    const auto chosen = std::find_if(points.begin(), points.end(), [&](const nlohmann::json& p) {
      return p["threshold"] == check["threshold"];
    });
    if (check.value("skipped", false)) {
      fmt::print("path check: skipped (the clips hardly travel)\n");
    } else if (chosen != points.end()) {
      const auto delivered = check.value("delivered", nlohmann::json());
      fmt::print("path check: the {:.0f} m test path{} followed {:.3f} m off{} ({}; {} threshold(s) tried){}\n",
                 check.value("probe_length_m", 0.0),
                 check.value("mirrored", false) ? " and its mirror (the worse of the two)" : "",
                 (*chosen).value("mean_deviation_m", 0.0),
                 (*chosen).value("reached_end", false) ? "" : ", end not reached",
                 check.value("passed", false) ? fmt::format("within {:g} m", check.value("tolerance_m", 0.0))
                                              : std::string("NOT within the tolerance: the clips may hold few turns"),
                 points.size(),
                 delivered.is_object() ? fmt::format("; path's motion, bent onto it: {:.3f} m off",
                                                     delivered.value("mean_deviation_m", 0.0))
                                       : std::string());
    }
  }
  if (report.is_object()) {
    print_statistics("before pruning", report["graph_before"]);
    print_statistics("after pruning ", report["graph_after"]);
    if (report.contains("timings")) {
      std::string timings;
      for (const auto& [stage, seconds] : report["timings"].items()) {
        timings += fmt::format(" {} {:.2f} s", stage, seconds.get<double>());
      }
      fmt::print("timings:{}\n", timings);
    }
    // What the build warned of, kept in the file (graphs built before it was kept have none).
    if (const auto warnings = report.find("warnings"); warnings != report.end() && warnings->is_array() &&
                                                       !warnings->empty()) {
      fmt::print("the build warned:\n");
      for (const nlohmann::json& line : *warnings) {
        if (line.is_string()) fmt::print("  {}\n", line.get<std::string>());
      }
    }
  }
  return 0;
}

}  // namespace

Command add_inspect_command(CLI::App& app) {
  auto o = std::make_shared<InspectOptions>();
  CLI::App* sub = app.add_subcommand("inspect", "Print the statistics of a graph file: database, threshold, graph "
                                                "before and after pruning, per tag, timings, and what the build "
                                                "warned of.");
  sub->add_option("GRAPH", o->graph, "A .mgraph file written by 'motiongraph build'")->required();
  sub->add_flag("--json", o->json, "Print the stored build report as JSON");
  sub->add_flag("--nodes", o->nodes,
                "List the pruned graph's nodes (the numbers 'walk --from/--to' take): frame, clip, time in "
                "the clip, edges out, transitions out, tags");
  sub->add_flag("--clips", o->clips,
                "List the clips: frames, seconds, the rate its file was read at, how many frames the pruned "
                "graph plays, tags, and for a clip it "
                "keeps nothing of, the threshold (RMS) from which its stored candidates could join it");
  return {sub, [o] { return run_inspect(*o); }};
}

}  // namespace mg::cli
