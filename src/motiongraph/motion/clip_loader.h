// Loading a clip from files: picks the reader by extension (.amc with its .asf, .bvh, .glb and
// .gltf: motion/gltf_import.h, .fbx: motion/fbx_import.h), reads
// the text through io/file.h and builds Skeleton + Motion. Parsed ASF skeletons are cached, so
// loading many AMC files of one subject reads its ASF once.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/acclaim_import.h"
#include "motiongraph/motion/in_place_choice.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/motion/up_axis_choice.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg {

struct ClipLoadSettings {
  std::optional<std::string> asf_path;  // skeleton for AMC files; otherwise the only .asf
                                        // in the AMC's folder
  std::optional<double> bvh_metres_per_unit;  // BVH carries no unit; nullopt: chosen from the
                                              // figure's size (length_unit.h)
  std::optional<UpAxis> up_axis;        // nullopt: chosen from the figure's shape (up_axis.h),
                                        // for AMC and BVH alike
  double input_fps = 0.0;               // > 0: the capture rate, overriding the file's
                                        // (AMC files store none: 120 by default, CMU's rate)
  bool keep_rest_frames = false;        // keep leading rest/T-pose frames of a BVH, and the first or
                                        // last frames a capture glitch cuts off (glitched_ends.h)
  TravelSource travel = TravelSource::kAuto;  // where the travel over the floor comes from:
                                              // kAuto recovers it from the feet for clips
                                              // animated in place (in_place.h)
  FootJointNames foot_names;            // the feet for that (empty: found by their names)

  Status validate() const;
};

struct LoadedClip {
  Clip clip;
  std::string format;         // "amc", "bvh", "gltf" or "fbx"
  std::vector<std::string> animations;  // a glTF or FBX file's, in order
  int animation = -1;                   // the one read among them
  double file_metres_per_unit = 0.0;    // an FBX file's unit, as it says (0: none said)
  std::string file_up_axis;             // an FBX file's up axis, as it says ("+y", "+z", "-z", ...)
  std::string skeleton_path;  // the ASF used, for AMC
  int source_channels = 0;    // values per frame in the file (its degrees of freedom)
};

class ClipLoader {
 public:
  explicit ClipLoader(ClipLoadSettings settings) : settings_(std::move(settings)) {}

  // `animation`: the one of a glTF or FBX file's animations to read (default: its first), sampled at
  // the rate of its keys unless input_fps gives one.
  Result<LoadedClip> load(const std::string& path, const std::optional<std::string>& animation = std::nullopt);
  // An ASF file alone: its skeleton, with no frames.
  Result<std::shared_ptr<const AcclaimRig>> load_asf(const std::string& path);

 private:
  Result<std::string> find_asf_for(const std::string& amc_path) const;

  ClipLoadSettings settings_;
  std::map<std::string, std::shared_ptr<const AcclaimRig>> rigs_;
  std::string scene_path_;  // the glTF or FBX file last read, and its clips
  std::vector<Clip> scene_clips_;
  double scene_metres_per_unit_ = 0.0;  // an FBX file's facts
  std::string scene_up_axis_;
};

constexpr double kCmuCaptureFps = 120.0;

// By extension, in any case: a file the loader reads as clips (.amc, .bvh, .glb, .gltf, .fbx); a
// scene file among them, whose every animation is a clip (glTF, FBX); a glTF file; an FBX file.
bool is_clip_file(std::string_view path);
bool is_scene_file(std::string_view path);
bool is_gltf_file(std::string_view path);
bool is_fbx_file(std::string_view path);

// The skeleton of an AMC file among the .asf files of its folder: the only one, or of several the
// one CMU's naming gives it (16.asf for 16_01.amc); none when there is none or none is so named.
std::optional<std::filesystem::path> asf_of_amc(std::span<const std::filesystem::path> asfs,
                                                const std::filesystem::path& amc_path);

// A scene file's clip names (its animations that move a skeleton), without sampling them.
Result<std::vector<std::string>> animation_names(const std::string& path);

}  // namespace mg
