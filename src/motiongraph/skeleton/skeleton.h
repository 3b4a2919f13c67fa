// An immutable skeleton: joints as flat arrays stored parent-before-child, so forward
// kinematics is one pass. Lengths are metres, in the parent joint's frame.
//
// Each joint j is placed at  world_j = world_parent * Translate(t_j) * Rotate(L_j)  where t_j
// is the joint's local translation (its rest offset, or per-frame values for joints with
// translation channels) and L_j its local rotation for the frame. The skeleton also keeps the
// file's Euler order per joint, used only to write BVH the way it was read.
//
// Built by SkeletonBuilder (skeleton_builder.h) from parsed ASF or BVH; nothing changes it.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/skeleton/rotation.h"

namespace mg {

struct JointDef {
  std::string name;
  int parent = -1;                        // -1 only for joint 0, the root
  Vec3 rest_offset_m = Vec3::Zero();      // translation from the parent joint, parent frame
  bool end_site = false;                  // a leaf marker without rotation (BVH End Site,
                                          // the end of an ASF leaf bone)
  bool animated_translation = false;      // has per-frame translation (root, BVH position
                                          // channels, ASF translation dofs)
  ComposeOrder euler_order{Axis::kZ, Axis::kY, Axis::kX};  // preferred order for writing
};

// A joint of the file's hierarchy above joint 0 that was folded away because it does not
// move (motion/trajectory_joint.h): a static root with the travelling hips below it. Kept
// only to write the file's hierarchy back; forward kinematics never sees it.
struct StaticAncestor {
  std::string name;
  Vec3 translation_m = Vec3::Zero();      // constant local translation, parent frame
  Quat rotation = Quat::Identity();       // constant local rotation
  bool position_channels = false;         // the file gave it position channels
  ComposeOrder euler_order{Axis::kZ, Axis::kY, Axis::kX};
};

class Skeleton {
 public:
  Skeleton() = default;
  // Checks the invariants (one root at index 0, parents before children, unique non-empty
  // names, finite offsets); nullopt-free by construction through SkeletonBuilder.
  explicit Skeleton(std::vector<JointDef> joints, std::vector<StaticAncestor> static_ancestors = {});

  int joint_count() const { return static_cast<int>(joints_.size()); }
  const JointDef& joint(int index) const { return joints_[index]; }
  std::span<const JointDef> joints() const { return joints_; }
  int parent(int index) const { return joints_[index].parent; }
  std::optional<int> find(std::string_view name) const;

  // Joints with per-frame translation, in joint order; slot i of a frame's translations
  // belongs to translated_joints()[i]. translation_slot(j) is -1 for the others.
  std::span<const int> translated_joints() const { return translated_; }
  int translation_slot(int joint) const { return slot_[joint]; }

  // The static joints the file had above joint 0, root first (empty unless joint 0 is a
  // trajectory joint, motion/trajectory_joint.h). Joint 0's local transform in the file is
  // static_ancestor_transform()^-1 times its transform here.
  std::span<const StaticAncestor> static_ancestors() const { return static_ancestors_; }
  // The ancestors' composed transform (identity when there are none).
  Vec3 static_ancestor_translation_m() const;
  Quat static_ancestor_rotation() const;

  // Sum of the bone lengths from the root down to the lowest joint, a size measure (metres).
  double leg_length_m() const;

 private:
  std::vector<JointDef> joints_;
  std::vector<int> translated_;
  std::vector<int> slot_;
  std::vector<StaticAncestor> static_ancestors_;
};

}  // namespace mg
