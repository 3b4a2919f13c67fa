// motiongraph info FILE...: skeleton and clip summary per file (text, or --json).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/library_info.h"
#include "cli/load_options.h"
#include "cli/unit_report.h"
#include "motiongraph/core/file_extension.h"
#include "motiongraph/core/json_text.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/clip_doubts.h"
#include "motiongraph/motion/clip_summary.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/up_axis.h"
#include "motiongraph/pipeline/clip_as_read.h"
#include "motiongraph/pipeline/feet_report.h"

namespace mg::cli {

namespace {

struct InfoOptions {
  std::vector<std::string> files;
  LoadOptions load;
  bool json = false;
  // For folders and manifests, read as build reads them.
  double fps = 30.0;
  bool fps_given = false;
  std::string cmu_index;
  bool no_cmu_tags = false;
  bool no_name_tags = false;
  bool whole_clip_tags = false;
  bool no_loops = false;
  std::string mirror = "auto";
};

int run_library(const InfoOptions& options) {
  LibraryInfoOptions library;
  library.json = options.json;
  DatabaseSettings& db = library.database;
  db = database_settings_reading_as(options.load.settings());
  db.fps = options.fps;
  db.prefer_manifest_fps = !options.fps_given;
  db.cmu_tags = !options.no_cmu_tags;
  db.name_tags = !options.no_name_tags;
  if (options.whole_clip_tags) db.travel_tags.min_speed_mps = 0.0;
  db.loops = !options.no_loops;
  db.cmu_index_path = options.cmu_index;
  db.mirror = *parse_mirroring(options.mirror);  // checked by run_info
  return run_library_info(options.files, library);
}

nlohmann::json static_ancestor_names(const Skeleton& skeleton) {
  nlohmann::json names = nlohmann::json::array();
  for (const StaticAncestor& a : skeleton.static_ancestors()) names.push_back(a.name);
  return names;
}

nlohmann::json skeleton_json(const Skeleton& skeleton) {
  nlohmann::json joints = nlohmann::json::array();
  for (const JointDef& joint : skeleton.joints()) {
    joints.push_back({{"name", joint.name}, {"parent", joint.parent}, {"end_site", joint.end_site}});
  }
  return joints;
}

int run_info(const InfoOptions& options) {
  if (!parse_mirroring(options.mirror)) {
    return fail_usage(Error{"", 0, "--mirror must be auto, on or off, not " + options.mirror});
  }
  if (is_library(options.files)) return run_library(options);
  if (options.fps_given || !options.cmu_index.empty() || options.no_cmu_tags || options.no_name_tags ||
      options.whole_clip_tags || options.no_loops || options.mirror != "auto") {
    spdlog::warn("--fps, --cmu-index, --no-cmu-tags, --no-name-tags, --whole-clip-tags, --no-loops and --mirror apply "
                 "to folders and manifests (a library); these files are summarised as read");
  }
  ClipLoadSettings settings = options.load.settings();
  // An .asf among the files is the skeleton of the .amc files given with it.
  for (const std::string& file : options.files) {
    if (lower_extension(file) == ".asf" && !settings.asf_path) settings.asf_path = file;
  }
  ClipLoader loader(settings);
  nlohmann::json all = nlohmann::json::array();
  for (const std::string& file : options.files) {
    if (lower_extension(file) == ".asf") {
      auto rig = loader.load_asf(file);
      if (!rig) return fail(rig.error());
      const Skeleton& skeleton = (*rig)->skeleton;
      int end_sites = 0;
      for (const JointDef& joint : skeleton.joints()) end_sites += joint.end_site ? 1 : 0;
      const int dofs = (*rig)->amc_layout.values_per_frame();
      if (options.json) {
        all.push_back({{"file", file}, {"format", "asf"}, {"joints", skeleton.joint_count() - end_sites},
                       {"end_sites", end_sites}, {"dofs", dofs}, {"metres_per_unit", (*rig)->metres_per_unit},
                       {"skeleton", skeleton_json(skeleton)}});
      } else {
        fmt::print("{}: ASF skeleton, {} joints + {} end sites, {} dofs, 1 unit = {:.6f} m, leg length {:.3f} m\n",
                   file, skeleton.joint_count() - end_sites, end_sites, dofs, (*rig)->metres_per_unit,
                   skeleton.leg_length_m());
      }
      continue;
    }
    auto loaded = loader.load(file);
    if (!loaded) return fail(loaded.error());
    const Clip& clip = loaded->clip;
    const ClipSummary s = summarize(clip.skeleton, clip.motion);
    // The feet (named by --feet or found by name) and their contacts: what the foot clean-up, the
    // in-place travel and the doubts below follow.
    auto judged = judge_clip_as_read(clip.skeleton, clip.motion, {}, clip.motion.fps, loaded->format,
                                     settings.foot_names);
    if (!judged) return fail(Error{file, 0, "--feet: " + judged.error().message});
    const std::optional<ClipContacts>& contacts = judged->contacts;
    const std::string& feet_missing = judged->feet_missing;
    const ClipDoubts& doubts = judged->doubts;
    // Capture glitches within it, where a library cuts it (motion/capture_glitches.h).
    const GlitchFreeParts glitch_parts =
        settings.keep_rest_frames ? GlitchFreeParts{} : glitch_free_parts(clip.skeleton, clip.motion);
    const std::string glitches = clip_glitches_description(clip, glitch_parts);
    const char* feet_source = settings.foot_names.empty() ? "found by name" : "--feet";
    if (clip.detected_unit && !clip.detected_unit->plausible) report_unit(file, *clip.detected_unit);
    std::string unit = fmt::format("{:g} m per unit (--scale)", options.load.scale.value_or(1.0));
    if (loaded->format == "amc") unit = "the ASF's units";
    if (loaded->format == "gltf") unit = "metres (glTF's)";
    if (loaded->format == "fbx") {
      unit = fmt::format("{:g} m (the FBX file's: centimetres times its UnitScaleFactor {:g})",
                         loaded->file_metres_per_unit, loaded->file_metres_per_unit * 100.0);
      if (options.load.scale) unit = fmt::format("{:g} m per unit of the file's numbers (--scale)", *options.load.scale);
    }
    if (clip.detected_unit && loaded->format == "fbx") {
      unit = fmt::format("{} (chosen by its size: the FBX file's own unit, {:g} m, made it {:.3g} m; --scale overrides)",
                         unit_description(*clip.detected_unit), loaded->file_metres_per_unit,
                         clip.detected_unit->figure_size_units * loaded->file_metres_per_unit);
    } else if (clip.detected_unit) {
      unit = unit_description(*clip.detected_unit) + " (chosen by its size; --scale overrides)";
    }
    std::string up = clip.detected_up_axis ? up_axis_description(*clip.detected_up_axis) +
                                                 " (chosen by its shape; --up-axis overrides)"
                                           : options.load.up_axis + " (--up-axis)";
    if (loaded->format == "gltf" && options.load.up_axis.empty()) up = "y (glTF's; --up-axis z turns it)";
    if (loaded->format == "fbx" && options.load.up_axis.empty()) {
      up = fmt::format("{} (the FBX file's{}; --up-axis takes the file as y or z up)", loaded->file_up_axis,
                       loaded->file_up_axis == "+y" ? "" : ", turned y up");
    }
    std::string static_joints;
    for (const StaticAncestor& a : clip.skeleton.static_ancestors()) {
      static_joints += (static_joints.empty() ? "" : ", ") + a.name;
    }
    if (options.json) {
      nlohmann::json entry = {
          {"file", file}, {"format", loaded->format}, {"joints", s.joints}, {"end_sites", s.end_sites},
          {"dofs", loaded->source_channels}, {"frames", s.frames}, {"fps", s.fps}, {"duration_s", s.duration_s},
          {"dropped_leading_frames", clip.dropped_leading_frames},
          {"glitched_leading_frames", clip.glitched_leading_frames},
          {"glitched_trailing_frames", clip.glitched_trailing_frames},
          {"floor_extent_m", {{"x", {s.floor_min_x_m, s.floor_max_x_m}}, {"z", {s.floor_min_z_m, s.floor_max_z_m}}}},
          {"height_m", {s.min_height_m, s.max_height_m}}, {"root_path_m", s.root_path_m},
          {"root", clip.skeleton.joint(0).name}, {"static_joints_above_root", static_ancestor_names(clip.skeleton)},
          {"joints_dropped_above_root", clip.dropped_at_fold},
          {"doubts", doubts.phrases()}, {"skeleton", skeleton_json(clip.skeleton)}};
      // Where a library cuts it: the glitches (the file's frames, 1-based, and seconds) and the
      // frames it drops.
      nlohmann::json glitch_list = nlohmann::json::array();
      for (const FileGlitch& g : in_file_frames(clip, glitch_parts.glitches)) {
        glitch_list.push_back({{"frame", g.frame}, {"seconds", g.seconds}, {"joint", g.joint}, {"jump_m", g.jump_m}});
      }
      entry["capture_glitches"] = {
          {"glitches", std::move(glitch_list)},
          {"parts", glitch_parts.glitches.empty() ? 1 : glitch_parts.parts.size()},
          {"dropped_frames", glitch_parts.glitches.empty() ? 0 : glitch_parts.dropped_frames(clip.motion.frame_count)}};
      // How fast its flights fall: the clock's evidence, doubted or not.
      const FlightFall& fall = doubts.flight_fall;
      entry["flight_fall"] = {{"flights", fall.flights},
                              {"highest_rise_m", fall.highest_rise_m},
                              {"fall_mps2", fall.measured() ? nlohmann::json(fall.fall_mps2) : nlohmann::json(nullptr)},
                              {"slowdown", fall.measured() ? nlohmann::json(fall.slowdown()) : nlohmann::json(nullptr)}};
      // How long its walking strides take for their length: the clock's evidence where it has no flights.
      const WalkPace& walk = doubts.walk_pace;
      entry["walk_pace"] = {{"strides", walk.strides},
                            {"stride_m", walk.measured() ? nlohmann::json(walk.stride_m) : nlohmann::json(nullptr)},
                            {"stride_s", walk.measured() ? nlohmann::json(walk.stride_s) : nlohmann::json(nullptr)},
                            {"walk_ratio", walk.measured() ? nlohmann::json(walk.walk_ratio) : nlohmann::json(nullptr)},
                            {"slowdown", walk.measured() ? nlohmann::json(walk.slowdown()) : nlohmann::json(nullptr)},
                            {"figure_m", walk.measured() ? nlohmann::json(walk.figure_m) : nlohmann::json(nullptr)}};
      entry["feet"] = contacts ? feet_json(clip.skeleton, contacts->feet, contacts->masks, feet_source)
                                : missing_feet_json(feet_missing);
      if (!loaded->skeleton_path.empty()) entry["asf"] = loaded->skeleton_path;
      if (!loaded->animations.empty()) entry["animations"] = loaded->animations;
      if (clip.detected_unit) {
        entry["unit"] = {{"name", clip.detected_unit->unit.name},
                         {"metres_per_unit", clip.detected_unit->unit.metres_per_unit},
                         {"figure_size_m", clip.detected_unit->figure_size_m},
                         {"plausible", clip.detected_unit->plausible}};
      }
      if (loaded->format == "fbx") {
        entry["unit"] = {{"name", "fbx"}, {"metres_per_unit", loaded->file_metres_per_unit}};
        if (options.load.up_axis.empty()) entry["up_axis"] = {{"axis", loaded->file_up_axis}, {"source", "file"}};
      }
      if (clip.detected_up_axis) {
        entry["up_axis"] = {{"axis", up_axis_name(clip.detected_up_axis->axis)},
                            {"animation_ratio", clip.detected_up_axis->animation_ratio},
                            {"rest_ratio", clip.detected_up_axis->rest_ratio}};
      } else if (!options.load.up_axis.empty()) {
        entry["up_axis"] = {{"axis", options.load.up_axis}};
      }
      if (clip.in_place) {
        entry["travel"] = {{"source", clip.in_place->recovered ? "feet" : "root"},
                           {"in_place", clip.in_place->in_place},
                           {"slide_speed_m_s", clip.in_place->slide_speed_m_s},
                           {"root_speed_m_s", clip.in_place->root_speed_m_s},
                           {"recovered_m", clip.in_place->recovered_m}};
      } else {
        entry["travel"] = {{"source", "root"}};
      }
      all.push_back(std::move(entry));
    } else {
      if (loaded->format == "gltf" || loaded->format == "fbx") {
        fmt::print("{}: {}, animation '{}' ({} of {}: {}; convert --animation picks one, a library reads "
                   "them all)\n",
                   file, loaded->format == "fbx" ? "FBX" : "glTF", loaded->animations[static_cast<size_t>(loaded->animation)], loaded->animation + 1,
                   loaded->animations.size(), fmt::join(loaded->animations, ", "));
      } else {
        fmt::print("{}: {}{}\n", file, loaded->format == "amc" ? "AMC on " : "BVH",
                   loaded->format == "amc" ? loaded->skeleton_path : "");
      }
      fmt::print("  skeleton: {} joints + {} end sites, {} dofs\n", s.joints, s.end_sites, loaded->source_channels);
      std::vector<std::string> dropped;
      if (clip.dropped_leading_frames > 0) dropped.push_back("leading rest/T-pose frames dropped");
      if (clip.glitched_leading_frames > 0 || clip.glitched_trailing_frames > 0) {
        dropped.push_back(glitched_ends_description(clip.glitched_leading_frames, clip.glitched_trailing_frames));
      }
      fmt::print("  motion:   {} frame{} at {:g} fps, {:.2f} s{}\n", s.frames, s.frames == 1 ? "" : "s", s.fps,
                 s.duration_s, dropped.empty() ? "" : fmt::format(" ({})", fmt::join(dropped, "; ")));
      fmt::print("  lengths:  {}\n", unit);
      fmt::print("  up:       {}\n", up);
      fmt::print("  feet:     {}\n", contacts ? feet_description(clip.skeleton, contacts->feet,
                                                                contacts->masks, feet_source)
                                               : missing_feet_description(feet_missing));
      if (clip.in_place && clip.in_place->recovered) {
        fmt::print("  travel:   {} (--travel overrides)\n", travel_description(*clip.in_place));
      }
      if (!static_joints.empty()) {
        fmt::print("  root:     {} carries the floor position and facing (above it, folded in: {}{})\n",
                   clip.skeleton.joint(0).name, static_joints,
                   clip.dropped_at_fold.empty() ? ""
                                                : fmt::format("; dropped, as they hung off it: {}",
                                                              fmt::join(clip.dropped_at_fold, ", ")));
      }
      fmt::print("  floor:    x {:.2f} .. {:.2f} m, z {:.2f} .. {:.2f} m; height {:.2f} .. {:.2f} m; root travels {:.2f} m\n",
                 s.floor_min_x_m, s.floor_max_x_m, s.floor_min_z_m, s.floor_max_z_m, s.min_height_m,
                 s.max_height_m, s.root_path_m);
      if (!glitches.empty()) fmt::print("  glitches: {} (--keep-rest-frames keeps it whole)\n", glitches);
      if (!doubts.empty()) fmt::print("  warning:  {}\n", clip_doubts_text(doubts));
    }
  }
  if (options.json) fmt::print("{}\n", json_text(all, 2));
  return 0;
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand("info", "Summarise skeletons and clips: joints, dofs, frames, fps, "
                                             "duration, floor extent (metres), up axis, feet, capture glitches; or a "
                                             "library (folders, manifests) as build reads it: its clips, tags and feet.");
  sub->add_option("FILE", options->files,
                  "ASF, AMC, BVH, glTF (.glb, .gltf) or FBX files (an AMC uses the .asf given with it, --asf, or its "
                  "folder's .asf, of several its subject's); or clip folders (with the folders in them) and .toml "
                  "manifests, summarised together as one library")
      ->required()
      ->check(CLI::ExistingPath);
  sub->add_option("--fps", options->fps, "A library's frame rate, as build's --fps (default 30; a manifest's own)")
      ->check(CLI::Range(1.0, 1000.0))
      ->each([o = options.get()](const std::string&) { o->fps_given = true; });
  sub->add_option("--cmu-index", options->cmu_index,
                  "For a library: CMU's motion index for tags, as build's (default: one beside or above the "
                  "inputs, else the one the program ships)")
      ->check(CLI::ExistingFile);
  sub->add_flag("--no-cmu-tags", options->no_cmu_tags, "For a library: no tags from CMU's descriptions");
  sub->add_flag("--no-name-tags", options->no_name_tags, "For a library: no tags from the words of clip names");
  sub->add_flag("--whole-clip-tags", options->whole_clip_tags,
                "For a library: a CMU description's walk or run on the whole clip (by default only where the root "
                "travels 0.25 m/s or more over a second)");
  sub->add_flag("--no-loops", options->no_loops, "For a library: clips that loop are not played on past their end");
  sub->add_option("--mirror", options->mirror,
                  "For a library: auto, on or off: every clip mirrored left to right too, as build reads it (auto: a "
                  "library whose travel turns one way)")
      ->capture_default_str();
  sub->add_flag("--json", options->json, "Print the summary as JSON");
  options->load.add_to(*sub);
  return {sub, [options] { return run_info(*options); }};
}

}  // namespace mg::cli
