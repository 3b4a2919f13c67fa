// Motion -> binary glTF 2.0 (.glb), the format game engines, Blender and three.js all import, or
// the same as a .gltf (JSON with its buffer in it as a base64 data URI: one file, a third larger):
// one node per joint (the skeleton's hierarchy, the static joints a trajectory joint was found
// below put back above it, as the BVH writer does), a skin over them, and one animation with a
// rotation track per joint that rotates and a translation track per joint whose translation is
// animated, keyed at every frame (LINEAR: glTF interpolates rotations by slerp). Lengths are
// metres and +Y is up, as glTF asks and as the skeleton already is.
//
// Several motions of one skeleton make one animation each (a character's animation set, as an
// engine imports it): a joint that any of them turns or moves is keyed in all of them, so that
// each animation poses the whole figure whichever played before it.
//
// Each node's local transform is the skeleton's (skeleton.h: Translate(t_j) * Rotate(L_j)), so a
// glTF reader finds the same world positions as forward kinematics. The rest pose the nodes hold
// without the animation (the skin's bind pose) has every rotation at identity, the rest offsets,
// the animated translations of the first animation's first frame, and the root over the origin
// at its first frame's height. Names that are not valid UTF-8 get U+FFFD for the bytes that are
// not. The joints are a skin's, which is what makes them a skeleton (Blender's armature, an
// engine's Skeleton) rather than loose nodes.
//
// A skeleton alone shows as nothing in most viewers and engines, so the file also carries a stick
// figure skinned to the joints: an octahedral bone from each joint to each of its children (as
// Blender draws bones), bound rigidly to the parent joint (a rig with no bone 1 mm long or more
// gets none). Without it (bone_mesh false) the skin is used by no mesh, which the Khronos
// validator notes (an info, not an error).
#pragma once

#include <span>
#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/export/keyed_joints.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct GltfWriteSettings {
  bool bone_mesh = true;  // the stick figure (false: the skeleton and its animations only)
};

using GltfAnimation = ExportAnimation;

// The .glb bytes: the skeleton at rest as its first animation's first frame has it, and one
// animation per motion with frames (none without). Fails on a motion that does not fit the
// skeleton and on an animation without a name.
Result<std::string> write_glb(const Skeleton& skeleton, std::span<const GltfAnimation> animations,
                              const GltfWriteSettings& settings = {});
// One animation.
Result<std::string> write_glb(const Skeleton& skeleton, const Motion& motion, const std::string& animation_name,
                              const GltfWriteSettings& settings = {});
// The same model as .gltf text (its buffer embedded).
Result<std::string> write_gltf(const Skeleton& skeleton, std::span<const GltfAnimation> animations,
                               const GltfWriteSettings& settings = {});
// Either: binary (.glb) or text (.gltf).
Result<std::string> write_gltf_file(const Skeleton& skeleton, std::span<const GltfAnimation> animations,
                                    const GltfWriteSettings& settings, bool binary);

}  // namespace mg
