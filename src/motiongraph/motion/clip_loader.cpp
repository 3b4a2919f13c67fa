#include "motiongraph/motion/clip_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "motiongraph/core/file_extension.h"
#include "motiongraph/io/amc_parser.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/fbx_import.h"
#include "motiongraph/motion/glitched_ends.h"
#include "motiongraph/motion/gltf_import.h"
#include "motiongraph/motion/in_place.h"
#include "motiongraph/motion/length_unit.h"
#include "motiongraph/motion/up_axis.h"

namespace mg {

namespace fs = std::filesystem;

bool is_gltf_file(std::string_view path) {
  const std::string ext = lower_extension(path);
  return ext == ".glb" || ext == ".gltf";
}

bool is_fbx_file(std::string_view path) { return lower_extension(path) == ".fbx"; }

bool is_scene_file(std::string_view path) { return is_gltf_file(path) || is_fbx_file(path); }

bool is_clip_file(std::string_view path) {
  const std::string ext = lower_extension(path);
  return ext == ".amc" || ext == ".bvh" || is_scene_file(path);
}

Result<std::vector<std::string>> animation_names(const std::string& path) {
  if (!is_scene_file(path)) return Error{path, 0, "only glTF and FBX files hold animations by name"};
  auto bytes = read_text_file(path);
  if (!bytes) return bytes.error();
  if (is_fbx_file(path)) return fbx_animation_names(*bytes, path);
  return gltf_animation_names(*bytes, path, fs::path(path).parent_path().string());
}

// An FBX file names its unit, but a figure it makes 170 m or 1.7 cm tall was exported with the
// wrong one (the classic factor of 100 between tools, a BVH imported unscaled): the file's clips
// are then read in the unit that makes the figure human-sized, as a BVH's are, and say so
// (detected_unit); `given` (--scale: metres per unit of the file's numbers) overrides both.
namespace {

void settle_fbx_unit(std::vector<Clip>& clips, double file_metres_per_unit, std::optional<double> given) {
  if (clips.empty() || !(file_metres_per_unit > 0.0)) return;
  double factor = 1.0;
  std::optional<LengthUnitChoice> choice;
  if (given) {
    factor = *given / file_metres_per_unit;
  } else {
    // The file's figure: the first clip's, the largest of its clips' (a held pose is small).
    double size_m = 0.0;
    for (const Clip& clip : clips) size_m = std::max(size_m, figure_size(clip.skeleton, clip.motion));
    if (size_m >= kPlausibleHeightMinM && size_m <= kPlausibleHeightMaxM) return;
    LengthUnitChoice chosen = choose_length_unit(size_m / file_metres_per_unit);
    if (!chosen.plausible) return;  // no unit helps: the file's own stands (the doubts will say)
    factor = chosen.unit.metres_per_unit / file_metres_per_unit;
    choice = chosen;
  }
  for (Clip& clip : clips) {
    scale_lengths(clip, factor);
    clip.detected_unit = choice;
  }
}

}  // namespace

Status ClipLoadSettings::validate() const {
  if (bvh_metres_per_unit && !is_length_unit_scale(*bvh_metres_per_unit)) {
    return Error{"", 0,
                 fmt::format("--scale must lie between {:g} and {:g} metres per unit, not {:g}", kMinLengthUnitScale,
                             kMaxLengthUnitScale, *bvh_metres_per_unit)};
  }
  if (!(input_fps >= 0.0) || !std::isfinite(input_fps)) return Error{"", 0, "--input-fps must be positive"};
  if (auto s = foot_names.validate(); !s) return s.error();
  return Ok{};
}

Result<std::string> ClipLoader::find_asf_for(const std::string& amc_path) const {
  if (settings_.asf_path) return *settings_.asf_path;
  fs::path folder = fs::path(amc_path).parent_path();
  if (folder.empty()) folder = ".";
  std::vector<fs::path> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_regular_file() && lower_extension(entry.path().string()) == ".asf") found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());
  if (auto asf = asf_of_amc(found, amc_path)) return asf->string();
  return Error{amc_path, 0,
               found.empty() ? "no skeleton: give --asf (no .asf file beside the AMC)"
                             : "several .asf files beside the AMC and none named as its subject (16.asf for "
                               "16_01.amc): choose one with --asf"};
}

std::optional<fs::path> asf_of_amc(std::span<const fs::path> asfs, const fs::path& amc_path) {
  if (asfs.size() == 1) return asfs.front();
  const std::string amc_stem = amc_path.stem().string();
  for (const fs::path& asf : asfs) {
    if (amc_stem.starts_with(asf.stem().string() + "_")) return asf;
  }
  return std::nullopt;
}

Result<std::shared_ptr<const AcclaimRig>> ClipLoader::load_asf(const std::string& path) {
  if (auto it = rigs_.find(path); it != rigs_.end()) return it->second;
  auto text = read_text_file(path);
  if (!text) return text.error();
  auto asf = parse_asf(*text, path);
  if (!asf) return asf.error();
  auto rig = build_acclaim_rig(*asf);
  if (!rig) return rig.error();
  auto shared = std::make_shared<const AcclaimRig>(std::move(*rig));
  rigs_.emplace(path, shared);
  return shared;
}

Result<LoadedClip> ClipLoader::load(const std::string& path, const std::optional<std::string>& animation) {
  if (auto s = settings_.validate(); !s) return s.error();
  const std::string ext = lower_extension(path);
  if (animation && !is_scene_file(path)) {
    return Error{path, 0, "an animation is chosen from a glTF (.glb, .gltf) or FBX (.fbx) file only"};
  }
  LoadedClip loaded;
  loaded.clip.name = fs::path(path).stem().string();
  if (ext == ".amc") {
    // A missing AMC is said as such, not as a skeleton missing beside it.
    if (std::error_code ec; !fs::exists(path, ec)) return Error{path, 0, "cannot open: No such file or directory"};
    auto asf_path = find_asf_for(path);
    if (!asf_path) return asf_path.error();
    auto rig = load_asf(*asf_path);
    if (!rig) return rig.error();
    auto text = read_text_file(path);
    if (!text) return text.error();
    auto amc = parse_amc(*text, path, (*rig)->amc_layout, (*rig)->angles_in_degrees);
    if (!amc) return amc.error();
    const double fps = settings_.input_fps > 0.0 ? settings_.input_fps : kCmuCaptureFps;
    loaded.clip.skeleton = (*rig)->skeleton;
    loaded.clip.motion = motion_from_amc(**rig, *amc, fps);
    // ASF names no up axis either (CMU's files stand in y; a z-up capture system's need not).
    stand_up(loaded.clip, settings_.up_axis);
    loaded.format = "amc";
    loaded.skeleton_path = *asf_path;
    loaded.source_channels = amc->values_per_frame;
  } else if (ext == ".bvh") {
    auto text = read_text_file(path);
    if (!text) return text.error();
    auto bvh = parse_bvh(*text, path);
    if (!bvh) return bvh.error();
    BvhImportSettings import;
    import.metres_per_unit = settings_.bvh_metres_per_unit;
    import.up_axis = settings_.up_axis;
    import.fps_override = settings_.input_fps;
    import.drop_rest_frames = !settings_.keep_rest_frames;
    auto clip = clip_from_bvh(*bvh, import);
    if (!clip) return Error{path, clip.error().line, clip.error().message};
    std::string name = std::move(loaded.clip.name);
    loaded.clip = std::move(*clip);
    loaded.clip.name = std::move(name);
    loaded.format = "bvh";
    loaded.source_channels = bvh->channel_count;
  } else if (is_scene_file(path)) {
    // A library reads each animation of a file in turn: the file is read once for all.
    if (scene_path_ != path) {
      auto bytes = read_text_file(path);
      if (!bytes) return bytes.error();
      Result<std::vector<Clip>> read = Error{path, 0, ""};
      scene_metres_per_unit_ = 0.0;
      scene_up_axis_.clear();
      if (is_fbx_file(path)) {
        FbxImportSettings import;
        import.fps_override = settings_.input_fps;
        import.up_axis = settings_.up_axis;
        FbxFileFacts facts;
        read = clips_from_fbx(*bytes, path, import, &facts);
        scene_metres_per_unit_ = facts.metres_per_unit;
        scene_up_axis_ = facts.up_axis;
        if (read) settle_fbx_unit(*read, facts.metres_per_unit, settings_.bvh_metres_per_unit);
      } else {
        GltfImportSettings import;
        import.fps_override = settings_.input_fps;
        import.up_axis = settings_.up_axis;
        import.base_dir = fs::path(path).parent_path().string();
        read = clips_from_gltf(*bytes, path, import);
      }
      if (!read) return read.error();
      scene_path_ = path;
      scene_clips_ = std::move(*read);
    }
    const std::vector<Clip>* clips = &scene_clips_;
    for (const Clip& clip : *clips) loaded.animations.push_back(clip.name);
    size_t chosen = 0;
    if (animation) {
      const auto it = std::find(loaded.animations.begin(), loaded.animations.end(), *animation);
      if (it == loaded.animations.end()) {
        return Error{path, 0,
                     fmt::format("no animation '{}' (the file has {})", *animation, fmt::join(loaded.animations, ", ")),
                     ErrorKind::kNoSuchAnimation};
      }
      chosen = static_cast<size_t>(it - loaded.animations.begin());
    }
    std::string name = std::move(loaded.clip.name);
    loaded.clip = (*clips)[chosen];
    // One animation is the file's clip; among several, the animation is named too.
    loaded.clip.name = clips->size() == 1 ? name : fmt::format("{}:{}", name, loaded.clip.name);
    loaded.format = is_fbx_file(path) ? "fbx" : "gltf";
    loaded.file_metres_per_unit = scene_metres_per_unit_;
    loaded.file_up_axis = scene_up_axis_;
    loaded.animation = static_cast<int>(chosen);
    loaded.source_channels = 0;
    for (int j = 0; j < loaded.clip.skeleton.joint_count(); ++j) {
      loaded.source_channels += loaded.clip.skeleton.translation_slot(j) >= 0 ? 7 : 4;  // a quaternion each
    }
  } else if (ext == ".asf") {
    return Error{path, 0, "an ASF file holds a skeleton only; give its AMC files"};
  } else {
    return Error{path, 0, "unknown file type (expected .amc, .bvh, .glb, .gltf or .fbx)"};
  }
  // Any format, standing in y and in metres: the frames a glitch cuts off its ends
  // (glitched_ends.h), kept with the rest frames, then its travel over the floor (in_place.h).
  if (!settings_.keep_rest_frames) drop_glitched_ends(loaded.clip);
  if (auto s = recover_travel(loaded.clip, settings_.travel, settings_.foot_names); !s) {
    return Error{path, 0, s.error().message};
  }
  return loaded;
}

}  // namespace mg
