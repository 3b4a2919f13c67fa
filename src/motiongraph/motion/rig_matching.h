// Clips of rigs that are the library's first rig under other names, or in another rest pose,
// read as that rig's clips, so that one database can hold them: synthesis plays every clip's
// local rotations on one skeleton, which needs the same joints and the same rest pose.
//
// CMU's capture comes converted to BVH by several tools, each with its own joint names (hip,
// lfemur / Hips, LeftUpLeg / Hips, LeftHip) on the same hierarchy, and some with another rest
// pose (the arms down instead of out). A library of such files is read on the first file's
// names, matched by place in the hierarchy; a clip whose rest pose differs is re-expressed on
// the first's rest pose, its world positions unchanged.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "motiongraph/motion/motion.h"

namespace mg {

enum class JointSide { kNone, kLeft, kRight };

// The side a joint's name says: "left"/"right" anywhere, an l or r standing alone between
// separators (thigh.L, Bip01 R Calf, hand_l, hand.L.001), or starting the name before a capital
// that starts a word (LHipJoint, rCollar; not ROOT) or before a limb word (lfemur, rhumerus).
// kNone otherwise.
JointSide joint_side(std::string_view name);

// Why `other` is not `reference`'s hierarchy under other names (nullopt when it is): both must
// have as many joints, each with the same parent index (end sites where the other has them),
// and no joint named for one side may stand where the other names the opposite side.
std::optional<std::string> hierarchy_mismatch(const Skeleton& reference, const Skeleton& other);

// Why `other` is not the same rig as `reference` (nullopt when it is), so that one file can hold
// both's motion on one skeleton: the same hierarchy (hierarchy_mismatch) with the same names and
// position channels, every offset that no channel animates (the bones) within 0.1 mm, and the
// same static ancestors (within 5 mm and about 1 degree: the fold keeps a clip's first frame).
std::optional<std::string> rig_difference(const Skeleton& reference, const Skeleton& other);

// The clip with its joints named as `reference`'s (the same hierarchy: hierarchy_mismatch is
// nullopt); nothing moves.
Clip renamed_as(const Clip& clip, const Skeleton& reference);

// The largest angle between a bone's rest direction in the two skeletons (the same joints, by
// index), over bones at least 1 cm long in both; `bone` names the joint that bone ends at.
struct RestPoseDifference {
  double angle_deg = 0.0;
  std::string bone;
};
RestPoseDifference rest_pose_difference(const Skeleton& reference, const Skeleton& other);

// Bones further than this from the reference's rest direction make a clip re-expressed on the
// reference's rest pose. CMU's subjects differ by up to 16 degrees (the arms), converters that
// hang the arms down by 90.
inline constexpr double kRestPoseRetargetDeg = 30.0;

// The clip re-expressed on `reference`'s rest pose (the same joints, by index): each joint's
// frame turned by the rotation that takes the reference's rest direction of its bone to the
// clip's (the least turn from its parent's; inherited where a joint has no single bone of 1 cm
// or more), its offsets and local rotations changed to match. Every joint's world position is
// unchanged in every frame; single-child bones then rest in the reference's directions.
Clip on_rest_pose_of(const Clip& clip, const Skeleton& reference);

}  // namespace mg
