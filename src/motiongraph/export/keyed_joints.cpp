#include "motiongraph/export/keyed_joints.h"

#include <fmt/format.h>

namespace mg {

Result<std::vector<const ExportAnimation*>> played_animations(const Skeleton& skeleton,
                                                              std::span<const ExportAnimation> animations,
                                                              const char* format) {
  std::vector<const ExportAnimation*> played;
  for (const ExportAnimation& a : animations) {
    if (a.name.empty()) return Error{"", 0, fmt::format("every {} animation needs a name", format)};
    if (!a.motion) return Error{"", 0, fmt::format("{} animation '{}' has no motion", format, a.name)};
    if (auto s = check_fits(skeleton, *a.motion); !s) {
      return Error{"", 0, fmt::format("animation '{}': {}", a.name, s.error().message)};
    }
    if (a.motion->frame_count > 0) played.push_back(&a);
  }
  return played;
}

namespace {

// The joint's translation from its parent at rest: the first motion's first frame's where it is
// animated, else its offset.
Vec3 rest_translation(const Skeleton& skeleton, const Motion* first, int joint) {
  const int slot = skeleton.translation_slot(joint);
  return slot >= 0 && first && first->frame_count > 0 ? first->translations(0)[slot]
                                                      : skeleton.joint(joint).rest_offset_m;
}

}  // namespace

Vec3 rest_node_translation(const Skeleton& skeleton, const Motion* first, int joint) {
  const int slot = skeleton.translation_slot(joint);
  Vec3 translation = rest_translation(skeleton, first, joint);
  if (joint != 0) return translation;
  // A travelling root stands over the origin at rest, at its first frame's height (its track
  // moves it); a root without position channels stays at its offset.
  if (slot >= 0) translation = Vec3(0.0, translation.y(), 0.0);
  return below_static_ancestors(skeleton, translation);
}

std::vector<Eigen::Affine3d> rest_transforms(const Skeleton& skeleton, const Motion* first) {
  std::vector<Eigen::Affine3d> out;
  Eigen::Affine3d above = Eigen::Affine3d::Identity();
  for (const StaticAncestor& a : skeleton.static_ancestors()) {
    above = above * Eigen::Translation3d(a.translation_m) * a.rotation;
    out.push_back(above);
  }
  const size_t first_joint = out.size();
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    const Eigen::Affine3d& parent = j == 0 ? above : out[first_joint + static_cast<size_t>(skeleton.parent(j))];
    out.push_back(parent * Eigen::Translation3d(rest_node_translation(skeleton, first, j)));
  }
  return out;
}

Vec3 below_static_ancestors(const Skeleton& skeleton, const Vec3& translation) {
  return skeleton.static_ancestor_rotation().conjugate() * (translation - skeleton.static_ancestor_translation_m());
}

Quat below_static_ancestors(const Skeleton& skeleton, const Quat& rotation) {
  return skeleton.static_ancestor_rotation().conjugate() * rotation;
}

KeyedJoints keyed_joints(const Skeleton& skeleton, std::span<const Motion* const> motions) {
  const Motion* first = motions.empty() ? nullptr : motions.front();
  KeyedJoints keyed;
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    if (skeleton.joint(j).end_site) continue;
    // Joint 0 below static ancestors: the node's own rotation does not hold the ancestors'.
    bool turns = j == 0 && !skeleton.static_ancestors().empty();
    for (const Motion* m : motions) {
      for (int f = 0; f < m->frame_count && !turns; ++f) turns = !m->rotations(f)[j].isApprox(Quat::Identity(), 1e-12);
    }
    if (turns) keyed.turned.push_back(j);
  }
  for (int j : skeleton.translated_joints()) {
    const int slot = skeleton.translation_slot(j);
    const Vec3 rest = rest_translation(skeleton, first, j);
    bool moves = j == 0;
    for (const Motion* m : motions) {
      for (int f = 0; f < m->frame_count && !moves; ++f) moves = m->translations(f)[slot] != rest;
    }
    if (moves) keyed.moved.push_back(j);
  }
  return keyed;
}

}  // namespace mg
