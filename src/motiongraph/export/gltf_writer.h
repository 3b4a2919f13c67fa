// Motion -> binary glTF 2.0 (.glb), the format game engines, Blender and three.js all import:
// one node per joint (the skeleton's hierarchy, the static joints a trajectory joint was found
// below put back above it, as the BVH writer does), a skin over them, and one animation with a
// rotation track per joint that rotates and a translation track per joint whose translation is
// animated, keyed at every frame (LINEAR: glTF interpolates rotations by slerp). Lengths are
// metres and +Y is up, as glTF asks and as the skeleton already is.
//
// Each node's local transform is the skeleton's (skeleton.h: Translate(t_j) * Rotate(L_j)), so a
// glTF reader finds the same world positions as forward kinematics. The rest pose the nodes hold
// without the animation (the skin's bind pose) has every rotation at identity, the rest offsets,
// the animated translations of the first frame, and the root over the origin at its first
// frame's height. Names that are not valid UTF-8 get U+FFFD for the bytes that are not.
//
// A skeleton alone shows as nothing in most viewers and engines, so the file also carries a stick
// figure skinned to the joints: an octahedral bone from each joint to each of its children (as
// Blender draws bones), bound rigidly to the parent joint (a rig with no bone 1 mm long or more
// gets neither mesh nor skin).
#pragma once

#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct GltfWriteSettings {
  std::string animation_name = "motion";
  bool bone_mesh = true;  // the stick figure (false: the skeleton and its animation only)

  Status validate() const;
};

// The .glb bytes. Fails only on a motion that does not fit its skeleton.
Result<std::string> write_glb(const Skeleton& skeleton, const Motion& motion, const GltfWriteSettings& settings);

}  // namespace mg
