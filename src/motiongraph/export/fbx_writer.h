// Motion -> binary FBX 7.4 (.fbx), the format Maya, MotionBuilder, 3ds Max, Unity and Unreal
// import natively (and Blender: File > Import > FBX): the skeleton as a hierarchy of LimbNode
// models (the static joints a trajectory joint was found below put back above it, as the BVH and
// glTF writers do), one animation stack per motion with a rotation curve per joint that turns and
// a translation curve per joint whose translation is animated, keyed at every frame (linear).
//
// Lengths are centimetres (UnitScaleFactor 1, as Maya and most FBX files are), +Y up, +Z front:
// an importer that works in metres (Unity, Blender with its default settings) scales by 0.01.
// Rotations are Euler angles in degrees in each joint's own order (the order its file gave it:
// ZXY for a BVH's "Zrotation Xrotation Yrotation", FBX's RotationOrder; the root's with the
// vertical axis outermost, so that its heading never sits in the middle angle, where Euler angles
// lock), kept continuous from frame to frame so that an importer resampling the curves never
// swings the long way round.
// The frame rate is the file's TimeMode (FBX's own rates, or custom), the key times FBX's ticks.
//
// Each model's local transform is the skeleton's (skeleton.h: Translate(t_j) * Rotate(L_j)), so an
// FBX reader finds the same world positions as forward kinematics. At rest every rotation is
// the identity and the translations are the first animation's first frame's, the root over the
// origin at its first frame's height (keyed_joints.h), as in the glTF writer. FBX applications
// draw a LimbNode hierarchy as bones themselves, but engines show nothing of a skeleton alone and
// Unreal makes a skeleton only of a skinned mesh's bones, so the file also carries glTF's grey
// stick figure (stick_figure.h) skinned to the joints (a cluster for every joint, those no vertex
// hangs from too, carrying its bind matrix; the mesh at the origin), with its bind pose (leave it
// out with stick_figure false). Names that are not valid UTF-8 get
// U+FFFD for the bytes that are not, bytes 0 and 1 (FBX's separator of name and class) '_', and
// names made alike so get "_2", "_3"....
#pragma once

#include <span>
#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/export/keyed_joints.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct FbxWriteSettings {
  bool stick_figure = true;  // a mesh skinned to the joints (false: the skeleton and its animation only)
};

using FbxAnimation = ExportAnimation;  // a stack each

// The .fbx bytes: the skeleton at rest as its first animation's first frame has it, and one
// animation stack per motion with frames (none without). Fails on a motion that does not fit the
// skeleton, an animation without a name, and a file over FBX 7.4's 4 GB.
Result<std::string> write_fbx(const Skeleton& skeleton, std::span<const FbxAnimation> animations,
                              const FbxWriteSettings& settings = {});
// One animation.
Result<std::string> write_fbx(const Skeleton& skeleton, const Motion& motion, const std::string& animation_name,
                              const FbxWriteSettings& settings = {});

}  // namespace mg
