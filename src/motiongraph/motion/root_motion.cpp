#include "motiongraph/motion/root_motion.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

namespace mg {

namespace {

// The unit facing on the floor (x, z) of a root rotation, or nullopt-like (0, 0) when the forward
// axis points up or down.
Eigen::Vector2d floor_facing(const Quat& rotation, const Vec3& forward_axis) {
  const Vec3 f = rotation * forward_axis;
  const Eigen::Vector2d d(f.x(), f.z());
  return d.norm() > 1e-9 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d(Eigen::Vector2d::Zero());
}

std::string unique_name(const Skeleton& skeleton, const std::string& wanted) {
  std::string name = wanted;
  for (int n = 2; skeleton.find(name); ++n) name = fmt::format("{}_{}", wanted, n);
  return name;
}

}  // namespace

Status RootMotionSettings::validate() const {
  if (joint_name.empty()) return Error{"", 0, "the root-motion joint needs a name"};
  if (!(smoothing_s >= 0.0) || !std::isfinite(smoothing_s)) {
    return Error{"", 0, fmt::format("root-motion smoothing must be 0 or more seconds, not {}", smoothing_s)};
  }
  return Ok{};
}

Result<RootMotionClip> add_root_motion(const Skeleton& skeleton, const Motion& motion, const Vec3& forward_axis,
                                       const RootMotionSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  if (motion.joint_count != skeleton.joint_count() || skeleton.translation_slot(0) != 0) {
    return Error{"", 0, "root motion needs a motion on its skeleton whose root joint travels"};
  }
  const int frames = motion.frame_count;
  // The hips' floor position and facing per frame; a frame facing straight up or down keeps the
  // facing before it (or after it, at the start).
  std::vector<Vec3> ground(static_cast<size_t>(frames));
  std::vector<Eigen::Vector2d> facing(static_cast<size_t>(frames), Eigen::Vector2d::Zero());
  for (int f = 0; f < frames; ++f) {
    const Vec3& hips = motion.translations(f)[0];
    ground[f] = Vec3(hips.x(), 0.0, hips.z());
    facing[f] = floor_facing(motion.rotations(f)[0], forward_axis);
    if (facing[f].isZero() && f > 0) facing[f] = facing[f - 1];
  }
  for (int f = frames - 2; f >= 0; --f) {
    if (facing[f].isZero()) facing[f] = facing[f + 1];
  }
  // Centred means over at most `half` frames each side, as many each side near the ends (a
  // lopsided window there would put the joint ahead of the hips at the start, behind at the end).
  const int half = static_cast<int>(std::lround(settings.smoothing_s * motion.fps / 2.0));
  std::vector<Vec3> smooth_ground = ground;
  std::vector<Eigen::Vector2d> smooth_facing = facing;
  if (half > 0) {
    for (int f = 0; f < frames; ++f) {
      const int reach = std::min({half, f, frames - 1 - f});
      const int first = f - reach, last = f + reach;
      Vec3 g = Vec3::Zero();
      Eigen::Vector2d h = Eigen::Vector2d::Zero();
      for (int i = first; i <= last; ++i) g += ground[i], h += facing[i];
      smooth_ground[f] = g / (last - first + 1);
      // Facings that cancel out (a half turn within the window) keep the frame's own.
      smooth_facing[f] = h.norm() > 1e-6 ? Eigen::Vector2d(h.normalized()) : facing[f];
    }
  }

  // The skeleton: the new joint, then every joint one index further on.
  std::vector<JointDef> joints;
  JointDef top;
  const auto ancestors = skeleton.static_ancestors();
  top.name = ancestors.empty() ? unique_name(skeleton, settings.joint_name) : ancestors.front().name;
  top.animated_translation = true;
  top.euler_order = skeleton.joint(0).euler_order;
  joints.push_back(top);
  for (const JointDef& joint : skeleton.joints()) {
    JointDef moved = joint;
    moved.parent = joint.parent + 1;  // the old root (-1) hangs below the new joint (0)
    joints.push_back(std::move(moved));
  }
  RootMotionClip out{Skeleton(std::move(joints)), Motion()};
  out.motion = Motion(out.skeleton, frames, motion.fps);
  const int slot_of_old = out.skeleton.translation_slot(1);
  for (int f = 0; f < frames; ++f) {
    const double yaw = std::atan2(smooth_facing[f].x(), smooth_facing[f].y());  // +z turned onto the facing
    const Quat turn(Eigen::AngleAxisd(yaw, Vec3::UnitY()));
    const auto from = motion.rotations(f);
    const auto to = out.motion.rotations(f);
    to[0] = turn;
    to[1] = turn.conjugate() * from[0];
    std::copy(from.begin() + 1, from.end(), to.begin() + 2);
    const auto from_t = motion.translations(f);
    const auto to_t = out.motion.translations(f);
    to_t[0] = smooth_ground[f];
    to_t[slot_of_old] = turn.conjugate() * (from_t[0] - smooth_ground[f]);
    for (int j : skeleton.translated_joints()) {
      if (j != 0) to_t[out.skeleton.translation_slot(j + 1)] = from_t[skeleton.translation_slot(j)];
    }
  }
  return out;
}

}  // namespace mg
