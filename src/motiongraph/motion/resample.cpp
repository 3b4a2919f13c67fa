#include "motiongraph/motion/resample.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace mg {

double resampled_frame_count(const Motion& motion, double fps_out) {
  if (motion.frame_count == 0 || fps_out == motion.fps) return motion.frame_count;
  // A tiny epsilon keeps exact multiples (120 -> 30 fps, 4 source frames per output frame)
  // from losing their last frame to rounding.
  return std::floor(motion.duration_s() * fps_out + 1e-9) + 1.0;
}

Result<Motion> resample(const Motion& motion, double fps_out) {
  if (!(fps_out > 0.0) || !std::isfinite(fps_out)) {
    return Error{"", 0, fmt::format("frame rate {} must be positive", fps_out)};
  }
  if (motion.frame_count == 0 || fps_out == motion.fps) {
    Motion same = motion;
    same.fps = fps_out;
    return same;
  }
  const double frames_out = resampled_frame_count(motion, fps_out);
  const double poses = frames_out * std::max(1, motion.joint_count);
  if (frames_out > 1e8 || poses > kMaxJointPoses) {
    return Error{"", 0,
                 fmt::format("resampled to {:g} fps the motion would have {:g} frames of {} joints, over the {:g} "
                             "million joint poses a clip may hold",
                             fps_out, frames_out, motion.joint_count, kMaxJointPoses / 1e6)};
  }
  Motion out = motion;
  out.fps = fps_out;
  out.frame_count = static_cast<int>(frames_out);
  out.local_rotations.resize(static_cast<size_t>(out.frame_count) * motion.joint_count);
  out.local_translations_m.resize(static_cast<size_t>(out.frame_count) * motion.translated_count);
  for (int i = 0; i < out.frame_count; ++i) {
    const double source = i * motion.fps / fps_out;
    const int a = std::min(static_cast<int>(std::floor(source)), motion.frame_count - 1);
    const int b = std::min(a + 1, motion.frame_count - 1);
    const double t = std::clamp(source - a, 0.0, 1.0);
    auto ra = motion.rotations(a);
    auto rb = motion.rotations(b);
    auto ro = out.rotations(i);
    for (int j = 0; j < motion.joint_count; ++j) ro[j] = ra[j].slerp(t, rb[j]).normalized();
    auto ta = motion.translations(a);
    auto tb = motion.translations(b);
    auto to = out.translations(i);
    for (int k = 0; k < motion.translated_count; ++k) to[k] = ta[k] + t * (tb[k] - ta[k]);
  }
  return out;
}

}  // namespace mg
