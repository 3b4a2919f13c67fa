// The trajectory joint: the joint that carries a character's floor position and heading.
// Usually the root. Some rigs put a static root above the moving hips (a root joint at the
// origin with the whole capture below it, e.g. Bandai Namco Research's motion datasets); then
// the root never travels, and centring, floor alignment and path following, which all follow
// joint 0, would follow a point that does not move.
//
// fold_static_root makes the hips joint 0 in that case: the joints above it (the root, and any
// single-child joints between) are removed from the skeleton and kept on it as its
// static_ancestors; joint 0's local transform becomes its world transform (ancestors composed
// in, frame by frame), so every world position is unchanged and the rest of the pipeline needs
// no change. The BVH writer writes the ancestors back, so a file keeps its hierarchy.
//
// When: the joints from the root down to the trajectory joint form a chain (one child each),
// the trajectory joint is the first joint below the root with animated translation, and over
// the clip the chain's local translations stay within `tolerance` (and its rotations within
// 0.5 degrees) while the trajectory joint's world position moves further than `tolerance`.
// Also when the root travels (by 50 tolerances) without ever turning (its rotation within 0.5
// degrees of its first frame's): an engine's root motion that carries the translation alone,
// whose rotation says nothing of where the body faces. Then the root's child above both ankles
// (found by name) is the trajectory joint, and joints hanging off the root beside it (an
// engine's IK targets) are dropped (Clip::dropped_at_fold). Not where the legs part at the
// root itself.
// Lengths in the clip's units (file units at import: the tolerance is relative to the figure).
#pragma once

#include <optional>
#include <span>

#include "motiongraph/motion/motion.h"

namespace mg {

// The joint that would become joint 0 (nullopt when the root itself is the trajectory joint).
std::optional<int> find_trajectory_joint(const Skeleton& skeleton, const Motion& motion, double tolerance);

// The clip with `trajectory_joint` (from find_trajectory_joint, or any joint below the root)
// as joint 0, with animated translation, as above; the joints hanging off its ancestors beside
// it are dropped (Clip::dropped_at_fold). Each ancestor keeps its first frame's transform, but a
// travelling one (a root carrying root motion) is kept at the origin, so that every clip of its
// rig has one hierarchy to write. `write_back`, when given, are the ancestors kept instead (only
// written back: every joint stays where it was whichever are kept).
Clip fold_static_root(const Clip& clip, int trajectory_joint,
                      std::optional<std::span<const StaticAncestor>> write_back = std::nullopt);

// The clip folded as `folded` (a clip of the same rig) is: when the joints above the one named
// as folded's joint 0 (after the clip's own static ancestors) are the ones `folded` has as
// static ancestors and it did not fold (a held pose, whose hips never travel), it is folded
// above that joint, with folded's ancestors, so that the two share a skeleton; otherwise the
// clip as it is.
Clip fold_as(const Clip& clip, const Skeleton& folded);

// The inverse: the skeleton's static ancestors as joints again (the root first, each with its
// constant transform; the root with animated translation), joint 0 below them with its local
// transform in the file's hierarchy. Returns the clip unchanged when there are none.
Clip unfold_static_root(const Clip& clip);

// The fraction of the figure's size (length_unit.h) under which a root counts as static:
// 0.002, about 3 mm on a 1.7 m figure.
constexpr double kStaticRootFraction = 0.002;

}  // namespace mg
