// glTF 2.0 (.glb, or .gltf with its buffers) -> Skeleton + Motion: one clip per animation of
// the file, on one skeleton.
//
// The skeleton is every skin's joints (without a skin: the nodes the animations move, those of the
// tree most of them are in),
// rooted at the lowest node above them all, with the nodes on the way between them; the nodes
// above the root (an armature, a scene node) are composed into it, frame by frame where they are
// animated (Blender's object animation), their uniform, constant scale (Blender's and Mixamo's
// 0.01 armatures) into every length. glTF's lengths are metres. An animation that moves neither
// the skeleton nor a node above it (a camera's) is no clip; images are not decoded.
//
// glTF joints rest in any rotation (a bone's frame along the bone, as Blender and Maya make
// them); the project's skeletons rest with every rotation at identity (skeleton.h). So each
// joint's frame is re-expressed on the rest pose the nodes hold without animation: turned by its
// rest world rotation, which makes its rest rotation the identity and its offset the rest
// offset in the world's axes; every joint's world position is unchanged in every frame.
//
// Animations are sampled at one rate: the rate of their keys (the step of evenly keyed tracks, or
// the most common step between two keys, snapped to a whole number of frames per second within
// 1e-4; 30 fps or more where keys lie off that rate's frames or come slower than 24 a second), or
// `fps_override`, from their first key to their last (at most 1 000 000 frames, and
// `max_joint_poses` over the file), by their samplers' rules (LINEAR:
// lerp, and slerp for rotations; STEP; CUBICSPLINE: Hermite, renormalised). A joint an animation
// does not move holds its rest transform. Scale other than 1 on a joint (or animated) is an
// error; morph weights are not read: the project reads rigid skeletons.
//
// Then, as for BVH, a static root above the travelling hips is folded away (trajectory_joint.h),
// in every animation of the file as in the first whose hips travel, so that they share a
// skeleton. glTF's up axis is +y: a file is turned only when `up_axis` says z.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/motion/up_axis_choice.h"

namespace mg {

struct GltfImportSettings {
  double fps_override = 0.0;     // > 0: sample at this rate instead of the keys'
  bool fold_static_root = true;  // the hips as joint 0 below a static root
  std::optional<UpAxis> up_axis;  // nullopt: chosen from the figure's shape
  std::string base_dir;          // where a .gltf's external buffers are (its folder)
  double max_joint_poses = 5e7;  // frames x joints over all the file's animations (1.6 GB of rotations)

  Status validate() const;
};

// The file's bytes (binary .glb, or a .gltf's JSON text); `file_name` for messages. One clip per
// animation, in the file's order, named as the animation ("animation_N" without a name).
Result<std::vector<Clip>> clips_from_gltf(std::string_view bytes, const std::string& file_name,
                                          const GltfImportSettings& settings);

// The names clips_from_gltf gives the file's animations, without reading them.
Result<std::vector<std::string>> gltf_animation_names(std::string_view bytes, const std::string& file_name,
                                                      const std::string& base_dir = "");

}  // namespace mg
