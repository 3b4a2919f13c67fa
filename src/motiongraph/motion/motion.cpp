#include "motiongraph/motion/motion.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <fmt/format.h>

namespace mg {

Motion::Motion(const Skeleton& skeleton, int frames, double frames_per_second)
    : fps(frames_per_second),
      frame_count(frames),
      joint_count(skeleton.joint_count()),
      translated_count(static_cast<int>(skeleton.translated_joints().size())),
      local_rotations(static_cast<size_t>(frames) * skeleton.joint_count(), Quat::Identity()),
      local_translations_m(static_cast<size_t>(frames) * skeleton.translated_joints().size(), Vec3::Zero()) {}

Motion::Motion(const Skeleton& skeleton, int frames, double frames_per_second, std::pmr::memory_resource* memory)
    : fps(frames_per_second),
      frame_count(frames),
      joint_count(skeleton.joint_count()),
      translated_count(static_cast<int>(skeleton.translated_joints().size())),
      local_rotations(memory),
      local_translations_m(memory) {
  // Quat and Vec3 leave their values unset when made: resize() allocates without writing.
  local_rotations.resize(static_cast<size_t>(frames) * skeleton.joint_count());
  local_translations_m.resize(static_cast<size_t>(frames) * skeleton.translated_joints().size());
}

Status check_fits(const Skeleton& skeleton, const Motion& motion) {
  const size_t frames = static_cast<size_t>(std::max(motion.frame_count, 0));
  if (motion.joint_count != skeleton.joint_count() ||
      motion.translated_count != static_cast<int>(skeleton.translated_joints().size()) ||
      motion.local_rotations.size() != frames * static_cast<size_t>(skeleton.joint_count()) ||
      motion.local_translations_m.size() != frames * skeleton.translated_joints().size()) {
    return Error{"", 0, "the motion does not fit its skeleton (joint or translation counts differ)"};
  }
  if (!(motion.fps > 0.0) || !std::isfinite(motion.fps)) {
    return Error{"", 0, fmt::format("the motion's frame rate {} is not a positive number", motion.fps)};
  }
  return Ok{};
}

Motion Motion::slice(int first, int count) const {
  assert(first >= 0 && count >= 0 && first + count <= frame_count);
  Motion out = *this;
  out.frame_count = count;
  out.local_rotations.assign(local_rotations.begin() + static_cast<ptrdiff_t>(first) * joint_count,
                             local_rotations.begin() + static_cast<ptrdiff_t>(first + count) * joint_count);
  out.local_translations_m.assign(
      local_translations_m.begin() + static_cast<ptrdiff_t>(first) * translated_count,
      local_translations_m.begin() + static_cast<ptrdiff_t>(first + count) * translated_count);
  return out;
}

}  // namespace mg
