// Clips of skeletons that differ only in some joints (fingers in some files and not in others,
// an extra toe or end site, a prop joint) read on the joints they share, so that one database
// can hold them all. Joints are matched by name (exactly) with the same parent's name.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"

namespace mg {

// The joints every skeleton has, by name with the same parent's name, in the first skeleton's
// order; a joint whose parent is not common is not either, so what is dropped from each
// skeleton is whole subtrees hanging from kept joints. Empty when the roots differ (or no
// skeleton is given).
std::vector<std::string> common_joints(std::span<const Skeleton> skeletons);

// The name of a root that every skeleton has as a joint, when the roots differ, or empty: a
// rig with a root-motion joint above the hips ("root" -> "Hips") beside rigs whose root is
// the hips gives "Hips". When several qualify, the deepest (the one below the others).
std::string shared_root(std::span<const Skeleton> skeletons);

// The clip with the joint named as its root (shared_root's): the joints above it, its chain of
// ancestors, are composed into it frame by frame (so it carries the travel, with animated
// translation), the joints hanging off that chain are dropped (added to Clip::dropped_at_fold),
// and every kept joint moves as before in the world. The joints above are kept to be written
// back only as `above_as` has them as static ancestors (motion/trajectory_joint.h: a skeleton
// of the rig whose travelling clips were folded at import, beside a clip that did not travel);
// without it the clip is the other rigs' from their root down. Fails naming a joint the
// skeleton lacks.
Result<Clip> reroot_at(const Clip& clip, const std::string& root_name, const Skeleton* above_as = nullptr);

// The clip on the joints named (in that order; the first must be its root, and each joint's
// parent must come before it): every kept joint moves as before, in the world too, since only
// subtrees below kept joints are dropped. Fails naming a joint the skeleton lacks or one whose
// parent is not kept.
Result<Clip> keep_joints(const Clip& clip, std::span<const std::string> names);

}  // namespace mg
