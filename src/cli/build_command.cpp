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
#include "cli/load_options.h"
#include "cli/unit_report.h"
#include "motiongraph/core/json_text.h"
#include "motiongraph/core/text.h"
#include "motiongraph/io/file.h"
#include "motiongraph/pipeline/build_graph.h"
#include "motiongraph/pipeline/build_options.h"
#ifdef MOTIONGRAPH_MPI
#include "mpi/mpi_team.h"
#endif

namespace mg::cli {

namespace {

using nlohmann::json;

// The library's options (pipeline/build_options.h) and what only the command has: the files
// it writes and the cache folder.
struct BuildCommandOptions {
  BuildOptions build;
  std::vector<std::string> inputs;
  std::string output;
  std::string cache_dir;
  bool no_cache = false;
  std::string report, export_matrix, export_clouds, matrix_png;
  bool quiet = false;
};

// The processes this build runs on: an MPI job's when started by an MPI launcher in a build
// with MPI, else this one alone. Several processes of a build without MPI would each build the
// whole graph: refused.
Result<std::unique_ptr<ProcessTeam>> make_team() {
#ifdef MOTIONGRAPH_MPI
  if (launched_by_mpi()) return std::unique_ptr<ProcessTeam>(std::make_unique<MpiTeam>());
#else
  if (launcher_processes() > 1) {
    return Error{"", 0,
                 "started on several MPI processes, but this motiongraph is built without MPI (install "
                 "libopenmpi-dev and build again; docs/cluster.md)"};
  }
#endif
  return std::unique_ptr<ProcessTeam>(std::make_unique<OneProcess>());
}

int run_build(BuildCommandOptions& o) {
  o.build.exports = {!o.export_matrix.empty(), !o.matrix_png.empty(), !o.export_clouds.empty()};
  auto settings = build_settings_from(o.build);
  if (!settings) return fail_usage(settings.error());
  if (auto s = check_graph_output(o.output); !s) return fail(s.error());
  const std::vector<std::string> outputs = {o.output, o.report, o.matrix_png, o.export_matrix, o.export_clouds};
  if (auto s = check_outputs(outputs, o.inputs); !s) return fail(s.error());
  settings->database.outputs = outputs;  // nor a file a folder or a manifest gives (checked as it is read)
  std::unique_ptr<DistanceCache> cache;
  if (!o.no_cache) {
    cache = std::make_unique<FileDistanceCache>(o.cache_dir.empty() ? default_distance_cache_folder() : o.cache_dir);
  }
  BuildLog log;
  if (!o.quiet) log.info = [](const std::string& line) { spdlog::info("{}", line); };
  log.warning = [](const std::string& line) { spdlog::warn("{}", line); };
  log.loaded = [&](const DatabaseLoadNotes& notes) { report_units(notes, o.quiet); };
  log.progress_bar = !o.quiet;
  auto team = make_team();
  if (!team) return fail(team.error());
  auto built = build_graph(o.inputs, *settings, cache.get(), log, team->get());
  // Only rank 0 tells, and fails the job: the other processes' errors reach it
  // (pipeline/build_graph.h). The others end quietly, so that the launcher does not stop rank 0
  // while it tells.
  if (!built) return built.error().kind == ErrorKind::kOtherProcess ? 0 : fail(built.error());
  if (built->worker) return 0;

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
  auto o = std::make_shared<BuildCommandOptions>();
  BuildOptions& b = o->build;
  CLI::App* sub = app.add_subcommand(
      "build", "Build a motion graph (Kovar et al. 2002): transitions at local minima of the windowed, floor-aligned "
               "point-cloud distance below a threshold; pruned to the largest strongly connected component per tag. "
               "Under mpirun (a build with MPI) the processes share the distance stage: docs/cluster.md.");
  sub->add_option("INPUT", o->inputs, "Folders (an .asf and its .amc files, or .bvh, .glb, .gltf and .fbx files; "
                                      "the folders in them too), clip files, or .toml manifests (see docs/manifest.md)")
      ->required();
  sub->add_option("-o,--output", o->output, "The graph file to write (.mgraph)")->required();
  sub->add_option("--fps", b.fps, "Database frame rate: every clip is resampled to it")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str()
      ->each([o](const std::string&) { o->build.fps_given = true; });
  sub->add_option("--asf", b.asf, "ASF skeleton of AMC files given one by one")->check(CLI::ExistingFile);
  sub->add_option("--scale", b.scale, kScaleHelp);
  sub->add_option("--up-axis", b.up_axis,
                  "Up axis of the clips, y or z (default: per file, whichever the figure stands along; z-up files are "
                  "turned y up)")
      ->check(CLI::IsMember({"y", "z"}));
  sub->add_option("--travel", b.travel,
                  "Where each clip's travel over the floor comes from: root (as read), feet (recovered from the "
                  "planted feet), or auto: the feet for clips animated in place, their planted feet sliding")
      ->check(CLI::IsMember({"auto", "root", "feet"}))
      ->capture_default_str();
  sub->add_option("--input-fps", b.input_fps, kInputFpsHelp)->check(CLI::Range(0.01, 10000.0));
  sub->add_flag("--keep-rest-frames", b.keep_rest_frames, kKeepRestFramesHelp);
  sub->add_option("--cmu-index", b.cmu_index,
                  "CMU's motion index (cmu-mocap-index.tsv) for tags from descriptions; default: one beside or above the "
                  "inputs, else the index the project ships (built in)");
  sub->add_flag("--no-cmu-tags", b.no_cmu_tags, "Do not tag clips from CMU's descriptions");
  sub->add_flag("--no-name-tags", b.no_name_tags,
                "Do not tag clips from the words of their names (Walk_Forward_01.bvh: walk; for clips that neither a "
                "manifest nor CMU's index tags)");
  sub->add_flag("--whole-clip-tags", b.whole_clip_tags,
                "Tag whole clips with the walk or run of their CMU description (by default only the frames where the "
                "root travels 0.25 m/s or more over a second keep them)");
  sub->add_flag("--no-loops", b.no_loops,
                "Do not play clips that loop (a game's cycle: their end meets their start) on past their end; by "
                "default they go on a window further, so that the graph can play them round");
  sub->add_option("--mirror", b.mirror,
                  "auto, on or off: also play every clip mirrored left to right (NAME_mirrored, after the clips read, "
                  "with its tags, turn_left as turn_right), so that walks turning one way turn both; auto mirrors a library under 30 minutes "
                  "whose travel turns 60 degrees or more one way and less than a third of that the other (a studio's "
                  "walk_turn_left without its right turn). Joints pair by their names (lfemur and rfemur, "
                  "LeftUpLeg and RightUpLeg, Hip_L and Hip_R); the distance stage then has four times the pairs")
      ->capture_default_str();
  sub->add_option("--feet", b.feet,
                  "Foot joints as LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,RIGHT_TOE, any left empty to find it by name "
                  "(default: found by name; a manifest's [feet] otherwise)");
  sub->add_flag("--ignore-tags", b.ignore_tags, "Prune to the largest strongly connected component only, ignoring tags");
  sub->add_option("--bridges", b.bridges.per_tag_pair,
                  "Bridges per ordered pair of tags that no transition below the threshold joins: their best candidates, "
                  "the best onto each set of tags the arriving frames carry first, then into each clip (0: none)")
      ->capture_default_str();
  sub->add_option("--max-bridge", b.max_bridge_cm,
                  "No bridge above this RMS point distance in cm (0: no cap); the report names the motion types left "
                  "unjoined and the distance that would join them")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  sub->add_option("--bridge-blend", b.bridges.max_blend_factor,
                  "A bridge blends over k sqrt(D / threshold) frames, k the window, at most this many windows (1: as "
                  "long as a transition)")
      ->check(CLI::Range(1.0, 20.0))
      ->capture_default_str();
  sub->add_option("--connect-tags", b.connect_tags,
                  "Motion types whose frames must form a strongly connected region each, and between which bridges "
                  "are added (default: every tag but turn, stop, start, backward)")
      ->delimiter(',');
  sub->add_option("--cloud", b.cloud, "Point cloud: 'rings' (points around each bone) or 'joints'")->capture_default_str();
  sub->add_option("--ring-spacing", b.cloud_settings.ring_spacing_m, "Metres between rings along a bone")
      ->capture_default_str();
  sub->add_option("--ring-radius", b.cloud_settings.ring_radius_m, "Metres from a bone to its ring's points")
      ->capture_default_str();
  sub->add_option("--ring-points", b.cloud_settings.points_per_ring, "Points per ring")->capture_default_str();
  sub->add_option("--joint-weight", b.joint_weights, "Weight of the points on the bone ending at a joint, NAME=WEIGHT "
                                                      "(repeatable; others weigh 1)");
  sub->add_option("--window", b.distance.window_frames, "Window and blend length k in frames (0: a third of a second)")
      ->capture_default_str();
  sub->add_option("--taper", b.taper, "Weights over the window: 'uniform' or 'hann'")->capture_default_str();
  sub->add_option("--threshold", b.threshold,
                  "'auto': the lowest threshold at which the pruned graph keeps --coverage of each motion type's "
                  "frames (one per type unless --no-tag-thresholds), at most --max-threshold; or an RMS point "
                  "distance over the window such as '4cm'; or an absolute distance D")
      ->capture_default_str();
  sub->add_option("--threshold-quantile", b.quantile,
                  "Instead of --threshold: the fraction of all defined pairs below the threshold (e.g. 0.02)");
  sub->add_option("--coverage", b.choice.coverage,
                  "--threshold auto: the share of each motion type's frames (and of the clips' of no type; of all "
                  "frames when no clip has a type) the pruned graph keeps")
      ->capture_default_str();
  sub->add_option("--min-transition-rate", b.choice.min_transition_rate,
                  "--threshold auto: transitions per second of kept motion the graph must offer (to be steerable)")
      ->capture_default_str();
  sub->add_option("--max-threshold", b.choice.max_rms_cm,
                  "--threshold auto: the highest threshold it may choose, as RMS point distance in cm (quality ceiling)")
      ->capture_default_str();
  sub->add_option("--path-check", b.path_check.tolerance_m,
                  "--threshold auto: raise the threshold (up to --max-threshold) until a test path of half circles of "
                  "4 m, right then left, and its mirror are both followed within this mean deviation in metres")
      ->capture_default_str();
  sub->add_flag("--no-path-check", b.no_path_check, "--threshold auto: keep the coverage threshold, untested");
  sub->add_flag("--no-path-check-mirror", b.no_path_check_mirror,
                "--threshold auto: judge a threshold by the test path alone, not by the worse of it and its mirror");
  sub->add_option("--max-out", b.spacing.max_out,
                  "Transitions leaving any --out-window consecutive frames of a clip, the best kept (0: no limit)")
      ->capture_default_str();
  sub->add_option("--out-window", b.spacing.out_window_frames,
                  "The stretch of frames --max-out counts over (-1: the window)")
      ->capture_default_str();
  sub->add_option("--min-piece", b.spacing.min_piece_frames,
                  "Frames of captured motion between arriving by a transition and leaving by the next (0: off)")
      ->capture_default_str();
  // A callback rather than "!--no-tag-thresholds", whose help read "--no-tag-thresholds{false}".
  sub->add_flag_callback(
      "--no-tag-thresholds", [o] { o->build.transitions.per_tag_thresholds = false; },
      "One threshold for everything: no motion type gets its own (by default, with --threshold auto, each gets the "
      "lowest at which it reaches --coverage; with a threshold given by hand, each keeps the same share of its own "
      "candidates as the database keeps of all)");
  sub->add_option("--locality", b.transitions.locality_radius,
                  "Keep the best transition within this many frames (-1: half the window)")
      ->capture_default_str();
  sub->add_option("--continuation-radius", b.continuation_radius,
                  "Ignore pairs of a clip simply continuing within this many frames of b = a + k - 1 (-1: the window)")
      ->capture_default_str();
  sub->add_option("--tile", b.tile_frames,
                  "Tile side in frames for the distance stage (0: 1024 for the exhaustive stage, from the window for "
                  "the pruned one: 64 at 30 fps, 256 at 120 fps)")
      ->capture_default_str();
  sub->add_flag("--exhaustive", b.exhaustive,
                "Compute every pair's distance. By default, with --threshold auto (or a threshold given as a distance "
                "under --max-threshold, with one threshold for all motion types) and no --export-matrix, only the "
                "tiles that can hold a pair below --max-threshold are computed (the same graph at the same --tile; "
                "bridges above it are found on demand), from --pruned-from frames on");
  sub->add_option("--pruned-from", b.pruned_from,
                  "Libraries of fewer frames run the exhaustive stage, faster there (0: the pruned stage at any size)")
      ->capture_default_str();
  sub->add_option("--threads", b.distance.threads, "Worker threads (0: one per core)")->capture_default_str();
  sub->add_option("--checkpoint", b.shared.checkpoint_folder,
                  "Keep the distance stage's finished tiles in this folder, so that the same build started again "
                  "skips them (a folder of another build's is refused); see docs/cluster.md");
  sub->add_option("--checkpoint-pairs", b.shared.checkpoint_pairs,
                  "--checkpoint: frame pairs per saved chunk of tiles (each process saves its own)")
      ->check(CLI::Range(1LL, 1LL << 50))
      ->capture_default_str();
  sub->add_option("--cache-dir", o->cache_dir, "Where the distance stage is cached (default: $XDG_CACHE_HOME/motiongraph)");
  sub->add_flag("--no-cache", o->no_cache, "Neither read nor write the distance cache");
  sub->add_option("--report", o->report,
                  "Write a JSON report (clips, settings, counts, graph statistics, timings, the warnings printed)");
  sub->add_option("--export-matrix", o->export_matrix, "Write the N x N distance matrix (.npy float32, NaN undefined; "
                                                       "row = frame we leave, column = frame we arrive at)");
  sub->add_option("--export-clouds", o->export_clouds, "Write the point clouds (.npy float32, N x P x 3, metres)");
  sub->add_option("--matrix-png", o->matrix_png, "Write the distance picture with clip boundaries and transitions (PNG)");
  sub->add_flag("-q,--quiet", o->quiet, "No progress or summary on stderr");
  return {sub, [o] { return run_build(*o); }};
}

}  // namespace mg::cli
