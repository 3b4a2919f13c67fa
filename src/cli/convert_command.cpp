// motiongraph convert IN... -o OUT [-o OUT...]: AMC, BVH, glTF or FBX in; BVH, glTF, FBX or
// positions JSON out (metres, FBX centimetres; the JSON with the feet's contacts); the clip is read
// once for all outputs. Several clips of one rig go into one glTF or FBX file, an animation each.
#include <algorithm>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/library_info.h"
#include "cli/load_options.h"
#include "cli/motion_output_options.h"
#include "cli/unit_report.h"
#include "motiongraph/core/file_extension.h"
#include "motiongraph/database/clip_on_skeleton.h"
#include "motiongraph/database/database_loader.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/export/positions_json.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_doubts.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/mirror.h"
#include "motiongraph/skeleton/foot_joints.h"
#include "motiongraph/motion/resample.h"
#include "motiongraph/pipeline/clip_as_read.h"
#include "motiongraph/synthesis/facing.h"

namespace mg::cli {

namespace {

struct ConvertOptions {
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;
  LoadOptions load;
  double fps = 0.0;
  int skeleton = -1;
  std::optional<std::string> animation;
  bool mirror = false;  // each clip's mirror image (motion/mirror.h)
  MotionOutputOptions output;
};

// A clip read as the options say, its messages printed, resampled when asked.
Result<Clip> read_clip(const ConvertOptions& options, ClipLoader& loader, const std::string& input) {
  auto loaded = loader.load(input, options.animation);
  if (!loaded) return loaded.error();
  Clip& clip = loaded->clip;
  if (clip.detected_unit) report_unit(input, *clip.detected_unit);
  if (clip.detected_up_axis) report_up_axis(input, *clip.detected_up_axis);
  if (clip.in_place) report_travel(input, *clip.in_place);
  if (clip.dropped_leading_frames > 0) {
    spdlog::info("{}: dropped {} leading rest/T-pose frame(s) (--keep-rest-frames keeps them)", input,
                 clip.dropped_leading_frames);
  }
  if (clip.glitched_leading_frames > 0 || clip.glitched_trailing_frames > 0) {
    spdlog::info("{}: {} (--keep-rest-frames keeps them)", input,
                 glitched_ends_description(clip.glitched_leading_frames, clip.glitched_trailing_frames));
  }
  if (!options.load.settings().keep_rest_frames) {
    const GlitchFreeParts found = glitch_free_parts(clip.skeleton, clip.motion);
    if (const std::string glitches = clip_glitches_description(clip, found); !glitches.empty()) {
      spdlog::warn("{}: {}; converted whole", input, glitches);
    }
  }
  // What looks wrong with it as read (its unit, floor, feet or clock), as info says it: judged at
  // the rate read, on the feet --feet names or found by name (none found: not judged by them).
  auto judged = judge_clip_as_read(clip.skeleton, clip.motion, {}, clip.motion.fps, loaded->format,
                                   options.load.settings().foot_names);
  if (!judged) return Error{input, 0, judged.error().message};  // feet named but not there
  if (!judged->doubts.empty()) spdlog::warn("{}", clip_doubt_line(input, judged->doubts));
  if (options.fps > 0.0) {
    auto resampled = resample(clip.motion, options.fps);
    if (!resampled) return Error{input, 0, resampled.error().message};
    clip.motion = std::move(*resampled);
  }
  if (options.mirror) {
    auto map = mirror_map(clip.skeleton);
    if (!map) return Error{input, 0, "cannot be mirrored: " + map.error().message};
    clip.motion = mirror_motion(clip.skeleton, *map, clip.motion);
  }
  return std::move(clip);
}

// Fails unless every output is a scene file, .glb, .gltf or .fbx (several clips make an animation
// set).
Status check_set_outputs(const ConvertOptions& options, size_t clips, const std::string& what) {
  if (clips < 2) return Ok{};
  for (const std::string& output : options.outputs) {
    if (!is_scene_extension(lower_extension(output))) {
      return Error{output, 0, fmt::format("{} {} clips, and several clips go into a {} only (an animation each); "
                                          "convert them one at a time for .bvh or .json",
                                          what, clips, kSceneFormats)};
    }
  }
  return Ok{};
}

// One clip to each of `outputs`, with its foot contacts for a JSON (none, with a warning, when
// its feet are not found).
int write_clip(const ConvertOptions& options, const std::vector<std::string>& outputs, const std::string& source,
               const Skeleton& skeleton, const Motion& motion, const FootJointNames& feet) {
  std::optional<ClipContacts> contacts;
  const bool any_json = std::any_of(outputs.begin(), outputs.end(), [](const std::string& path) {
    return lower_extension(path) == ".json";
  });
  if (any_json || !feet.empty()) {
    std::string why;
    auto found = clip_contacts(skeleton, motion, feet, why);
    if (!found) return fail(Error{source, 0, found.error().message});
    contacts = std::move(*found);
    if (!contacts) spdlog::warn("{}: no foot contacts in the JSON: {} (name the feet with --feet)", source, why);
  }
  const PositionsJsonContacts json_contacts{contacts ? contacts->feet : FootJoints{},
                                            contacts ? std::span<const ContactMask>(contacts->masks)
                                                     : std::span<const ContactMask>()};
  // Where the clip's skeleton faces, for its root-motion joint.
  MotionFileSettings settings = options.output.settings(
      options.output.root_motion ? learn_clip_forward_axis(skeleton, motion, feet) : Vec3::UnitZ());
  settings.keep_root_order = true;  // a clip written back as it was read, its root's rotation order too
  // Every output made before any is written: one that cannot be (a root too far for glTF's
  // floats) leaves no other written.
  std::vector<std::string> made;
  for (const std::string& output : outputs) {
    auto bytes = motion_file_bytes(output, skeleton, motion, settings, contacts ? &json_contacts : nullptr);
    if (!bytes) return fail(bytes.error());
    made.push_back(std::move(*bytes));
  }
  for (size_t i = 0; i < outputs.size(); ++i) {
    if (auto s = write_file_atomic(outputs[i], made[i]); !s) return fail(s.error());
  }
  return 0;
}

// A library: every clip as `build` reads it (whole, not played on past a loop's end), on one of
// its skeletons as synthesis plays them, an animation each named as the clip.
int convert_library(const ConvertOptions& options, const ClipLoadSettings& load) {
  DatabaseSettings settings = database_settings_reading_as(load);
  if (options.fps > 0.0) settings.fps = options.fps;
  settings.prefer_manifest_fps = options.fps <= 0.0;
  settings.cmu_tags = false;  // no tags go into the file
  settings.loops = false;
  // The clips as they are, or their mirror images (after them, the ones written).
  settings.mirror = options.mirror ? DatabaseSettings::Mirroring::kAlways : DatabaseSettings::Mirroring::kOff;
  settings.progress_bar = true;  // a terminal's stderr only
  settings.outputs = options.outputs;
  DatabaseLoadNotes notes;
  auto loaded = load_database(options.inputs, settings, &notes);
  if (!loaded) return fail(loaded.error());
  const MotionDatabase& db = *loaded;
  if (options.mirror && !notes.unmirrored.empty()) {
    const auto& u = notes.unmirrored.front();
    return fail(Error{u.skeleton, 0, "cannot be mirrored: " + u.reason});
  }
  report_units(notes, false);
  for (const std::string& line : load_warnings(notes)) spdlog::warn("{}", line);
  // The clips written: all of them, or with --mirror their mirror images alone (after them), as a
  // file is written mirrored.
  std::vector<int> written;
  for (size_t c = options.mirror ? db.clips.size() - notes.mirrored.size() : 0; c < db.clips.size(); ++c) {
    written.push_back(static_cast<int>(c));
  }
  if (auto s = check_set_outputs(options, written.size(), "the library holds"); !s) return fail(s.error());
  const int target = options.skeleton >= 0 ? options.skeleton : db.clips.front().skeleton;
  if (target >= static_cast<int>(db.skeletons.size())) {
    return fail(Error{"", 0, fmt::format("--skeleton {}: the library has {} skeleton(s)", target, db.skeletons.size())});
  }
  std::vector<Motion> played;
  for (const int c : written) {
    auto motion = clip_on_skeleton(db, c, target);
    if (!motion) return fail(Error{db.clips[static_cast<size_t>(c)].source, 0, motion.error().message});
    played.push_back(std::move(*motion));
  }
  // A library of one clip (a manifest's frame range) goes into BVH and JSON too (a scene file
  // below, its animation named as the clip).
  std::vector<std::string> clip_outputs, set_outputs;
  for (const std::string& output : options.outputs) {
    const std::string ext = lower_extension(output);
    (is_scene_extension(ext) ? set_outputs : clip_outputs).push_back(output);
  }
  if (!clip_outputs.empty()) {
    const int status = write_clip(options, clip_outputs, db.clips[static_cast<size_t>(written.front())].source,
                                  db.skeletons[target], played.front(), db.foot_names);
    if (status != 0) return status;
  }
  const Vec3 forward_axis =
      options.output.root_motion ? learn_forward_axis(db, target, learn_travel_axes(db)[target]) : Vec3::UnitZ();
  std::vector<NamedMotion> motions;
  for (size_t i = 0; i < written.size(); ++i) {
    const DatabaseClip& clip = db.clips[static_cast<size_t>(written[i])];
    motions.push_back({clip.source, clip.name, &db.skeletons[target], &played[i], forward_axis});
  }
  for (const std::string& output : set_outputs) {
    if (auto s = write_animation_set(output, motions, options.output.settings()); !s) return fail(s.error());
  }
  if (db.skeletons.size() > 1) {
    spdlog::info("{} clips of {} skeletons played on {}'s (--skeleton {})", db.clips.size(), db.skeletons.size(),
                 db.skeleton_names[target], target);
  }
  return 0;
}

// Several clips of one rig: one .glb, .gltf or .fbx, an animation each, named as its file.
int convert_animation_set(const ConvertOptions& options, const ClipLoadSettings& load) {
  if (auto s = check_set_outputs(options, options.inputs.size(), "the inputs are"); !s) return fail(s.error());
  ClipLoader loader(load);
  std::vector<Clip> clips;
  for (const std::string& input : options.inputs) {
    auto clip = read_clip(options, loader, input);
    if (!clip) return fail(clip.error());  // feet named must be there (read_clip), as for one clip
    clips.push_back(std::move(*clip));
  }
  std::vector<NamedMotion> motions;
  for (size_t i = 0; i < clips.size(); ++i) {
    const Clip& clip = clips[i];
    const std::string stem = std::filesystem::path(options.inputs[i]).stem().string();
    motions.push_back({options.inputs[i], options.mirror ? stem + "_mirrored" : stem, &clip.skeleton,
                       &clip.motion,
                       options.output.root_motion ? learn_clip_forward_axis(clip.skeleton, clip.motion, load.foot_names)
                                                  : Vec3::UnitZ()});
  }
  for (const std::string& output : options.outputs) {
    if (auto s = write_animation_set(output, motions, options.output.settings()); !s) return fail(s.error());
  }
  return 0;
}

int run_convert(const ConvertOptions& options) {
  for (const std::string& output : options.outputs) {
    if (auto s = check_motion_output(output); !s) return fail(s.error());
  }
  if (auto s = check_outputs(options.outputs, options.inputs); !s) return fail(s.error());
  if (auto s = options.output.settings().validate(); !s) return fail_usage(s.error());
  const ClipLoadSettings load = options.load.settings();
  if (is_library(options.inputs)) {
    if (options.animation) return fail(Error{"", 0, "--animation applies to glTF and FBX files, not to a library"});
    return convert_library(options, load);
  }
  if (options.skeleton >= 0) return fail(Error{"", 0, "--skeleton applies to a library (a folder or a manifest)"});
  if (options.inputs.size() > 1) return convert_animation_set(options, load);
  const std::string& input = options.inputs.front();
  ClipLoader loader(load);
  auto loaded = read_clip(options, loader, input);
  if (!loaded) return fail(loaded.error());
  return write_clip(options, options.outputs, input, loaded->skeleton, loaded->motion, load.foot_names);
}

}  // namespace

Command add_convert_command(CLI::App& app) {
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* sub = app.add_subcommand(
      "convert", "Convert an AMC, BVH, glTF or FBX clip to BVH (metres), to binary glTF (.glb: the skeleton, its animation and "
                 "a stick figure skinned to it, in metres; .gltf: the same as one JSON file), to binary FBX (.fbx: the same, in "
                 "centimetres, for Maya, MotionBuilder, Unity, Unreal, Blender) or to JSON world positions "
                 "({\"fps\", \"joints\": [{\"name\", \"parent\"}], \"positions\": [frame][joint][x,y,z], "
                 "\"contacts\": {\"joints\": [the foot joints], \"planted\": [frame][foot joint] 0 or 1}}). Several "
                 "clips of one rig make one .glb, .gltf or .fbx, an animation each.");
  sub->add_option("IN", options->inputs,
                  "Input clip (.amc, .bvh, or .glb/.gltf/.fbx: an animation of it); several clips of one rig go into one .glb, .gltf or .fbx, an animation each "
                  "named as its file (a character's animation set, as game engines import it); a library (folders, .toml "
                  "manifests) goes into one .glb, .gltf or .fbx as build reads it (at 30 fps unless --fps or its manifest says), "
                  "every clip on one of its skeletons; a library of one clip (a manifest's frame range) into any "
                  "format")
      ->required()
      ->check(CLI::ExistingPath);
  sub->add_option("--animation", options->animation,
                  "The animation of a glTF or FBX input to read (default: its first; a library reads them all)");
  sub->add_option("--skeleton", options->skeleton,
                  "A library's skeleton to play every clip on, as synthesis plays them: rotations kept, translations "
                  "scaled by the legs' lengths (default: the first clip's)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("-o,--output", options->outputs,
                  "Output file, .bvh, .glb (binary glTF 2.0), .gltf (the same as JSON, one file), .fbx (binary FBX 7.4) or "
                  ".json; repeat -o for several (read once)")
      ->required()
      ->allow_extra_args(false);  // one file each: inputs may follow it
  sub->add_option("--fps", options->fps, "Resample to this frame rate (slerp rotations, lerp translations)")
      ->check(CLI::Range(0.01, 10000.0));
  sub->add_flag("--mirror", options->mirror,
                "Write the clips' mirror images, left to right (a walk turning left turns right), in place of the "
                "clips; several clips' or a library's animations are named NAME_mirrored. Joints pair by their names "
                "(lfemur and rfemur, LeftUpLeg and RightUpLeg, Hip_L and Hip_R); a rig that cannot be mirrored stops "
                "it");
  options->output.add_to(*sub);
  options->load.add_to(*sub);
  return {sub, [options] { return run_convert(*options); }};
}

}  // namespace mg::cli
