// Motion written to a file, the format by extension: .bvh in metres (times units_per_metre),
// .glb binary glTF in metres (gltf_writer.h; .gltf the same as JSON with its buffer embedded), .fbx
// binary FBX in centimetres (fbx_writer.h) or
// .json world positions (positions_json.h), checked before any work.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/export/keyed_joints.h"
#include "motiongraph/export/positions_json.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/motion/root_motion.h"

namespace mg {

// Fails unless the path ends in .bvh, .glb, .gltf, .fbx or .json.
Status check_motion_output(const std::string& path);

// Whether `ext` (lower_extension) names a scene file, which holds a skeleton and animations: .glb,
// .gltf or .fbx (the formats an animation set goes into).
bool is_scene_extension(const std::string& ext);
// The formats it names, for messages: ".glb, .gltf or .fbx".
inline constexpr const char* kSceneFormats = ".glb, .gltf or .fbx";

// The bytes of a scene file, `ext` ".glb" or ".gltf" (gltf_writer.h) or ".fbx" (fbx_writer.h),
// holding the animations, with the stick figure when `figure`.
Result<std::string> scene_bytes(const std::string& ext, const Skeleton& skeleton,
                                std::span<const ExportAnimation> animations, bool figure);
// A root-motion joint to add before writing (motion/root_motion.h), and where the skeleton faces
// in its root's frame (synthesis/facing.h).
struct RootMotionOutput {
  RootMotionSettings settings;
  Vec3 forward_axis = Vec3::UnitZ();
};

// How motion is written, beyond the format its file's extension names.
struct MotionFileSettings {
  double units_per_metre = 1.0;  // BVH length units per metre (glTF and JSON are in metres, FBX in centimetres)
  bool figure = true;            // glTF, FBX: a stick figure skinned to the joints (false: the skeleton and its animation only)
  std::optional<RootMotionOutput> root_motion;  // a root-motion joint added above the root first
  bool keep_root_order = false;  // BVH: the root's rotation in the file's order (bvh_writer.h)
  std::string animation_name;    // glTF, FBX: the animation's name (empty: the file's, without its extension)

  Status validate() const;
};

// Writes the motion atomically as BVH (metres * units_per_metre), glTF or FBX (its animation named
// settings.animation_name, or as the file without its extension) or JSON positions.
// JSON gets the feet's contacts too when `contacts` is given (positions_json.h).
Status write_motion(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                    const MotionFileSettings& settings = {}, const PositionsJsonContacts* contacts = nullptr);
// What write_motion writes, not written (several outputs made before any is written).
Result<std::string> motion_file_bytes(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                                      const MotionFileSettings& settings,
                                      const PositionsJsonContacts* contacts = nullptr);

// One motion of an animation set.
struct NamedMotion {
  std::string source;                 // where it came from, for messages (a clip's file)
  std::string name;                   // its animation's name
  const Skeleton* skeleton = nullptr;
  const Motion* motion = nullptr;
  Vec3 forward_axis = Vec3::UnitZ();  // where its skeleton faces, for a root-motion joint
};

// Several motions of one rig into one .glb, .gltf or .fbx, an animation each (gltf_writer.h,
// fbx_writer.h), written atomically: a character's animation set as game engines import it. Each
// gets the root-motion joint asked for in `settings` facing its own forward axis
// (settings.root_motion's is not used); a held pose folded as the set's static-root clips
// (trajectory_joint.h: fold_as) faces theirs, its own having been learnt on the root it had. Fails
// unless the path ends in .glb, .gltf or .fbx, and when a motion's rig is not the first's
// (motion/rig_matching.h: rig_difference), naming its source.
Status write_animation_set(const std::string& path, std::span<const NamedMotion> motions,
                           const MotionFileSettings& settings = {});

// A captured clip's foot contacts, for its JSON: the feet found by name unless `names` gives
// them (skeleton/foot_joints.h). nullopt, with `why` set, when they are not found and none was
// named; an error when a joint named is missing.
struct ClipContacts {
  FootJoints feet;
  std::vector<ContactMask> masks;  // one per frame
};
Result<std::optional<ClipContacts>> clip_contacts(const Skeleton& skeleton, const Motion& motion,
                                                  const FootJointNames& names, std::string& why);

}  // namespace mg
