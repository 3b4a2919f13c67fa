#include "motiongraph/motion/root_motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "motiongraph/core/quantile.h"
#include "motiongraph/core/unique_name.h"
#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

namespace {

// The value at `f` of the least-squares line through values[first..last] (a centred window's
// mean; near the ends, where the window is cut, the line's value, so that steady motion stays
// where it is).
double local_line(const std::vector<double>& values, int f, int first, int last) {
  double n = 0.0, st = 0.0, stt = 0.0, sy = 0.0, sty = 0.0;
  for (int i = first; i <= last; ++i) {
    const double t = i - f;
    n += 1.0, st += t, stt += t * t, sy += values[i], sty += t * values[i];
  }
  const double det = n * stt - st * st;
  return det > 1e-12 ? (stt * sy - st * sty) / det : sy / n;
}

// Horizontal extent of a joint's path: the largest distance on the floor from its first frame.
double floor_reach(const std::vector<Vec3>& positions, int joints, int joint, int frames) {
  double reach = 0.0;
  const Vec3& first = positions[joint];
  for (int f = 1; f < frames; ++f) {
    const Vec3 d = positions[static_cast<size_t>(f) * joints + joint] - first;
    reach = std::max(reach, std::hypot(d.x(), d.z()));
  }
  return reach;
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
  if (auto s = check_fits(skeleton, motion); !s) return s.error();
  if (skeleton.translation_slot(0) != 0) {
    return Error{"", 0, fmt::format("root motion needs the root joint '{}' to carry the travel, but it has no position "
                                    "channels", skeleton.joint(0).name)};
  }
  const int frames = motion.frame_count;
  const int joints = skeleton.joint_count();
  const std::vector<Vec3> world = world_positions(skeleton, motion);
  // A root that stands while a joint below it with position channels travels (a fixed root the
  // import did not fold away) would give a root-motion joint that stands still: say so instead.
  // (Joints without position channels only swing about it: an arm waving over a standing root.)
  if (frames > 1 && floor_reach(world, joints, 0, frames) < 0.01) {
    for (int j : skeleton.translated_joints()) {
      if (j == 0) continue;
      const double reach = floor_reach(world, joints, j, frames);
      if (reach > 0.5) {
        return Error{"", 0, fmt::format("the root joint '{}' does not travel but '{}' below it goes {:.2f} m: root "
                                        "motion needs the joint that carries the travel at the root",
                                        skeleton.joint(0).name, skeleton.joint(j).name, reach)};
      }
    }
  }
  // The floor: the lowest joint's height, its 5th percentile over the frames (a jump's flight
  // and a glitch or two left out).
  std::vector<double> lowest(static_cast<size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    double y = world[static_cast<size_t>(f) * joints].y();
    for (int j = 1; j < joints; ++j) y = std::min(y, world[static_cast<size_t>(f) * joints + j].y());
    lowest[f] = y;
  }
  const double floor_y = quantile(lowest, 0.05);

  // The hips' floor position and heading (yaw of the facing, unwrapped) per frame; a frame facing
  // straight up or down keeps the heading before it (or after it, at the start).
  std::vector<double> xs(static_cast<size_t>(frames)), zs(static_cast<size_t>(frames)), yaws(static_cast<size_t>(frames));
  std::vector<char> known(static_cast<size_t>(frames), 0);
  for (int f = 0; f < frames; ++f) {
    const Vec3& hips = motion.translations(f)[0];
    xs[f] = hips.x(), zs[f] = hips.z();
    const Vec3 facing = motion.rotations(f)[0] * forward_axis;
    if (std::hypot(facing.x(), facing.z()) > 1e-9) yaws[f] = std::atan2(facing.x(), facing.z()), known[f] = 1;
  }
  for (int f = 1; f < frames; ++f) {
    if (!known[f] && known[f - 1]) yaws[f] = yaws[f - 1], known[f] = 1;
  }
  for (int f = frames - 2; f >= 0; --f) {
    if (!known[f] && known[f + 1]) yaws[f] = yaws[f + 1], known[f] = 1;
  }
  for (int f = 1; f < frames; ++f) {
    yaws[f] = yaws[f - 1] + std::remainder(yaws[f] - yaws[f - 1], 2.0 * std::numbers::pi);
  }
  // Local lines over at most `half` frames each side.
  const double half_frames = settings.smoothing_s * motion.fps / 2.0;
  const int half = half_frames >= frames ? frames : static_cast<int>(std::lround(half_frames));
  const auto smooth = [&](const std::vector<double>& values, int f) {
    return half > 0 ? local_line(values, f, std::max(0, f - half), std::min(frames - 1, f + half)) : values[f];
  };

  // The skeleton: the new joint, then every joint one index further on. A rig's fixed root above
  // the hips gives the new joint its name and place; the fixed joints above that one stay above.
  std::vector<JointDef> new_joints;
  JointDef top;
  const auto ancestors = skeleton.static_ancestors();
  top.name = ancestors.empty()
                 ? unique_name(settings.joint_name, [&](const std::string& n) { return skeleton.find(n).has_value(); })
                 : ancestors.back().name;
  top.animated_translation = true;
  top.euler_order = ancestors.empty() ? skeleton.joint(0).euler_order : ancestors.back().euler_order;
  new_joints.push_back(top);
  for (const JointDef& joint : skeleton.joints()) {
    JointDef moved = joint;
    moved.parent = joint.parent + 1;  // the old root (-1) hangs below the new joint (0)
    new_joints.push_back(std::move(moved));
  }
  std::vector<StaticAncestor> above(ancestors.begin(), ancestors.empty() ? ancestors.end() : ancestors.end() - 1);
  RootMotionClip out{Skeleton(std::move(new_joints), std::move(above)), Motion()};
  out.motion = Motion(out.skeleton, frames, motion.fps);
  const int slot_of_old = out.skeleton.translation_slot(1);
  for (int f = 0; f < frames; ++f) {
    const Vec3 ground(smooth(xs, f), floor_y, smooth(zs, f));
    const Quat turn(Eigen::AngleAxisd(smooth(yaws, f), Vec3::UnitY()));  // +z turned onto the facing
    const auto from = motion.rotations(f);
    const auto to = out.motion.rotations(f);
    to[0] = turn;
    to[1] = turn.conjugate() * from[0];
    std::copy(from.begin() + 1, from.end(), to.begin() + 2);
    const auto from_t = motion.translations(f);
    const auto to_t = out.motion.translations(f);
    to_t[0] = ground;
    to_t[slot_of_old] = turn.conjugate() * (from_t[0] - ground);
    for (int j : skeleton.translated_joints()) {
      if (j != 0) to_t[out.skeleton.translation_slot(j + 1)] = from_t[skeleton.translation_slot(j)];
    }
  }
  return out;
}

}  // namespace mg
