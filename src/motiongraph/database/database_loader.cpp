#include "motiongraph/database/database_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>
#include <tuple>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "motiongraph/core/default_window.h"
#include "motiongraph/core/file_extension.h"
#include "motiongraph/core/progress.h"
#include "motiongraph/core/stop.h"
#include "motiongraph/core/unique_name.h"
#include "motiongraph/database/cmu_tags.h"
#include "motiongraph/database/database_doubts.h"
#include "motiongraph/database/folder_tree.h"
#include "motiongraph/database/travel_tags.h"
#include "motiongraph/database/database_contacts.h"
#include "motiongraph/database/manifest.h"
#include "motiongraph/database/shipped_cmu_index.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/capture_glitches.h"
#include "motiongraph/motion/clip_doubts.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/common_joints.h"
#include "motiongraph/motion/mirror.h"
#include "motiongraph/motion/resample.h"
#include "motiongraph/motion/rig_matching.h"
#include "motiongraph/motion/up_axis.h"

namespace mg {

namespace fs = std::filesystem;

namespace {

// One clip to read, with everything the inputs said about it.
struct ClipSpec {
  std::string path;
  std::string name;
  std::string cmu_name;            // the file's stem, the key into CMU's index
  ClipLoadSettings load;
  std::optional<std::string> animation;  // of a glTF or FBX file
  int animation_line = 0;                // of the manifest's `animation`
  std::optional<int> first_frame;  // file numbering, from 1
  std::optional<int> last_frame;
  bool gives_tags = false;         // the manifest decides the tags (no CMU lookup)
  std::vector<std::string> tags;
  std::vector<ManifestRange> ranges;
  std::string manifest;            // empty when the clip was not named by a manifest
  bool in_folder = false;          // found in a folder given (not named itself): left out when its rig cannot join
  std::string folder;              // its folder below the one given ('/' between; "" at its top)
  int line = 0;                    // of its [[clip]]
  int frames_line = 0;

  // Where to point an error about this clip: its manifest line, or the file itself.
  Error error(std::string message) const {
    if (manifest.empty()) return Error{path, 0, std::move(message)};
    return Error{manifest, line, fmt::format("clip {}: {}", path, message)};
  }
};

ClipLoadSettings default_load_settings(const DatabaseSettings& settings) {
  ClipLoadSettings load;
  load.asf_path = settings.asf_path;
  load.bvh_metres_per_unit = settings.bvh_metres_per_unit;
  load.up_axis = settings.up_axis;
  load.input_fps = settings.input_fps;
  load.keep_rest_frames = settings.keep_rest_frames;
  load.travel = settings.travel;
  return load;
}

ClipSpec spec_for_file(const fs::path& path, const ClipLoadSettings& load) {
  ClipSpec spec;
  spec.path = path.string();
  spec.name = path.stem().string();
  spec.cmu_name = spec.name;
  spec.load = load;
  return spec;
}

// The clips of a file: one, or one per animation of a glTF or FBX file (named FILE:ANIMATION when
// it has several, as the clip loader names them). Such a file without animation (a character's
// model) is passed over in a folder, an error when given itself.
Status add_file_specs(const fs::path& path, const ClipLoadSettings& load, std::vector<ClipSpec>& specs,
                      bool in_folder) {
  if (!is_scene_file(path.string())) {
    specs.push_back(spec_for_file(path, load));
    return Ok{};
  }
  auto names = animation_names(path.string());
  if (!names) return names.error();
  if (names->empty() && !in_folder) {
    return Error{path.string(), 0, fmt::format("the {} file has no animation that moves a skeleton",
                                               is_fbx_file(path.string()) ? "FBX" : "glTF")};
  }
  for (const std::string& animation : *names) {
    ClipSpec spec = spec_for_file(path, load);
    spec.animation = animation;
    if (names->size() > 1) {
      spec.name = fmt::format("{}:{}", spec.name, animation);
      spec.cmu_name = animation;  // an animation set of CMU's clips keeps their tags
    }
    specs.push_back(std::move(spec));
  }
  return Ok{};
}

// The clips of a folder and the folders in it (database/folder_tree.h). An AMC file's skeleton
// is the only .asf in its folder; of several, the one CMU's naming gives it (16_01.amc: 16.asf).
Result<std::string> asf_in_folder(const TreeFolder& folder, const fs::path& amc) {
  const std::vector<fs::path>& asfs = folder.asfs;
  if (auto asf = asf_of_amc(asfs, amc)) return asf->string();
  if (asfs.empty()) return Error{folder.path.string(), 0, "the folder holds AMC files but no .asf skeleton"};
  return Error{folder.path.string(), 0,
               fmt::format("the folder holds {} .asf files and none is named as {}'s subject (as 16.asf for "
                           "16_01.amc); name the clips and their skeletons in a manifest (docs/manifest.md)",
                           asfs.size(), amc.filename().string())};
}

Status expand_folder(const std::string& input, const DatabaseSettings& settings, std::vector<ClipSpec>& specs,
                     std::vector<std::string>& remarks) {
  auto tree = read_folder_tree(input);
  if (!tree) return tree.error();
  remarks.insert(remarks.end(), tree->left_out.begin(), tree->left_out.end());
  const size_t before = specs.size();
  for (const TreeFolder& folder : tree->folders) {
    for (const TreeClipFile& clip : folder.clips) {
      ClipLoadSettings load = default_load_settings(settings);
      if (lower_extension(clip.file.string()) == ".amc") {
        auto asf = asf_in_folder(folder, clip.file);
        if (!asf) return asf.error();
        load.asf_path = *asf;
      }
      const size_t first = specs.size();
      if (auto s = add_file_specs(clip.file, load, specs, true); !s) return s;
      // A name taken by a file of another folder: this one's is the folder's and the file's.
      const std::string stem = clip.file.stem().string();
      for (size_t i = first; i < specs.size(); ++i) {
        specs[i].name = clip.name + specs[i].name.substr(stem.size());
        specs[i].in_folder = true;
        specs[i].folder = folder.relative;
      }
    }
  }
  if (specs.size() == before) return Error{input, 0, "the folder holds no clip (its glTF and FBX files have no animation)"};
  return Ok{};
}

// What the manifests say of the whole database, and which manifest said it first.
struct ManifestWide {
  std::optional<double> fps;
  std::string fps_source;
  std::optional<FootJointNames> feet;
  std::string feet_source;
  int feet_line = 0;
};

Status expand_manifest(const std::string& input, const DatabaseSettings& settings, std::vector<ClipSpec>& specs,
                       ManifestWide& wide) {
  auto text = read_text_file(input);
  if (!text) return text.error();
  auto manifest = parse_manifest(*text, input);
  if (!manifest) return manifest.error();
  if (manifest->fps && settings.prefer_manifest_fps) {
    if (wide.fps && *wide.fps != *manifest->fps) {
      return Error{input, manifest->fps_line,
                   fmt::format("fps {} differs from the fps {} of {}; one database has one frame rate",
                               *manifest->fps, *wide.fps, wide.fps_source)};
    }
    wide.fps = manifest->fps;
    wide.fps_source = input;
  }
  if (manifest->feet && settings.foot_names.empty()) {
    if (wide.feet && !(*wide.feet == *manifest->feet)) {
      return Error{input, manifest->feet_line,
                   fmt::format("[feet] names other joints than the [feet] of {}; one database has one set of feet",
                               wide.feet_source)};
    }
    wide.feet = manifest->feet;
    wide.feet_source = input;
    wide.feet_line = manifest->feet_line;
  }
  const fs::path folder = fs::path(input).parent_path();
  const auto resolve = [&](const std::string& path) { return (folder / path).lexically_normal().string(); };
  for (const ManifestClip& clip : manifest->clips) {
    ClipSpec spec;
    spec.path = resolve(clip.file);
    spec.cmu_name = fs::path(clip.file).stem().string();
    spec.name = clip.name ? *clip.name : spec.cmu_name;
    if (clip.animation) {
      // An animation of a glTF or FBX file: named and looked up in CMU's index as the animation.
      spec.animation = clip.animation;
      if (!clip.name) spec.name = fmt::format("{}:{}", spec.cmu_name, *clip.animation);
      spec.cmu_name = *clip.animation;
    }
    spec.load = default_load_settings(settings);
    if (clip.skeleton || manifest->skeleton) {
      spec.load.asf_path = resolve(clip.skeleton ? *clip.skeleton : *manifest->skeleton);
    }
    // The clip's own value, else the manifest's default, else the settings'.
    if (auto scale = clip.bvh_scale ? clip.bvh_scale : manifest->bvh_scale) spec.load.bvh_metres_per_unit = *scale;
    if (auto up = clip.up_axis ? clip.up_axis : manifest->up_axis) spec.load.up_axis = *up;
    if (auto fps = clip.input_fps ? clip.input_fps : manifest->input_fps) spec.load.input_fps = *fps;
    if (auto keep = clip.keep_rest_frames ? clip.keep_rest_frames : manifest->keep_rest_frames) {
      spec.load.keep_rest_frames = *keep;
    }
    if (auto travel = clip.travel ? clip.travel : manifest->travel) spec.load.travel = *travel;
    spec.first_frame = clip.first_frame;
    spec.last_frame = clip.last_frame;
    spec.gives_tags = clip.gives_tags();
    if (clip.tags) spec.tags = *clip.tags;
    spec.ranges = clip.ranges;
    spec.manifest = input;
    spec.line = clip.line;
    spec.frames_line = clip.frames_line;
    spec.animation_line = clip.animation_line;
    std::error_code ec;
    if (!fs::is_regular_file(spec.path, ec)) {
      return Error{input, clip.file_line,
                   fmt::format("clip file {} not found (paths are relative to the manifest's folder)", spec.path)};
    }
    const bool is_amc = lower_extension(spec.path) == ".amc";
    if (is_amc && (clip.skeleton || manifest->skeleton) && !fs::is_regular_file(*spec.load.asf_path, ec)) {
      return Error{input, clip.skeleton ? clip.skeleton_line : manifest->skeleton_line,
                   fmt::format("skeleton file {} not found (paths are relative to the manifest's folder)",
                               *spec.load.asf_path)};
    }
    specs.push_back(std::move(spec));
  }
  return Ok{};
}

// The first difference between two skeletons' joint lists, or nullopt when they match.
std::optional<std::string> topology_difference(const Skeleton& expected, const Skeleton& found) {
  const int common = std::min(expected.joint_count(), found.joint_count());
  const auto parent_name = [](const Skeleton& s, int j) {
    return s.parent(j) < 0 ? std::string("none") : fmt::format("'{}'", s.joint(s.parent(j)).name);
  };
  for (int j = 0; j < common; ++j) {
    if (expected.joint(j).name != found.joint(j).name) {
      return fmt::format("joint {} is '{}' there, '{}' here", j, expected.joint(j).name, found.joint(j).name);
    }
    if (expected.parent(j) != found.parent(j)) {
      return fmt::format("joint {} '{}' has parent {} there, {} here", j, found.joint(j).name,
                         parent_name(expected, j), parent_name(found, j));
    }
  }
  if (expected.joint_count() != found.joint_count()) {
    return fmt::format("{} joints there, {} here", expected.joint_count(), found.joint_count());
  }
  return std::nullopt;
}

// Output frames [first, last] whose times fall inside [start_s, end_s] (seconds from the clip's
// first frame); the nearest frame when none does (a range shorter than one output frame).
std::pair<int, int> output_frames(double start_s, double end_s, double fps, int frame_count) {
  int first = static_cast<int>(std::ceil(start_s * fps - 1e-9));
  int last = static_cast<int>(std::floor(end_s * fps + 1e-9));
  first = std::clamp(first, 0, frame_count - 1);
  last = std::clamp(last, 0, frame_count - 1);
  if (first > last) {
    first = last = std::clamp(static_cast<int>(std::lround(0.5 * (start_s + end_s) * fps)), 0, frame_count - 1);
  }
  return {first, last};
}

using LoaderKey = std::tuple<std::string, double, int, double, bool, int>;

class Loaders {
 public:
  ClipLoader& for_settings(const ClipLoadSettings& load) {
    const int up = load.up_axis ? static_cast<int>(*load.up_axis) : -1;
    LoaderKey key{load.asf_path.value_or(""), load.bvh_metres_per_unit.value_or(0.0), up, load.input_fps,
                  load.keep_rest_frames, static_cast<int>(load.travel)};
    auto it = loaders_.find(key);
    if (it == loaders_.end()) it = loaders_.emplace(key, std::make_unique<ClipLoader>(load)).first;
    return *it->second;
  }

 private:
  std::map<LoaderKey, std::unique_ptr<ClipLoader>> loaders_;
};

Status add_tag_range(MotionDatabase& db, const std::string& tag, int first_frame, int frame_count,
                     const ClipSpec& spec) {
  const int index = db.tag_index(tag);
  if (index < 0) return spec.error(fmt::format("tag '{}' would be the 65th; a database holds at most 64 tags", tag));
  db.tag_ranges.push_back(TagRange{index, first_frame, frame_count});
  return Ok{};
}

// A clip tagged by its CMU description, or by its name: the tags it gives.
struct DescribedClip {
  size_t spec_index = 0;
  size_t clip = 0;
  std::vector<std::string> tags;
};

// Its tags on the database: walk and run on the frames where its root travels, stop where it
// halts and slows into a halt (travel_tags.h), the others on all its frames.
Status tag_described_clip(MotionDatabase& db, const DescribedClip& d, const ClipSpec& spec,
                          const TravelTagSettings& settings, DatabaseLoadNotes* notes) {
  const DatabaseClip& clip = db.clips[d.clip];
  std::optional<std::vector<FrameSpan>> spans;  // the clip's travelling spans, found once
  std::optional<PaceSpans> paces;               // ... split by pace, for a clip called walk and run
  const bool both_paces = std::find(d.tags.begin(), d.tags.end(), "walk") != d.tags.end() &&
                          std::find(d.tags.begin(), d.tags.end(), "run") != d.tags.end() &&
                          settings.min_speed_mps > 0.0;
  // The root's translation (a root without one stays where it is: it travels nowhere).
  auto roots = [&] {
    const int slot = db.skeletons[static_cast<size_t>(clip.skeleton)].translation_slot(0);
    std::vector<Vec3> at(static_cast<size_t>(clip.frame_count), Vec3::Zero());
    for (int f = 0; slot >= 0 && f < clip.frame_count; ++f) {
      at[static_cast<size_t>(f)] = clip.motion.translations(f)[static_cast<size_t>(slot)];
    }
    return at;
  };
  for (const std::string& tag : d.tags) {
    if (is_stop_tag(tag)) {
      for (const FrameSpan& span : stopping_spans(roots(), db.fps, settings)) {
        if (auto s = add_tag_range(db, tag, clip.first_frame + span.first, span.count, spec); !s) return s;
      }
      continue;
    }
    if (!is_locomotion_tag(tag)) {
      if (auto s = add_tag_range(db, tag, clip.first_frame, clip.frame_count, spec); !s) return s;
      continue;
    }
    if (!spans) spans = travelling_spans(roots(), db.fps, settings);
    // Called both walk and run ("Walk to Run"): each where the pace says.
    if (!paces && both_paces) {
      const double run_mps = run_pace_mps(db.skeletons[static_cast<size_t>(clip.skeleton)].leg_length_m());
      paces = pace_spans(roots(), db.fps, settings, run_mps);
    }
    // (A part of one pace, cut from such a clip at a glitch, is a walk or a run, not both.)
    for (const FrameSpan& span : !paces ? *spans : tag == "run" ? paces->running : paces->walking) {
      if (auto s = add_tag_range(db, tag, clip.first_frame + span.first, span.count, spec); !s) return s;
    }
    // Left off where the root stands (not where the clip goes at the other pace).
    int travelling = 0;
    for (const FrameSpan& span : *spans) travelling += span.count;
    if (travelling < clip.frame_count && notes != nullptr) {
      notes->standing_tags.push_back({clip.name, tag, travelling, clip.frame_count});
    }
  }
  return Ok{};
}

}  // namespace

std::optional<DatabaseSettings::Mirroring> parse_mirroring(std::string_view text) {
  if (text == "auto") return DatabaseSettings::Mirroring::kWhenLopsided;
  if (text == "on") return DatabaseSettings::Mirroring::kAlways;
  if (text == "off") return DatabaseSettings::Mirroring::kOff;
  return std::nullopt;
}

const char* mirroring_name(DatabaseSettings::Mirroring mirroring) {
  switch (mirroring) {
    case DatabaseSettings::Mirroring::kOff: return "off";
    case DatabaseSettings::Mirroring::kAlways: return "on";
    case DatabaseSettings::Mirroring::kWhenLopsided: break;
  }
  return "auto";
}

DatabaseSettings database_settings_reading_as(const ClipLoadSettings& load) {
  DatabaseSettings settings;
  settings.asf_path = load.asf_path;
  settings.bvh_metres_per_unit = load.bvh_metres_per_unit;
  settings.up_axis = load.up_axis;
  settings.input_fps = load.input_fps;
  settings.keep_rest_frames = load.keep_rest_frames;
  settings.travel = load.travel;
  settings.foot_names = load.foot_names;
  return settings;
}

Status DatabaseSettings::validate() const {
  // build --fps's range: under a frame a second no window of frames is motion, over 1000 no capture.
  if (!(fps >= 1.0 && fps <= 1000.0)) return Error{"", 0, fmt::format("fps must be 1 to 1000, not {}", fps)};
  if (bvh_metres_per_unit && (!(*bvh_metres_per_unit > 0.0) || !std::isfinite(*bvh_metres_per_unit))) {
    return Error{"", 0, fmt::format("bvh_metres_per_unit (--scale) must be positive, not {}", *bvh_metres_per_unit)};
  }
  if (auto s = foot_names.validate(); !s) return s.error();
  if (!(input_fps >= 0.0) || !std::isfinite(input_fps)) {
    return Error{"", 0, fmt::format("input_fps must be positive (or 0: the files' own), not {}", input_fps)};
  }
  if (auto s = travel_tags.validate(); !s) return s.error();
  if (loop_overlap_frames < 0 || loop_overlap_frames > 10001) {
    return Error{"", 0, fmt::format("loop_overlap_frames must be 0 (automatic) to 10001, not {}", loop_overlap_frames)};
  }
  if (!(max_lopsided_mirror_s >= 0.0)) {
    return Error{"", 0, fmt::format("max_lopsided_mirror_s must be >= 0, not {}", max_lopsided_mirror_s)};
  }
  return Ok{};
}

int DatabaseSettings::loop_frames_at(double database_fps) const {
  if (loop_overlap_frames > 0) return loop_overlap_frames;
  return default_window_frames(database_fps) + 1;
}

namespace {

// cmu-mocap-index.tsv beside, or up to two folders above, the first input (a folder, or a
// file's folder) that has one; "" when none has.
std::string find_cmu_index(std::span<const std::string> inputs) {
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

// Whether a skeleton takes the first's names: it is the first's hierarchy under other names
// (motion/rig_matching.h), not all its joints bearing names the first has (in another order:
// matched by name, not by place).
bool takes_names_of(const Skeleton& skeleton, const Skeleton& first) {
  bool all_known = true;
  for (int j = 0; all_known && j < skeleton.joint_count(); ++j) {
    all_known = first.find(skeleton.joint(j).name).has_value();
  }
  return !all_known && !hierarchy_mismatch(first, skeleton);
}

// The clip's joints renamed as the database's first skeleton's (read in full) when it takes its
// names: the pairs renamed (its name, the first's); none otherwise (named as the first's, or other
// joints: topology_difference tells that).
std::vector<std::pair<std::string, std::string>> rename_as_first(Clip& clip, const Skeleton& first) {
  std::vector<std::pair<std::string, std::string>> renamed;
  const Skeleton& skeleton = clip.skeleton;
  if (!takes_names_of(skeleton, first)) return renamed;
  for (int j = 0; j < first.joint_count(); ++j) {
    if (skeleton.joint(j).name != first.joint(j).name && !first.joint(j).end_site) {
      renamed.emplace_back(skeleton.joint(j).name, first.joint(j).name);
    }
  }
  clip = renamed_as(clip, first);
  return renamed;
}

// The notes' entry of a skeleton file read as the first file's rig, made when missing.
DatabaseLoadNotes::MatchedRig& rig_note(DatabaseLoadNotes& notes, const std::string& file) {
  for (DatabaseLoadNotes::MatchedRig& rig : notes.matched_rigs) {
    if (rig.file == file) return rig;
  }
  notes.matched_rigs.push_back({file, {}, std::nullopt});
  return notes.matched_rigs.back();
}

// Every clip of a skeleton whose bones rest further than kRestPoseRetargetDeg from the first
// skeleton's re-expressed on the first's rest pose (motion/rig_matching.h), once the joints are
// settled (the same joints in every skeleton).
void rest_as_first(MotionDatabase& db, DatabaseLoadNotes* notes) {
  for (size_t s = 1; s < db.skeletons.size(); ++s) {
    if (topology_difference(db.skeletons.front(), db.skeletons[s])) continue;
    const RestPoseDifference difference = rest_pose_difference(db.skeletons.front(), db.skeletons[s]);
    if (difference.angle_deg <= kRestPoseRetargetDeg) continue;
    std::optional<Skeleton> rested;
    for (DatabaseClip& clip : db.clips) {
      if (clip.skeleton != static_cast<int>(s)) continue;
      Clip whole;
      whole.skeleton = db.skeletons[s];
      whole.motion = std::move(clip.motion);
      Clip out = on_rest_pose_of(whole, db.skeletons.front());
      clip.motion = std::move(out.motion);
      rested = std::move(out.skeleton);
    }
    if (rested) db.skeletons[s] = std::move(*rested);
    if (notes != nullptr) rig_note(*notes, db.skeleton_names[s]).rest_pose = difference;
  }
}

// Every skeleton of `db` whose root is not `root` read from that joint down (reroot_at), with
// its clips; a note for each.
Status reroot_database(MotionDatabase& db, const std::string& root, std::vector<DatabaseLoadNotes::Rerooted>& notes) {
  for (size_t s = 0; s < db.skeletons.size(); ++s) {
    const Skeleton skeleton = db.skeletons[s];
    if (skeleton.joint(0).name == root) continue;
    // The joints above the root, root first: kept to be written back where another skeleton of
    // the rig has them as its static ancestors (folded at import: trajectory_joint.h).
    std::vector<std::string> chain;
    for (int a = skeleton.parent(*skeleton.find(root)); a >= 0; a = skeleton.parent(a)) {
      chain.insert(chain.begin(), skeleton.joint(a).name);
    }
    const auto above_as = std::find_if(db.skeletons.begin(), db.skeletons.end(), [&](const Skeleton& other) {
      if (other.joint(0).name != root || other.static_ancestors().size() != chain.size()) return false;
      for (size_t i = 0; i < chain.size(); ++i) {
        if (other.static_ancestors()[i].name != chain[i]) return false;
      }
      return true;
    });
    // A copy: db.skeletons changes below.
    const std::optional<Skeleton> kept_as =
        above_as == db.skeletons.end() ? std::nullopt : std::optional<Skeleton>(*above_as);
    std::optional<Skeleton> rerooted;
    std::vector<std::string> dropped;
    for (DatabaseClip& clip : db.clips) {
      if (clip.skeleton != static_cast<int>(s)) continue;
      Clip whole;
      whole.name = clip.name;
      whole.skeleton = skeleton;
      whole.motion = std::move(clip.motion);
      auto out = reroot_at(whole, root, kept_as ? &*kept_as : nullptr);
      if (!out) return Error{clip.source, 0, out.error().message};
      clip.motion = std::move(out->motion);
      if (!rerooted) {
        rerooted = std::move(out->skeleton);
        dropped = std::move(out->dropped_at_fold);  // those hanging off the joints above (none before)
      }
    }
    if (!rerooted) continue;
    notes.push_back(DatabaseLoadNotes::Rerooted{db.skeleton_names[s], root, chain, std::move(dropped)});
    db.skeletons[s] = std::move(*rerooted);
  }
  return Ok{};
}

// The first root name that is not the first skeleton's.
std::string other_root(std::span<const Skeleton> skeletons) {
  for (const Skeleton& skeleton : skeletons) {
    if (skeleton.joint(0).name != skeletons.front().joint(0).name) return skeleton.joint(0).name;
  }
  return skeletons.front().joint(0).name;
}

// Why the joints every skeleton has cannot hold the library (nullopt when they can): they must
// be at least two thirds of the smallest skeleton's joints, both ankles among them.
std::optional<std::string> common_joints_fall_short(std::span<const Skeleton> skeletons,
                                                    const FootJointNames& foot_names,
                                                    const std::vector<std::string>& common) {
  size_t smallest = static_cast<size_t>(skeletons.front().joint_count());
  for (const Skeleton& skeleton : skeletons) smallest = std::min(smallest, static_cast<size_t>(skeleton.joint_count()));
  if (common.empty()) {
    return fmt::format("they share no joint: joints match by name and their parent's name from the root down, and the "
                       "roots are '{}' and '{}'",
                       skeletons.front().joint(0).name, other_root(skeletons));
  }
  if (3 * common.size() < 2 * smallest) {
    return fmt::format("they share {} joint{} (by name, with the same parent's name), fewer than two thirds of the "
                       "smallest skeleton's {}",
                       common.size(), common.size() == 1 ? "" : "s", smallest);
  }
  auto feet = find_foot_joints(skeletons.front(), foot_names);
  if (!feet) return std::nullopt;  // the feet are missing anyway (a warning later), not for want of joints
  for (const int ankle : {feet->left.ankle, feet->right.ankle}) {
    const std::string& name = skeletons.front().joint(ankle).name;
    if (std::find(common.begin(), common.end(), name) == common.end()) {
      return fmt::format("the ankle '{}' is not among the {} joints they share", name, common.size());
    }
  }
  return std::nullopt;
}

// Whether skeletons as read, in the library's order, are read together as loading reads them:
// each of the first's hierarchy under other names on the first's names (rename_as_first), read
// from a root every one has when their roots differ (reroot_database), then enough joints shared.
bool read_together(std::span<const Skeleton* const> in_order, const FootJointNames& foot_names) {
  std::vector<Skeleton> as_library;
  const Skeleton& first = *in_order.front();
  for (const Skeleton* skeleton : in_order) as_library.push_back(takes_names_of(*skeleton, first) ? first : *skeleton);
  std::vector<std::string> common = common_joints(as_library);
  if (common.empty()) {  // roots that differ: read from one every skeleton has, as 3b does
    const std::string root = shared_root(as_library);
    if (root.empty()) return false;
    for (Skeleton& skeleton : as_library) {
      if (skeleton.joint(0).name == root) continue;
      Clip pose;
      pose.skeleton = skeleton;
      pose.motion = Motion(skeleton, 0, 30.0);
      auto rerooted = reroot_at(pose, root);
      if (!rerooted) return false;
      skeleton = std::move(rerooted->skeleton);
    }
    common = common_joints(as_library);
  }
  return !common_joints_fall_short(as_library, foot_names, common);
}

// The rigs of the library that can be read together, of the most frames, given the skeletons as
// read (before any took the first's names), in the library's order; one flag a skeleton.
// Skeletons of the same joints (names and parents) are one rig. Each rig seeds a family, taking
// the others by frames when the family, read in the library's order, still reads together.
std::vector<bool> largest_rig_family(const MotionDatabase& db, const std::vector<Skeleton>& read_skeletons) {
  // The rigs: their joint names and parents' names, their first skeleton, their frames.
  std::map<std::vector<std::pair<std::string, std::string>>, size_t> rig_of;
  std::vector<size_t> rig_skeleton;  // the first skeleton of each rig, in the library's order
  std::vector<long> rig_frames;
  std::vector<size_t> rig(read_skeletons.size());
  for (size_t s = 0; s < read_skeletons.size(); ++s) {
    std::vector<std::pair<std::string, std::string>> joints;
    for (const JointDef& joint : read_skeletons[s].joints()) {
      joints.emplace_back(joint.name, joint.parent < 0 ? "" : read_skeletons[s].joint(joint.parent).name);
    }
    const auto [it, added] = rig_of.emplace(std::move(joints), rig_skeleton.size());
    if (added) {
      rig_skeleton.push_back(s);
      rig_frames.push_back(0);
    }
    rig[s] = it->second;
  }
  for (const DatabaseClip& clip : db.clips) rig_frames[rig[static_cast<size_t>(clip.skeleton)]] += clip.frame_count;
  std::vector<size_t> by_frames(rig_skeleton.size());
  for (size_t r = 0; r < by_frames.size(); ++r) by_frames[r] = r;
  std::stable_sort(by_frames.begin(), by_frames.end(),
                   [&](size_t a, size_t b) { return rig_frames[a] > rig_frames[b]; });

  std::vector<bool> best;
  long best_frames = -1;
  for (const size_t seed : by_frames) {
    std::vector<bool> in(rig_skeleton.size(), false);
    in[seed] = true;
    long frames = rig_frames[seed];
    for (const size_t r : by_frames) {
      if (in[r]) continue;
      in[r] = true;
      std::vector<const Skeleton*> in_order;  // rigs are numbered in the library's order
      for (size_t o = 0; o < in.size(); ++o) {
        if (in[o]) in_order.push_back(&read_skeletons[rig_skeleton[o]]);
      }
      if (read_together(in_order, db.foot_names)) {
        frames += rig_frames[r];
      } else {
        in[r] = false;
      }
    }
    if (frames > best_frames) {
      best = std::move(in);
      best_frames = frames;
    }
  }
  std::vector<bool> out(read_skeletons.size());
  for (size_t s = 0; s < out.size(); ++s) out[s] = best[rig[s]];
  return out;
}

// A hash of a clip as read: its rate, its joints' names and its motion's numbers.
std::uint64_t motion_content_hash(const Clip& clip) {
  std::string bytes = fmt::format("{} {} {}|", clip.motion.fps, clip.motion.frame_count, clip.motion.joint_count);
  for (int j = 0; j < clip.skeleton.joint_count(); ++j) bytes += clip.skeleton.joint(j).name + '|';
  const Motion& m = clip.motion;
  bytes.append(reinterpret_cast<const char*>(m.local_rotations.data()), m.local_rotations.size() * sizeof(Quat));
  bytes.append(reinterpret_cast<const char*>(m.local_translations_m.data()),
               m.local_translations_m.size() * sizeof(Vec3));
  return std::hash<std::string>{}(bytes);
}

// DatabaseSettings::mirror: every clip of a skeleton that can be mirrored, mirrored (motion/mirror.h)
// after them all, under NAME_mirrored (or NAME_mirrored_2... when taken), with the tag ranges of
// its own moved along, a tag that names a side naming the other (turn_left -> turn_right: the
// mirror turns right).
Status mirror_clips(MotionDatabase& db, DatabaseLoadNotes* notes) {
  std::vector<Result<MirrorMap>> maps;
  for (const Skeleton& skeleton : db.skeletons) maps.push_back(mirror_map(skeleton));
  std::set<std::string> names;
  for (const DatabaseClip& clip : db.clips) names.insert(clip.name);
  const size_t read = db.clips.size();
  const size_t ranges = db.tag_ranges.size();
  std::vector<int> unmirrored_clips(db.skeletons.size(), 0);
  std::vector<int> mirrored_tag(db.tag_names.size());
  for (size_t t = 0; t < mirrored_tag.size(); ++t) {
    const std::string other = mirrored_side_words(db.tag_names[t]);
    mirrored_tag[t] = other == db.tag_names[t] ? static_cast<int>(t) : db.tag_index(other);
    if (mirrored_tag[t] < 0) {
      return Error{"", 0, fmt::format("the tag '{}' of mirrored clips would be one tag more than the 64 a library "
                                      "holds",
                                      other)};
    }
  }
  for (size_t c = 0; c < read; ++c) {
    const int skeleton = db.clips[c].skeleton;
    const Result<MirrorMap>& map = maps[static_cast<size_t>(skeleton)];
    if (!map) {
      ++unmirrored_clips[static_cast<size_t>(skeleton)];
      continue;
    }
    DatabaseClip mirrored;
    mirrored.name =
        unique_name(db.clips[c].name + "_mirrored", [&](const std::string& n) { return names.count(n) > 0; });
    names.insert(mirrored.name);
    mirrored.source = db.clips[c].source;
    mirrored.skeleton = skeleton;
    mirrored.first_frame = db.frame_count();
    mirrored.frame_count = db.clips[c].frame_count;
    mirrored.motion = mirror_motion(db.skeletons[static_cast<size_t>(skeleton)], *map, db.clips[c].motion);
    mirrored.read_fps = db.clips[c].read_fps;
    const int from = db.clips[c].first_frame, to = from + db.clips[c].frame_count;
    for (size_t r = 0; r < ranges; ++r) {
      const TagRange range = db.tag_ranges[r];
      const int first = std::max(range.first_frame, from), last = std::min(range.first_frame + range.frame_count, to);
      if (first < last) {
        db.tag_ranges.push_back(TagRange{mirrored_tag[static_cast<size_t>(range.tag)],
                                         mirrored.first_frame + first - from, last - first});
      }
    }
    if (notes != nullptr) {
      notes->mirrored.push_back(mirrored.name);
      notes->mirror_sources.push_back(db.clips[c].name);
    }
    db.clips.push_back(std::move(mirrored));
  }
  if (notes != nullptr) {
    for (size_t s = 0; s < maps.size(); ++s) {
      if (unmirrored_clips[s] > 0) {
        notes->unmirrored.push_back({db.skeleton_names[s], maps[s].error().message, unmirrored_clips[s]});
      }
    }
  }
  return Ok{};
}

// Steps 3-5 of load_database: the clips read, back to back, on `joints` when given (else as
// read), the feet's contacts, the doubts. When the skeletons differ in some joints, every clip
// is kept on those they share (motion/common_joints.h); a file whose own up axis is not settled
// and differs from the library's (motion/up_axis.h) is read again in the library's: the
// database is made once more, with every file.
Result<MotionDatabase> load_clips(std::vector<ClipSpec> specs, const DatabaseSettings& settings,
                                  const ManifestWide& wide, const std::optional<CmuIndex>& cmu,
                                  DatabaseLoadNotes* notes, const std::vector<std::string>& joints) {
  MotionDatabase db;
  db.fps = wide.fps.value_or(settings.fps);
  db.foot_names = settings.foot_names.empty() ? wide.feet.value_or(FootJointNames{}) : settings.foot_names;
  for (ClipSpec& spec : specs) spec.load.foot_names = db.foot_names;  // travel from the feet (in_place.h)

  // 3. Clips, back to back.
  Loaders loaders;
  std::map<std::string, int> skeleton_of_file;  // canonical skeleton path -> index
  int next_frame = 0;
  std::vector<std::pair<size_t, UpAxisChoice>> chosen_up_axes;  // spec index, its own choice
  std::optional<Error> other_joints;  // the first skeleton whose joints differ from the first's
  std::set<std::string> noted_units, noted_up_axes, noted_travels, noted_folds, noted_rests,
      noted_glitches;  // files
  std::optional<Skeleton> first_skeleton;  // the first clip's, as read (all its joints)
  std::vector<Skeleton> read_skeletons;    // db.skeletons' as read, before any took the first's names
  std::vector<DescribedClip> described;    // clips tagged by their CMU descriptions
  std::set<std::string> clip_names;        // taken, for the parts a capture glitch cuts a clip into
  for (const ClipSpec& spec : specs) clip_names.insert(spec.name);
  ProgressBar reading("reading", specs.size(), !settings.progress_bar, settings.progress_lines);
  std::unordered_map<std::uint64_t, std::string> read_motions;  // a folder's clips: content hash -> file
  std::vector<Error> unreadable;  // a folder's files passed over
  for (size_t spec_index = 0; spec_index < specs.size(); ++spec_index) {
    const ClipSpec& spec = specs[spec_index];
    if (auto s = check_stop(settings.stop); !s) return s.error();
    reading.advance();  // counted as it starts: every way on from here is past it
    auto loaded = loaders.for_settings(spec.load).load(spec.path, spec.animation);
    if (!loaded && loaded.error().kind == ErrorKind::kNoSuchAnimation && !spec.manifest.empty()) {
      // The manifest's line that asked for it is what to change.
      return Error{spec.manifest, spec.animation_line, fmt::format("clip {}: {}", spec.path, loaded.error().message)};
    }
    // A folder's file that cannot be read is passed over, its error noted (once: the clips may be
    // read again below); a library of hundreds is not stopped by one file cut short.
    if (!loaded && spec.in_folder && loaded.error().kind == ErrorKind::kGeneral) {
      unreadable.push_back(loaded.error());
      if (notes != nullptr && std::none_of(notes->unreadable.begin(), notes->unreadable.end(),
                                           [&](const Error& e) { return e.file == loaded.error().file; })) {
        notes->unreadable.push_back(loaded.error());
      }
      continue;
    }
    if (!loaded) return loaded.error();
    if (loaded->format == "amc") {  // its skeleton, when found beside it
      const std::string how = fmt::format("the skeleton of {}", spec.path);
      if (auto s = check_not_an_output(loaded->skeleton_path, settings.outputs, how); !s) return s.error();
    }
    // A file a folder holds with a pose, not a motion (no frame, or under 2 at the library's rate:
    // a T-pose export, a character's skeleton), is passed over with a note, before anything of it
    // is noted or counted; given itself, an error below.
    if (spec.in_folder && resampled_frame_count(loaded->clip.motion, db.fps) < 2) {
      const Motion& pose = loaded->clip.motion;
      if (notes != nullptr) notes->poses.push_back({spec.path, pose.frame_count, pose.fps});
      continue;
    }
    // A folder's file whose motion as read is another file's (a copy in other bytes: other line
    // endings, numbers written otherwise) is left out as the folder leaves out a copy of the same
    // bytes: it would add nothing but transitions between the copies, at distance 0.
    if (spec.in_folder) {
      const auto [first, fresh] = read_motions.try_emplace(motion_content_hash(loaded->clip), spec.path);
      if (!fresh && first->second != spec.path) {
        const std::string line =
            fmt::format("{} left out: the same motion as {}, in other bytes (a copy)", spec.path, first->second);
        if (notes != nullptr && std::find(notes->name_clashes.begin(), notes->name_clashes.end(), line) ==
                                    notes->name_clashes.end()) {
          notes->name_clashes.push_back(line);
        }
        continue;
      }
    }
    // Folded at import as read (before the library's own rerooting below, which it notes apart).
    if (notes && !loaded->clip.dropped_at_fold.empty() && noted_folds.insert(spec.path).second) {
      DatabaseLoadNotes::Rerooted fold{spec.path, loaded->clip.skeleton.joint(0).name, {},
                                       loaded->clip.dropped_at_fold};
      for (const StaticAncestor& a : loaded->clip.skeleton.static_ancestors()) fold.above.push_back(a.name);
      notes->folded_roots.push_back(std::move(fold));
    }
    // Capture glitches within it (motion/capture_glitches.h), kept with the rest frames: found on
    // the file as read, all its joints, before the library reroots or cuts it to shared joints.
    const std::vector<CaptureGlitch> glitches = spec.load.keep_rest_frames
                                                    ? std::vector<CaptureGlitch>{}
                                                    : find_capture_glitches(loaded->clip.skeleton, loaded->clip.motion);
    // Another converter's names on the first skeleton's hierarchy: the first's names.
    if (!first_skeleton) first_skeleton = loaded->clip.skeleton;
    Skeleton as_read = loaded->clip.skeleton;  // before it takes the first's names
    const auto renamed = rename_as_first(loaded->clip, *first_skeleton);
    if (!joints.empty()) {
      if (loaded->clip.skeleton.joint(0).name != joints.front()) {  // rerooted in 3b, as read before
        auto rerooted = reroot_at(loaded->clip, joints.front());
        if (!rerooted) return spec.error(rerooted.error().message);
        loaded->clip = std::move(*rerooted);
      }
      auto kept = keep_joints(loaded->clip, joints);
      if (!kept) return spec.error(kept.error().message);
      loaded->clip = std::move(*kept);
    }
    if (loaded->clip.detected_up_axis) chosen_up_axes.emplace_back(spec_index, *loaded->clip.detected_up_axis);
    // Noted once a file, however many clips a manifest cuts from it.
    if (notes && loaded->clip.detected_unit && noted_units.insert(spec.path).second) {
      notes->detected_units.push_back({spec.path, *loaded->clip.detected_unit});
    }
    if (notes && loaded->clip.detected_up_axis && noted_up_axes.insert(spec.path).second) {
      notes->detected_up_axes.push_back({spec.path, *loaded->clip.detected_up_axis, std::nullopt});
    }
    if (notes && loaded->clip.in_place && loaded->clip.in_place->recovered &&
        noted_travels.insert(spec.path).second) {
      notes->recovered_travels.push_back({spec.path, spec.load.travel, *loaded->clip.in_place});
    }
    const Motion& motion = loaded->clip.motion;
    const int rest = loaded->clip.dropped_leading_frames;
    if (notes && rest > 0 && noted_rests.insert(spec.path).second) notes->rest_frames.push_back({spec.path, rest});
    const int glitched_leading = loaded->clip.glitched_leading_frames;
    const int trailing = loaded->clip.glitched_trailing_frames;
    if (notes && (glitched_leading > 0 || trailing > 0) && noted_glitches.insert(spec.path).second) {
      notes->glitched_ends.push_back({spec.path, glitched_leading, trailing});
    }
    const int dropped = rest + glitched_leading;  // leading frames the reader dropped
    const int file_frames = dropped + motion.frame_count + trailing;

    if (file_frames == 0) return Error{spec.path, 0, "the clip has no frames (a skeleton without motion)"};
    // Frame range, in the file's numbering; frames the reader dropped are not part of it.
    const int first = std::max(spec.first_frame.value_or(1), dropped + 1);
    const int asked_last = spec.last_frame.value_or(file_frames);
    const int last = std::min(asked_last, file_frames - trailing);
    if (asked_last > file_frames) {
      return Error{spec.manifest, spec.frames_line,
                   fmt::format("last_frame {} is past the end of {} ({} frames)", asked_last, spec.path, file_frames)};
    }
    if (spec.first_frame.value_or(1) > file_frames) {
      return Error{spec.manifest, spec.frames_line,
                   fmt::format("first_frame {} is past the end of {} ({} frames)", *spec.first_frame, spec.path,
                               file_frames)};
    }
    // Why frames of the file are not the clip's, for the errors below: what the reader dropped.
    const char* dropped_why =
        rest > 0 && glitched_leading + trailing == 0 ? "a rest pose before the capture"
        : rest == 0 ? "cut off by a capture glitch; --keep-rest-frames keeps them"
                    : "a rest pose before the capture, or cut off by a capture glitch; --keep-rest-frames keeps them";
    if (last < first) {
      return Error{spec.manifest, spec.frames_line,
                   fmt::format("frames {}..{} of {} hold only frames the reader drops ({}); the clip's frames are "
                               "{}..{}", spec.first_frame.value_or(1), asked_last, spec.path, dropped_why, dropped + 1,
                               file_frames - trailing)};
    }
    const bool whole = first == dropped + 1 && last == file_frames - trailing;
    Motion sliced;
    if (!whole) sliced = motion.slice(first - 1 - dropped, last - first + 1);
    const Motion& cut = whole ? motion : sliced;
    const double input_fps = cut.fps;
    // Cut at the capture glitches within its frames.
    GlitchFreeParts glitch_parts = glitch_free_parts(glitches, first - 1 - dropped, cut.frame_count, input_fps);
    bool split = !glitch_parts.glitches.empty();
    // A whole file that loops goes on past its end (motion/loop.h), as far as a window and a
    // frame at the database's rate, so that a transition can lead from its end back to its start.
    // A clip cut out of a longer file is not judged: its file holds what comes after it.
    Motion unrolled;
    std::optional<DatabaseLoadNotes::Loop> loop_note;
    if (settings.loops && whole && !split) {
      const LoopChoice loop = find_loop(loaded->clip.skeleton, cut);
      if (loop.loops) {
        const int extra = static_cast<int>(std::ceil(settings.loop_frames_at(db.fps) * input_fps / db.fps - 1e-9));
        unrolled = unrolled_loop(loaded->clip.skeleton, cut, loop, extra);
        loop_note = DatabaseLoadNotes::Loop{spec.name, spec.path, loop, 0};
      }
    }
    // The clip's parts at the database's rate, with their frames in the file's numbering.
    struct Part {
      Motion motion;
      int first = 0, last = 0;  // file frames, 1-based
    };
    std::vector<Part> parts;
    for (const auto& [part_first, part_count] : glitch_parts.parts) {
      if (!split) break;  // one part, the frames whole: resampled below
      auto resampled = resample(cut.slice(part_first, part_count), db.fps);
      if (!resampled) return spec.error(resampled.error().message);
      // A part too short at the library's rate is dropped too.
      if (resampled->frame_count >= 2) {
        parts.push_back({std::move(*resampled), first + part_first, first + part_first + part_count - 1});
      }
    }
    if (split && parts.empty()) split = false;  // no part of 2 frames at this rate: the frames whole
    if (!split) {
      auto resampled = resample(loop_note ? unrolled : cut, db.fps);
      if (!resampled) return spec.error(resampled.error().message);
      if (resampled->frame_count < 2) {
        return spec.error(fmt::format("{} frame{} at {} fps ({} frames at {} fps in the file{}): a clip needs at "
                                      "least 2", resampled->frame_count, resampled->frame_count == 1 ? "" : "s", db.fps,
                                      cut.frame_count, input_fps, whole ? "" : ", in its frame range"));
      }
      parts.push_back({std::move(*resampled), first, last});
    }

    // Skeleton: one entry per skeleton file, all with the same joints.
    const std::string skeleton_file = loaded->format == "amc" ? loaded->skeleton_path : spec.path;
    if (notes != nullptr && !renamed.empty()) {
      DatabaseLoadNotes::MatchedRig& rig = rig_note(*notes, skeleton_file);
      if (rig.renamed.empty()) rig.renamed = renamed;
    }
    std::error_code ec;
    std::string key = fs::weakly_canonical(skeleton_file, ec).string();
    if (ec) key = fs::absolute(skeleton_file).lexically_normal().string();
    // An ASF's clips read z up have its skeleton turned (motion/up_axis.h): another entry.
    const auto& detected = loaded->clip.detected_up_axis;
    if ((detected ? detected->axis : spec.load.up_axis.value_or(UpAxis::kY)) == UpAxis::kZ) key += " (z up)";
    int skeleton = 0;
    if (auto it = skeleton_of_file.find(key); it != skeleton_of_file.end()) {
      skeleton = it->second;
    } else {
      if (!db.skeletons.empty()) {
        if (auto difference = topology_difference(db.skeletons.front(), loaded->clip.skeleton)) {
          // The same hierarchy under other names was matched above unless a joint's side says not.
          const auto other_hierarchy = hierarchy_mismatch(db.skeletons.front(), loaded->clip.skeleton);
          const std::string sides =
              other_hierarchy && db.skeletons.front().joint_count() == loaded->clip.skeleton.joint_count()
                  ? fmt::format(" (nor is it the same hierarchy under other names: {})", *other_hierarchy)
                  : "";
          Error error = spec.error(fmt::format(
              "skeleton {} does not match {}, the database's first skeleton: {}{}; clips of one database need the "
              "same joints (names and parents, or the same hierarchy), or most of them in common",
              skeleton_file, db.skeleton_names.front(), *difference, sides));
          if (!joints.empty()) return error;
          if (!other_joints) other_joints = std::move(error);
        }
      }
      skeleton = static_cast<int>(db.skeletons.size());
      db.skeletons.push_back(loaded->clip.skeleton);
      read_skeletons.push_back(std::move(as_read));
      db.skeleton_names.push_back(skeleton_file);
      skeleton_of_file.emplace(key, skeleton);
    }

    if (loop_note && notes != nullptr) {
      loop_note->added_frames = parts.front().motion.frame_count - static_cast<int>(resampled_frame_count(cut, db.fps));
      notes->loops.push_back(std::move(*loop_note));
    }

    // Ranges are in the file's frames, as far as the clip's last asked (the file's end); they
    // cover the frames the clip keeps of them.
    if (spec.gives_tags) {
      for (const ManifestRange& range : spec.ranges) {
        if (range.last_frame > asked_last) {
          return Error{spec.manifest, range.line,
                       fmt::format("range last_frame {} is past the end of {} (frame {})", range.last_frame,
                                   spec.path, asked_last)};
        }
        if (range.last_frame < first || range.first_frame > last) {
          return Error{spec.manifest, range.line,
                       fmt::format("range {}..{} holds only frames the reader drops from {} ({}); the clip's frames "
                                   "are {}..{}", range.first_frame, range.last_frame, spec.path, dropped_why, first,
                                   last)};
        }
      }
    }
    std::optional<DatabaseLoadNotes::GlitchSplit> split_note;
    if (split && notes != nullptr) {
      split_note = DatabaseLoadNotes::GlitchSplit{spec.path, spec.name,
                                                  in_file_frames(glitch_parts.glitches, first, input_fps), {},
                                                  cut.frame_count};
      for (const Part& part : parts) split_note->dropped_frames -= part.last - part.first + 1;
    }
    std::vector<char> range_kept(spec.ranges.size(), 0);  // a range covers some part's frames
    for (size_t p = 0; p < parts.size(); ++p) {
      Part& part = parts[p];
      DatabaseClip clip;
      // The first part keeps the clip's name, the others are its _part2, _part3...
      clip.name = p == 0 ? spec.name : fmt::format("{}_part{}", spec.name, p + 1);
      if (p > 0) {
        if (clip_names.count(clip.name) > 0) {
          const std::string taken = clip.name;
          clip.name = unique_name(taken, [&](const std::string& n) { return clip_names.count(n) > 0; });
          if (notes != nullptr) {
            notes->name_clashes.push_back(fmt::format("{}: a clip is named {} already; this clip's part {}, cut at "
                                                      "capture glitches, is {}", spec.path, taken, p + 1, clip.name));
          }
        }
        clip_names.insert(clip.name);
      }
      clip.source = spec.path;
      clip.skeleton = skeleton;
      clip.first_frame = next_frame;
      clip.frame_count = part.motion.frame_count;
      clip.motion = std::move(part.motion);
      clip.read_fps = input_fps;
      next_frame += clip.frame_count;
      if (split_note) split_note->parts.push_back({clip.name, part.first, part.last});

      // Tags.
      if (spec.gives_tags) {
        for (const std::string& tag : spec.tags) {
          if (auto s = add_tag_range(db, tag, clip.first_frame, clip.frame_count, spec); !s) return s.error();
        }
        for (size_t r = 0; r < spec.ranges.size(); ++r) {
          const ManifestRange& range = spec.ranges[r];
          if (range.last_frame < part.first || range.first_frame > part.last) continue;  // in another part
          range_kept[r] = 1;
          const double start_s = (std::max(range.first_frame, part.first) - part.first) / input_fps;
          const double end_s = (std::min(range.last_frame, part.last) - part.first) / input_fps;
          const auto [lo, hi] = output_frames(start_s, end_s, db.fps, clip.frame_count);
          for (const std::string& tag : range.tags) {
            if (auto s = add_tag_range(db, tag, clip.first_frame + lo, hi - lo + 1, spec); !s) return s.error();
          }
        }
      } else {
        // Tagged once the motion is settled (3e): walk and run only where the root travels. CMU's
        // description wins; a clip it does not list is tagged by the words of its name.
        const CmuMotion* motion_entry = cmu ? cmu->find(spec.cmu_name) : nullptr;
        if (motion_entry != nullptr) {
          described.push_back({spec_index, db.clips.size(), cmu_description_tags(motion_entry->description)});
        } else if (settings.name_tags) {
          // The clip's name; where it says nothing, its file's or animation's (a manifest's name
          // for it), then its folder's below the one given ("walk/w01").
          const std::string stem = fs::path(spec.path).stem().string();
          const std::pair<const char*, const std::string*> sources[] = {
              {"name", &spec.name}, {"file", &spec.cmu_name}, {"file", &stem}, {"folder", &spec.folder}};
          for (const auto& [source, text] : sources) {
            auto tags = clip_name_tags(*text);
            if (tags.empty()) continue;
            if (notes != nullptr) notes->name_tagged.push_back({clip.name, tags, source, *text});
            described.push_back({spec_index, db.clips.size(), std::move(tags)});
            break;
          }
        }
      }
      db.clips.push_back(std::move(clip));
    }
    for (size_t r = 0; r < spec.ranges.size(); ++r) {
      if (range_kept[r] || !spec.gives_tags) continue;
      const ManifestRange& range = spec.ranges[r];
      std::vector<std::string> kept;
      for (const Part& part : parts) kept.push_back(fmt::format("{}..{}", part.first, part.last));
      return Error{spec.manifest, range.line,
                   fmt::format("range {}..{} holds only frames the reader drops from {} (between capture glitches "
                               "within it; --keep-rest-frames keeps them); the clip's frames are {}",
                               range.first_frame, range.last_frame, spec.path, fmt::join(kept, ", "))};
    }
    if (split_note) notes->glitch_splits.push_back(std::move(*split_note));
  }
  reading.finish();
  if (db.clips.empty() && !unreadable.empty()) {  // nothing read: the first file's error says why
    Error first = unreadable.front();
    if (unreadable.size() > 1) {
      first.message += fmt::format(" (and {} other file{} of the folder could not be read either)",
                                   unreadable.size() - 1, unreadable.size() == 2 ? "" : "s");
    }
    return first;
  }
  if (db.clips.empty()) {
    return Error{specs.front().path, 0,
                 fmt::format("every clip file of the folder holds a pose, not a motion (under 2 frames at {} fps)",
                             db.fps)};
  }

  // 3b. Skeletons that differ in some joints: every clip on the joints all share, as read (a
  // joint's motion is resampled on its own, so dropping joints after resampling is the same).
  std::vector<std::string> read_on = joints;
  std::vector<DatabaseLoadNotes::DroppedJoints> dropped_joints;
  std::vector<DatabaseLoadNotes::Rerooted> rerooted;
  if (other_joints) {
    std::vector<std::string> common = common_joints(db.skeletons);
    // Roots that differ: a root-motion joint above the hips in some rigs, the hips the root of
    // the others. Those read from the hips down, their root's motion composed into them.
    if (const std::string root = common.empty() ? shared_root(db.skeletons) : std::string(); !root.empty()) {
      if (auto s = reroot_database(db, root, rerooted); !s) return s.error();
      common = common_joints(db.skeletons);
    }
    if (auto short_by = common_joints_fall_short(db.skeletons, db.foot_names, common)) {
      // Files a folder holds whose rig cannot join the others' (another converter's, another
      // studio's): the library is the rigs that can, of the most frames; those left out.
      const std::vector<bool> family = largest_rig_family(db, read_skeletons);
      std::set<std::string> out_files;
      for (const DatabaseClip& clip : db.clips) {
        if (!family[static_cast<size_t>(clip.skeleton)]) out_files.insert(clip.source);
      }
      const bool all_in_folders = std::all_of(specs.begin(), specs.end(), [&](const ClipSpec& spec) {
        return spec.in_folder || out_files.count(spec.path) == 0;
      });
      if (out_files.empty() || !all_in_folders || !joints.empty()) {
        return Error{other_joints->file, other_joints->line, other_joints->message + " (" + *short_by + ")"};
      }
      DatabaseLoadNotes::OtherRigs left_out;
      // Why, of the first left out against the first kept.
      const auto first_of = [&](bool kept) {
        for (const DatabaseClip& clip : db.clips) {
          if (family[static_cast<size_t>(clip.skeleton)] == kept) return static_cast<size_t>(clip.skeleton);
        }
        return size_t{0};
      };
      const Skeleton pair[] = {db.skeletons[first_of(true)], db.skeletons[first_of(false)]};
      const auto pair_short = common_joints_fall_short(pair, db.foot_names, common_joints(pair));
      left_out.reason = fmt::format("{} against {}: {}{}", db.skeleton_names[first_of(false)],
                                    db.skeleton_names[first_of(true)],
                                    topology_difference(pair[0], pair[1]).value_or("other joints"),
                                    pair_short ? fmt::format(" ({})", *pair_short) : "");
      std::vector<ClipSpec> kept;
      for (ClipSpec& spec : specs) {
        if (out_files.count(spec.path) == 0) {
          kept.push_back(std::move(spec));
        } else if (left_out.files.empty() || left_out.files.back() != spec.path) {
          left_out.files.push_back(spec.path);
        }
      }
      if (notes != nullptr) *notes = DatabaseLoadNotes{};
      auto again = load_clips(std::move(kept), settings, wide, cmu, notes, joints);
      if (again && notes != nullptr) notes->other_rigs.insert(notes->other_rigs.begin(), std::move(left_out));
      return again;
    }
    std::vector<DatabaseLoadNotes::DroppedJoints> dropped;
    for (size_t s = 0; s < db.skeletons.size(); ++s) {
      DatabaseLoadNotes::DroppedJoints d{db.skeleton_names[s], {}};
      for (const JointDef& joint : db.skeletons[s].joints()) {
        if (std::find(common.begin(), common.end(), joint.name) == common.end()) d.joints.push_back(joint.name);
      }
      if (!d.joints.empty()) dropped.push_back(std::move(d));
    }
    std::vector<std::optional<Skeleton>> kept_skeletons(db.skeletons.size());
    for (DatabaseClip& clip : db.clips) {
      Clip whole;
      whole.name = clip.name;
      whole.skeleton = db.skeletons[static_cast<size_t>(clip.skeleton)];
      whole.motion = std::move(clip.motion);
      auto kept = keep_joints(whole, common);
      if (!kept) return Error{clip.source, 0, kept.error().message};
      std::optional<Skeleton>& skeleton = kept_skeletons[static_cast<size_t>(clip.skeleton)];
      if (!skeleton) skeleton = kept->skeleton;
      clip.motion = std::move(kept->motion);
    }
    for (size_t s = 0; s < db.skeletons.size(); ++s) db.skeletons[s] = std::move(*kept_skeletons[s]);
    dropped_joints = std::move(dropped);
    read_on = std::move(common);
    if (notes != nullptr) {
      notes->common_joints = read_on;
      notes->dropped_joints = dropped_joints;
      notes->rerooted = rerooted;
    }
  }

  // 3c. Files whose own up axis is not settled follow the library's: read again in it. Each file
  // votes once, however many clips (frame ranges) a manifest cuts from it.
  std::map<std::string, UpAxisChoice> choice_of_file;
  std::vector<std::string> voting_files;  // in clip order
  for (const auto& [spec_index, choice] : chosen_up_axes) {
    if (choice_of_file.emplace(specs[spec_index].path, choice).second) voting_files.push_back(specs[spec_index].path);
  }
  std::vector<UpAxisChoice> choices;
  for (const std::string& file : voting_files) choices.push_back(choice_of_file.at(file));
  if (const std::optional<UpAxis> library = library_up_axis(choices)) {
    std::vector<DatabaseLoadNotes::DetectedUpAxis> followed;
    for (const std::string& file : voting_files) {
      const UpAxisChoice& choice = choice_of_file.at(file);
      if (up_axis_settled(choice) || choice.axis == *library) continue;
      followed.push_back({file, choice, *library});
    }
    for (const auto& [spec_index, choice] : chosen_up_axes) {
      if (!up_axis_settled(choice) && choice.axis != *library) specs[spec_index].load.up_axis = *library;
    }
    if (!followed.empty()) {
      if (notes != nullptr) *notes = DatabaseLoadNotes{};
      auto again = load_clips(std::move(specs), settings, wide, cmu, notes, read_on);
      if (again && notes != nullptr) {
        notes->detected_up_axes.insert(notes->detected_up_axes.end(), followed.begin(), followed.end());
        if (other_joints) {  // read on the shared joints this time, as 3b kept them
          notes->common_joints = read_on;
          notes->dropped_joints = std::move(dropped_joints);
          notes->rerooted = std::move(rerooted);
        }
      }
      return again;
    }
  }

  // 3d. Rest poses, with the joints settled (after 3c, which reads everything again when it must).
  rest_as_first(db, notes);

  // 3e. The tags of CMU's descriptions and of clip names, in clip order: walk and run where the
  // root travels.
  for (const DescribedClip& d : described) {
    if (auto s = tag_described_clip(db, d, specs[d.spec_index], settings.travel_tags, notes); !s) return s.error();
  }
  if (notes != nullptr) {
    notes->standing_speed_mps = settings.travel_tags.min_speed_mps;
    // A tag no frame keeps: every clip that asked for it is among the standing ones.
    for (const auto& t : notes->standing_tags) {
      if (std::find(db.tag_names.begin(), db.tag_names.end(), t.tag) != db.tag_names.end()) continue;
      auto it = std::find_if(notes->vanished_tags.begin(), notes->vanished_tags.end(),
                             [&](const auto& v) { return v.tag == t.tag; });
      if (it == notes->vanished_tags.end()) it = notes->vanished_tags.insert(it, {t.tag, {}});
      it->clips.push_back(t.clip);
    }
  }

  // 3f. Each clip mirrored, after them all, with its own tags: always, or when the library turns
  // one way.
  const TurningBalance turning = turning_balance(db);
  const bool auto_lopsided = settings.mirror == DatabaseSettings::Mirroring::kWhenLopsided && turning.lopsided();
  const bool too_long = db.frame_count() >= settings.max_lopsided_mirror_s * db.fps;
  const bool lopsided = auto_lopsided && !too_long;
  if (notes != nullptr) {
    notes->turning = turning;
    notes->mirroring = settings.mirror;
    notes->mirrored_for_turning = lopsided;
    notes->too_long_to_mirror = auto_lopsided && too_long;
    notes->max_lopsided_mirror_s = settings.max_lopsided_mirror_s;
  }
  const size_t read_clips = db.clips.size();
  if (settings.mirror == DatabaseSettings::Mirroring::kAlways || lopsided) {
    if (auto s = mirror_clips(db, notes); !s) return s.error();
  }

  // 4. The feet's contacts (a rig whose feet are not found keeps the reason instead).
  if (auto s = find_database_contacts(db); !s) {
    if (!settings.foot_names.empty()) return Error{"", 0, "the foot joints named: " + s.error().message};
    return Error{wide.feet_source, wide.feet_line, s.error().message};
  }

  // 5. What looks wrong with a clip as read, for the caller to say (a mirrored clip's doubts are
  // its clip's).
  if (notes != nullptr) {
    for (DoubtedClip& clip : database_clip_doubts(db, read_clips)) {
      if (!clip.doubts.empty()) notes->clip_doubts.push_back(std::move(clip));
    }
  }
  return db;
}

}  // namespace

std::vector<std::string> load_warnings(const DatabaseLoadNotes& notes) {
  std::vector<std::string> lines;
  // The first `shown` names, "and N more".
  const auto listed = [](const std::vector<std::string>& all, size_t shown) {
    const std::vector<std::string> first(all.begin(), all.begin() + static_cast<long>(std::min(shown, all.size())));
    return fmt::format("{}{}", fmt::join(first, ", "),
                       all.size() > shown ? fmt::format(" and {} more", all.size() - shown) : "");
  };
  for (const auto& [file, choice] : notes.detected_units) {
    if (!choice.plausible || !choice.also) continue;
    lines.push_back(fmt::format("{}: lengths read in {} (figure {:.2f} m), but in {} the figure is {:.2f} m, a "
                                "person's size too: --scale {:g} reads it so",
                                file, choice.unit.name, choice.figure_size_m, choice.also->name,
                                choice.also_figure_size_m, choice.also->metres_per_unit));
  }
  // Once a reason: a rig spread over many files gives each the same.
  std::vector<std::pair<std::string, std::vector<std::string>>> unmirrored;  // reason, skeletons
  std::map<std::string, int> unmirrored_clips;
  for (const auto& u : notes.unmirrored) {
    auto it = std::find_if(unmirrored.begin(), unmirrored.end(), [&](const auto& r) { return r.first == u.reason; });
    if (it == unmirrored.end()) it = unmirrored.insert(it, {u.reason, {}});
    it->second.push_back(u.skeleton);
    unmirrored_clips[u.reason] += u.clips;
  }
  for (const auto& [reason, skeletons] : unmirrored) {
    const int clips = unmirrored_clips.at(reason);
    lines.push_back(fmt::format("{}: {} not mirrored: {}{}", listed(skeletons, 2),
                                clips == 1 ? std::string("its clip is")
                                           : fmt::format("{} {} clips are", skeletons.size() == 1 ? "its" : "their",
                                                         clips),
                                skeletons.size() == 1 ? "" : "of each rig, ", reason));
  }
  for (const auto& d : notes.detected_up_axes) {
    if (!d.library_axis) continue;
    lines.push_back(fmt::format("{}: read {} up like the library's other files, though its own shape says {} (z over "
                                "y: {:.2f} as played, {:.2f} at rest); --up-axis or a manifest's up_axis decides",
                                d.file, up_axis_name(*d.library_axis), up_axis_name(d.choice.axis),
                                d.choice.animation_ratio, d.choice.rest_ratio));
  }
  if (!notes.dropped_joints.empty()) {
    std::vector<std::string> names, files;
    for (const auto& d : notes.dropped_joints) {
      if (std::find(files.begin(), files.end(), d.skeleton) == files.end()) files.push_back(d.skeleton);
      for (const std::string& name : d.joints) {
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
      }
    }
    constexpr size_t kShown = 4;
    lines.push_back(fmt::format("the skeletons differ in some joints: every clip is read on the {} joints all of them "
                                "have; dropped {} ({} joint{}) from {}",
                                notes.common_joints.size(), listed(names, kShown), names.size(),
                                names.size() == 1 ? "" : "s", listed(files, 2)));
  }
  const auto hanging_off = [&listed](const DatabaseLoadNotes::Rerooted& r) {
    if (r.dropped.empty()) return std::string();
    return fmt::format("; dropped {}, which hung off {}", listed(r.dropped, 4), r.above.size() == 1 ? "it" : "them");
  };
  for (const auto& r : notes.rerooted) {
    lines.push_back(fmt::format("{}: read from '{}' down, the root of the library's other rigs: the motion of '{}' "
                                "above it is composed into it{}",
                                r.skeleton, r.root, fmt::join(r.above, "', '"), hanging_off(r)));
  }
  // Files of one rig folded alike: one line for them all.
  std::vector<std::pair<const DatabaseLoadNotes::Rerooted*, std::vector<std::string>>> alike;
  for (const auto& r : notes.folded_roots) {
    auto same = std::find_if(alike.begin(), alike.end(), [&](const auto& a) {
      return a.first->root == r.root && a.first->above == r.above && a.first->dropped == r.dropped;
    });
    if (same == alike.end()) same = alike.insert(alike.end(), {&r, {}});
    same->second.push_back(r.skeleton);
  }
  for (const auto& [r, files] : alike) {
    const std::string who = files.size() == 1 ? files.front()
                            : files.size() <= 2 ? fmt::format("{} and {}", files[0], files[1])
                                                : fmt::format("{}, {} and {} more", files[0], files[1],
                                                              files.size() - 2);
    lines.push_back(fmt::format("{}: {} root '{}' travels without turning (an engine's root motion), so '{}' below it "
                                "carries the floor position and facing{}",
                                who, files.size() == 1 ? "its" : "their", fmt::join(r->above, "', '"), r->root,
                                hanging_off(*r)));
  }
  for (const auto& rig : notes.matched_rigs) {
    std::vector<std::string> parts;
    if (!rig.renamed.empty()) {
      constexpr size_t kShown = 3;
      std::vector<std::string> pairs;
      for (size_t i = 0; i < std::min(kShown, rig.renamed.size()); ++i) {
        pairs.push_back(fmt::format("{} as {}", rig.renamed[i].first, rig.renamed[i].second));
      }
      parts.push_back(fmt::format("its joints are the library's first rig's under other names, matched by their place "
                                  "in the hierarchy ({}{})",
                                  fmt::join(pairs, ", "),
                                  rig.renamed.size() > kShown ? fmt::format(", {} in all", rig.renamed.size()) : ""));
    }
    if (rig.rest_pose) {
      parts.push_back(fmt::format("it rests in another pose than the library's first rig (the bone to '{}' {:.0f} "
                                  "degrees away), so its rotations are re-expressed on that rest pose, every joint "
                                  "where it was",
                                  rig.rest_pose->bone, rig.rest_pose->angle_deg));
    }
    lines.push_back(fmt::format("{}: {}", rig.file, fmt::join(parts, "; ")));
  }
  for (const auto& v : notes.vanished_tags) {
    lines.push_back(fmt::format("the library has no {0}: every clip CMU's descriptions or its name call {0} stands "
                                "where it is ({1}{2}; under {3} m/s over a second); --whole-clip-tags keeps their {0}",
                                v.tag, v.clips.front(),
                                v.clips.size() > 1 ? fmt::format(" and {} more", v.clips.size() - 1) : "",
                                notes.standing_speed_mps));
  }
  for (std::string& line : clip_doubt_lines(notes.clip_doubts)) lines.push_back(std::move(line));
  std::vector<std::string> first = notes.name_clashes;
  for (const Error& e : notes.unreadable) {
    first.push_back(fmt::format("{} (passed over: the library is read without it)", e.to_string()));
  }
  if (!notes.poses.empty()) {
    std::vector<std::string> files;
    for (const auto& pose : notes.poses) {
      files.push_back(fmt::format("{} ({} frame{} at {} fps)", pose.file, pose.frames, pose.frames == 1 ? "" : "s",
                                  pose.fps));
    }
    first.push_back(fmt::format("{} file{} passed over, a pose rather than a motion (under 2 frames at the library's "
                                "rate): {}", files.size(), files.size() == 1 ? "" : "s", listed(files, 4)));
  }
  for (const auto& o : notes.other_rigs) {
    first.push_back(fmt::format("{} file{} left out, {} rig cannot be read with the library's (the rigs that can, of "
                                "the most frames): {}; {}; a manifest, or the files given one by one, says which to "
                                "read",
                                o.files.size(), o.files.size() == 1 ? "" : "s", o.files.size() == 1 ? "its" : "their",
                                listed(o.files, 4), o.reason));
  }
  lines.insert(lines.begin(), first.begin(), first.end());
  return lines;
}

Result<MotionDatabase> load_database(const std::vector<std::string>& inputs, const DatabaseSettings& settings,
                                     DatabaseLoadNotes* notes) {
  if (auto s = settings.validate(); !s) return s.error();
  if (inputs.empty()) return Error{"", 0, "no inputs: give clip folders, clip files or a .toml manifest"};
  if (std::error_code ec; settings.asf_path && !fs::is_regular_file(*settings.asf_path, ec)) {
    return Error{*settings.asf_path, 0, "no such file (the skeleton given for AMC files)"};
  }

  // 1. What to read, in order.
  std::vector<ClipSpec> specs;
  ManifestWide wide;
  std::vector<std::string> name_clashes;
  for (const std::string& input : inputs) {
    if (input.empty()) return Error{"", 0, kEmptyFileName};
    std::error_code ec;
    const fs::file_status status = fs::status(input, ec);
    if (!fs::exists(status)) return Error{input, 0, "no such file or folder"};
    if (fs::is_directory(status)) {
      if (auto s = expand_folder(input, settings, specs, name_clashes); !s) return s.error();
      continue;
    }
    const std::string ext = lower_extension(input);
    if (ext == ".toml") {
      if (auto s = check_not_an_output(input, settings.outputs, "a manifest given"); !s) return s.error();
      if (auto s = expand_manifest(input, settings, specs, wide); !s) return s.error();
    } else if (is_clip_file(input)) {
      if (auto s = add_file_specs(input, default_load_settings(settings), specs, false); !s) return s.error();
    } else if (ext == ".asf") {
      return Error{input, 0, "an ASF file holds a skeleton only: give its folder, or its AMC files with --asf"};
    } else {
      return Error{input, 0, "unknown input: expected a folder, a .amc, .bvh, .glb, .gltf or .fbx clip, or a .toml manifest"};
    }
  }

  // A file two inputs reach (a folder and a folder in it, one folder under two names: `data/cmu
  // data/cmu/16`) is read once: a folder's file that a folder read already, or that is given
  // itself, is left out (given itself it is read where it is given: a file named itself stops
  // loading when it cannot be read with the others). A file given itself twice, or named by
  // manifests, is read each time (named NAME_2 below).
  {
    const auto key_of = [](const ClipSpec& spec) {
      std::error_code ec;
      const fs::path absolute = fs::absolute(spec.path, ec);
      fs::path canonical = ec ? fs::path(spec.path) : fs::weakly_canonical(absolute, ec);
      if (ec) canonical = absolute.lexically_normal();
      return std::pair{canonical.string(), spec.animation.value_or("")};
    };
    std::set<std::pair<std::string, std::string>> given, read_in_folders;
    for (const ClipSpec& spec : specs) {
      if (!spec.in_folder && spec.manifest.empty()) given.insert(key_of(spec));
    }
    std::vector<ClipSpec> once;
    std::vector<std::string> twice;
    for (ClipSpec& spec : specs) {
      if (spec.in_folder) {
        const auto key = key_of(spec);
        if (given.count(key) > 0 || !read_in_folders.insert(key).second) {
          if (twice.empty() || twice.back() != spec.path) twice.push_back(spec.path);
          continue;
        }
      }
      once.push_back(std::move(spec));
    }
    specs = std::move(once);
    if (!twice.empty()) {
      name_clashes.push_back(fmt::format("{} file{} read once, reached by inputs that overlap: {}{}", twice.size(),
                                         twice.size() == 1 ? "" : "s", twice.front(),
                                         twice.size() == 1 ? "" : fmt::format(" and {} more", twice.size() - 1)));
    }
  }

  // No file read is one the command will write: clips a folder holds or a manifest names, and
  // skeletons given them (an AMC's found beside it: when it is read).
  for (const ClipSpec& spec : specs) {
    const std::string how = spec.in_folder           ? std::string("a clip file of a folder given")
                            : !spec.manifest.empty() ? fmt::format("a clip {} names", spec.manifest)
                                                     : std::string("a clip file given");
    if (auto s = check_not_an_output(spec.path, settings.outputs, how); !s) return s.error();
    if (spec.load.asf_path) {
      const std::string skeleton_how = fmt::format("the skeleton of {}", spec.path);
      if (auto s = check_not_an_output(*spec.load.asf_path, settings.outputs, skeleton_how); !s) return s.error();
    }
  }

  // Every clip under a name of its own: a name met again (a file given itself twice, a manifest
  // and a folder reading one file, one file's ranges in a manifest) gets _2, _3..., with a warning.
  std::set<std::string> names;
  for (ClipSpec& spec : specs) {
    if (names.insert(spec.name).second) continue;
    const std::string taken = spec.name;
    spec.name = unique_name(taken, [&](const std::string& n) { return names.count(n) > 0; });
    names.insert(spec.name);
    name_clashes.push_back(fmt::format("{}{}: a clip is named {} already; this one is {}", spec.path,
                                       spec.manifest.empty() ? "" : fmt::format(" ({}:{})", spec.manifest, spec.line),
                                       taken, spec.name));
  }

  // 2. The CMU index, read once when some clip will look its tags up.
  std::optional<CmuIndex> cmu;
  const bool wants_cmu = settings.cmu_tags &&
                         std::any_of(specs.begin(), specs.end(), [](const ClipSpec& s) { return !s.gives_tags; });
  if (wants_cmu) {
    std::string text = settings.cmu_index_text;
    std::string name = "CMU index";
    std::string path = settings.cmu_index_path;
    if (text.empty() && path.empty() && settings.cmu_index_beside_inputs) path = find_cmu_index(inputs);
    if (text.empty() && !path.empty()) {
      if (auto s = check_not_an_output(path, settings.outputs, "the CMU index"); !s) return s.error();
      auto read = read_text_file(path);
      if (!read) return read.error();
      text = std::move(*read);
      name = path;
    } else if (text.empty()) {
      text = shipped_cmu_index();
      name = kShippedCmuIndexName;
    }
    auto index = parse_cmu_index(text, name);
    if (!index) return index.error();
    cmu = std::move(*index);
  }

  if (notes != nullptr) *notes = DatabaseLoadNotes{};
  auto database = load_clips(std::move(specs), settings, wide, cmu, notes, {});
  if (notes != nullptr) {  // the specs' clashes, then those of the parts clips were cut into
    notes->name_clashes.insert(notes->name_clashes.begin(), name_clashes.begin(), name_clashes.end());
  }
  return database;
}

}  // namespace mg
