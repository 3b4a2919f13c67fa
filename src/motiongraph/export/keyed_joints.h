// What the scene writers (glTF, FBX) share about a skeleton written as a node hierarchy with
// animations: the animations they take, the rest pose its nodes hold, joint 0 below the static
// ancestors a trajectory joint was found under (skeleton.h), and which joints the animations key.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"

namespace mg {

// A motion to write as a named animation (glTF) or animation stack (FBX).
struct ExportAnimation {
  std::string name;  // not empty; names that repeat get "_2", "_3"...
  const Motion* motion = nullptr;
};

// Those of the animations with frames, after checking that each has a name and a motion that fits
// the skeleton (`format` names the file's format in the messages).
Result<std::vector<const ExportAnimation*>> played_animations(const Skeleton& skeleton,
                                                              std::span<const ExportAnimation> animations,
                                                              const char* format);

// The node's translation at rest (metres, its parent node's frame): the rest offset, or for a
// joint with animated translation the first animation's first frame's (`first` null: none); a
// travelling root stands over the origin at that frame's height, re-expressed below the static
// ancestors.
Vec3 rest_node_translation(const Skeleton& skeleton, const Motion* first, int joint);

// Every node's world transform at rest (metres): the static ancestors' (root first), then the
// joints', each joint resting unturned at rest_node_translation.
std::vector<Eigen::Affine3d> rest_transforms(const Skeleton& skeleton, const Motion* first);

// Joint 0's transform in the file's hierarchy, below the static ancestors, from its transform
// here (where they are composed in).
Vec3 below_static_ancestors(const Skeleton& skeleton, const Vec3& translation);
Quat below_static_ancestors(const Skeleton& skeleton, const Quat& rotation);

struct KeyedJoints {
  std::vector<int> turned;  // joints any motion turns (and joint 0 below static ancestors)
  std::vector<int> moved;   // translated joints any motion moves from rest (and a travelling root)
};
// The joints that need keys so that each motion poses the whole figure whichever played before.
KeyedJoints keyed_joints(const Skeleton& skeleton, std::span<const Motion* const> motions);

}  // namespace mg
