#include "motiongraph/skeleton/skeleton.h"

#include <algorithm>
#include <cassert>
#include <functional>

namespace mg {

Skeleton::Skeleton(std::vector<JointDef> joints, std::vector<StaticAncestor> static_ancestors)
    : joints_(std::move(joints)), static_ancestors_(std::move(static_ancestors)) {
  slot_.assign(joints_.size(), -1);
  for (int j = 0; j < joint_count(); ++j) {
    assert((j == 0) == (joints_[j].parent < 0));
    assert(joints_[j].parent < j);
    if (joints_[j].animated_translation) {
      slot_[j] = static_cast<int>(translated_.size());
      translated_.push_back(j);
    }
  }
}

std::optional<int> Skeleton::find(std::string_view name) const {
  for (int j = 0; j < joint_count(); ++j) {
    if (joints_[j].name == name) return j;
  }
  return std::nullopt;
}

Vec3 Skeleton::static_ancestor_translation_m() const {
  Vec3 position = Vec3::Zero();
  Quat rotation = Quat::Identity();
  for (const StaticAncestor& a : static_ancestors_) {
    position += rotation * a.translation_m;
    rotation = rotation * a.rotation;
  }
  return position;
}

Quat Skeleton::static_ancestor_rotation() const {
  Quat rotation = Quat::Identity();
  for (const StaticAncestor& a : static_ancestors_) rotation = rotation * a.rotation;
  return rotation;
}

double Skeleton::leg_length_m() const {
  // Rest pose heights: the root's height above its lowest descendant.
  std::vector<double> height(joints_.size(), 0.0);
  double lowest = 0.0;
  for (int j = 1; j < joint_count(); ++j) {
    height[j] = height[joints_[j].parent] + joints_[j].rest_offset_m.y();
    lowest = std::min(lowest, height[j]);
  }
  return -lowest;
}

}  // namespace mg
