// The grey stick figure the scene writers (glTF, FBX) skin to a skeleton so that it shows in any
// viewer: an octahedral bone from each joint to each of its children (as Blender draws bones),
// flat-shaded, each bound rigidly to the joint it hangs from but for its tip, bound to the child,
// so that a bone reaches a child whose translation is animated (the hips below a root-motion
// joint, a rig with position channels on every joint).
#pragma once

#include <span>
#include <vector>

#include "motiongraph/motion/motion.h"

namespace mg {

struct StickFigure {
  // Three vertices per triangle, counter-clockwise seen from outside, at rest (world, metres).
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // each vertex its face's
  std::vector<int> joints;    // each vertex's joint (the bone's parent joint; the child for its tip)

  bool empty() const { return positions.empty(); }
};

// The figure over the joints at rest (`rest_world_m`: each joint's world position); no bone
// between a joint and a child closer than 1 mm.
StickFigure stick_figure(const Skeleton& skeleton, std::span<const Vec3> rest_world_m);

}  // namespace mg
