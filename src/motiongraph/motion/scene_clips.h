// A scene of nodes with keyed animation -> Skeleton + Motion: one clip per animation, on one
// skeleton. The part glTF's and FBX's readers share (gltf_import.h, fbx_import.h): each turns
// its file into a NodeScene, and this makes the clips.
//
// The skeleton is every skin's joints (without a skin: the nodes the animations move, those of the
// tree most of them are in), rooted at the lowest node above them all, with the nodes on the way
// between them and every node below the root that holds no mesh, camera or light (fingers no key
// moves, end bones no skin lists: an FBX skin's bones are those vertices hang from); the nodes
// above the root (an armature, a scene node) are composed into it, frame by frame where they are
// animated (Blender's object animation), their uniform, constant scale (Blender's and Mixamo's
// 0.01 armatures, FBX's 100) into every length, and the file's unit (`metres_per_unit`). An
// animation that moves neither the skeleton nor a node above it (a camera's) is no clip.
//
// Such joints rest in any rotation (a bone's frame along the bone, as Blender and Maya make
// them); the project's skeletons rest with every rotation at identity (skeleton.h). So each
// joint's frame is re-expressed on the rest pose the nodes hold without animation: turned by its
// rest world rotation, which makes its rest rotation the identity and its offset the rest
// offset in the world's axes; every joint's world position is unchanged in every frame.
//
// Animations are sampled at one rate: the rate of their keys (the step of evenly keyed tracks, or
// the most common step between two keys, snapped to a whole number of frames per second within
// 1e-4; 30 fps or more where keys lie off that rate's frames or come slower than 24 a second), or
// `fps_override`, from their first key to their last (at most 1 000 000 frames, and
// `max_joint_poses` over the file), by their tracks' rules (linear: lerp, and slerp for
// rotations; step; cubic: Hermite, renormalised). A joint an animation does not move holds its
// rest transform. Scale other than 1 on a joint (or animated) is an error: the project reads
// rigid skeletons.
//
// Then, as for BVH, a static root above the travelling hips is folded away (trajectory_joint.h),
// in every animation of the file as in the first whose hips travel, so that they share a
// skeleton. The scene is y up; a file is turned only when `up_axis` says z.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/motion/up_axis_choice.h"

namespace mg {

struct SceneClipSettings {
  double fps_override = 0.0;     // > 0: sample at this rate instead of the keys'
  bool fold_static_root = true;  // the hips as joint 0 below a static root
  std::optional<UpAxis> up_axis;  // nullopt or y: the scene's own (+y up); z: turned
  double max_joint_poses = kMaxJointPoses;  // frames x joints over all the file's animations

  Status validate() const;
};

// A node's transform: translation, rotation, scale.
struct NodeTrs {
  Vec3 translation = Vec3::Zero();
  Quat rotation = Quat::Identity();
  Vec3 scale = Vec3::Ones();
};

// One animated property of one node: keys and how to go between them.
struct KeyTrack {
  using Value = Eigen::Vector4d;  // x, y, z (and w for rotations)
  enum class Rule { kLinear, kStep, kCubic };

  std::vector<double> times;   // seconds, in order
  std::vector<double> values;  // per key: width values (kCubic: in-tangent, value, out-tangent)
  int width = 3;               // 4 for rotations (x, y, z, w)
  Rule rule = Rule::kLinear;

  // The value at time t (before the first key the first, after the last the last).
  Value sample(double t) const;
  Value value(size_t key) const;

 private:
  Value at_key(size_t key, int part) const;
};

enum class TrackPath { kTranslation, kRotation, kScale };

struct SceneNode {
  std::string name;
  std::vector<int> children;
  NodeTrs rest;
  std::string rest_error;  // not empty: the rest transform could not be read (an error if the node is used)
  bool content = false;    // holds a mesh, a camera or a light: no joint unless a skin says
};

struct SceneAnimation {
  std::string name;  // empty: "animation_N"
  std::vector<int> targets;  // the nodes its tracks move (scale included)
  std::map<std::pair<int, TrackPath>, KeyTrack> tracks;
  std::string error;  // not empty: its tracks could not be read (an error if it moves the skeleton)
  // The frame rate the file declares (FBX's), 0 when it declares none (glTF): keys on its frames
  // are sampled at it, however slow (keys slower than 24 a second are otherwise sampled at 30).
  double declared_fps = 0.0;
};

struct NodeScene {
  std::string format;  // "glTF", "FBX": for messages
  std::vector<SceneNode> nodes;
  std::vector<std::vector<int>> skins;  // each skin's joints
  std::vector<SceneAnimation> animations;
  double metres_per_unit = 1.0;
  Quat turn = Quat::Identity();  // the file's axes turned y up, above every node
};

// One clip per animation that moves the skeleton, in the scene's order, named as the animation
// ("animation_N" without a name, a repeated name made unique). `file_name` for messages.
Result<std::vector<Clip>> clips_from_scene(const NodeScene& scene, const std::string& file_name,
                                           const SceneClipSettings& settings);

// The names clips_from_scene gives the scene's clips, without sampling them.
Result<std::vector<std::string>> scene_clip_names(const NodeScene& scene, const std::string& file_name);

}  // namespace mg
