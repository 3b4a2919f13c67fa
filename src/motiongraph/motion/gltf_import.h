// glTF 2.0 (.glb, or .gltf with its buffers) -> Skeleton + Motion: one clip per animation of
// the file, on one skeleton.
//
// The file becomes a scene of nodes (scene_clips.h, which makes the clips: the skeleton from the
// skins, nodes above composed in, rests re-expressed, keys sampled, a static root folded). glTF's
// lengths are metres and its up axis +y. Images are not decoded; morph weights are not read: the
// project reads rigid skeletons. Samplers: LINEAR, STEP, CUBICSPLINE.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/motion/scene_clips.h"

namespace mg {

struct GltfImportSettings : SceneClipSettings {
  std::string base_dir;  // where a .gltf's external buffers are (its folder)
};

// The file's bytes (binary .glb, or a .gltf's JSON text); `file_name` for messages. One clip per
// animation, in the file's order, named as the animation ("animation_N" without a name).
Result<std::vector<Clip>> clips_from_gltf(std::string_view bytes, const std::string& file_name,
                                          const GltfImportSettings& settings);

// The names clips_from_gltf gives the file's animations, without reading them.
Result<std::vector<std::string>> gltf_animation_names(std::string_view bytes, const std::string& file_name,
                                                      const std::string& base_dir = "");

}  // namespace mg
