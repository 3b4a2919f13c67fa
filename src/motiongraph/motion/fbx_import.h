// FBX (binary or ASCII, as Maya, MotionBuilder, Blender and Mixamo write it) -> Skeleton + Motion:
// one clip per animation stack of the file, on one skeleton. Read by Debian's Open Asset Import
// Library (assimp), which keeps FBX's pivots (pre- and post-rotations, rotation and scaling
// pivots and offsets) as helper nodes above each node; they are composed back into it, at rest
// and at every key of any of them where an animation moves them, so that a joint is one node;
// geometric transforms (a mesh's own) are left out. Assimp's RootNode is no node of the scene:
// the file's top objects are (an armature, a camera, a prop). The file becomes a scene of nodes
// and scene_clips.h makes the clips (the skeleton from the skins' bones, or without a mesh from
// the animated nodes' tree and every node below its root that holds no mesh, camera or light;
// nodes above composed in; rests re-expressed; keys sampled, linearly as assimp reads them; a
// static root folded). An animation that moves a node whose name another node bears is an error
// (assimp names channels by node).
//
// Lengths are the file's unit (FBX's UnitScaleFactor, in centimetres: 1 unless the file says
// otherwise) taken to metres. The file's up axis (its GlobalSettings: +y, +z, -z, +x, ...) is
// turned to +y; `up_axis` instead takes the file as y up (or z, turned). An animation stack named as Blender names them,
// "OBJECT|ACTION" with OBJECT a node of the file, takes the ACTION's name.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/motion/scene_clips.h"

namespace mg {

using FbxImportSettings = SceneClipSettings;

// What the file says of itself: its unit and its up axis.
struct FbxFileFacts {
  double metres_per_unit = 0.01;  // centimetres times UnitScaleFactor
  std::string up_axis = "+y";     // "+y", "+z", "-z", "+x", ...
};

// The file's bytes; `file_name` for messages. One clip per animation stack that moves the
// skeleton, in the file's order; `facts`, when given, gets the file's unit and up axis.
Result<std::vector<Clip>> clips_from_fbx(std::string_view bytes, const std::string& file_name,
                                         const FbxImportSettings& settings, FbxFileFacts* facts = nullptr);

// The names clips_from_fbx gives the file's clips, without sampling them.
Result<std::vector<std::string>> fbx_animation_names(std::string_view bytes, const std::string& file_name);

}  // namespace mg
