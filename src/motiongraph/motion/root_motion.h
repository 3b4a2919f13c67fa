// A root-motion joint, as game engines take motion: a new top joint on the floor under the
// hips, turned (about the vertical alone) the way the character faces, that carries its travel
// over the floor; the hips hang below it. Unreal extracts root motion from the root bone, Unity
// (a Generic rig's root node) and Godot (an AnimationTree's root-motion track) from a joint the
// user names: this one. Nothing moves: every other joint keeps its world position in every
// frame (the hips' local transform is what it was, seen from the new joint).
//
// The new joint stands on the floor under the hips (the floor: the lowest joint's height, its 5th
// percentile over the frames, so a clip whose file puts the floor elsewhere than y = 0 keeps its
// feet on it) and faces the way the hips' rotation faces (synthesis/facing.h: the forward axis
// turned by the root's rotation, on the floor); its +z axis points there, in the file's frame
// (glTF's, three.js's and Godot's forward; Unreal and Unity turn an import to their own). Both
// sway with the gait (a walking pelvis moves a few centimetres from side to side and turns a few
// degrees each step), which an engine's character would copy, so by default they are smoothed:
// each frame takes the value at it of the least-squares line through the frames within
// `smoothing_s` / 2 seconds either side (the window's mean where it is whole; near the ends,
// where it is cut, the line keeps steady motion where it is), the heading unwrapped so that a
// spin of any speed stays a spin. A steady straight walk, or a steady turn's heading, is kept
// exactly (0: the hips' floor position and facing as they are).
//
// A skeleton with static joints folded away above its hips (motion/trajectory_joint.h, a rig's
// fixed root) gets the new joint in the place of the one directly above the hips, named as it;
// those further up stay above it: the rig's own root bone then carries the root motion, as an
// engine expects of it. A root without position channels, or one that stands while a joint
// below it with position channels travels (a fixed root the import did not fold away), is an
// error.
#pragma once

#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct RootMotionSettings {
  std::string joint_name = "root_motion";  // when the skeleton has no static root to take the name of;
                                           // "_2", "_3"... appended while a joint has it
  double smoothing_s = 0.5;                // window for the floor position and heading (0: none)

  Status validate() const;
};

struct RootMotionClip {
  Skeleton skeleton;  // the new joint 0, then the skeleton's joints in order (indices + 1)
  Motion motion;
};

// `forward_axis`: where the skeleton faces in its root joint's frame (synthesis/facing.h).
Result<RootMotionClip> add_root_motion(const Skeleton& skeleton, const Motion& motion, const Vec3& forward_axis,
                                       const RootMotionSettings& settings);

}  // namespace mg
