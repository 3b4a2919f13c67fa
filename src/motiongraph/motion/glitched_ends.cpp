// Frames cut off by a capture glitch at a clip's ends.
#include "motiongraph/motion/glitched_ends.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

namespace {

struct Step {
  double largest_m = 0.0;  // of any joint, from frame f to f + 1
  int joint = -1;
};

}  // namespace

GlitchedEnds find_glitched_ends(const Skeleton& skeleton, const Motion& motion) {
  GlitchedEnds out;
  const int frames = motion.frame_count;
  const int joints = skeleton.joint_count();
  if (frames < 4 || joints == 0 || !(motion.fps > 0.0)) return out;
  const int window = std::max(1, static_cast<int>(std::floor(kGlitchEndSeconds * motion.fps)));
  // The steps within a window of either end (each needs its neighbours), FK on those frames only:
  // steps 0..head-2 and tail..frames-2, which meet or overlap in a short clip.
  const int head = std::min(frames, window + 2), tail = std::max(head - 1, frames - window - 2);
  std::vector<Vec3> positions(static_cast<size_t>(joints)), previous(static_cast<size_t>(joints));
  std::vector<Quat> rotations(static_cast<size_t>(joints));
  std::vector<Step> steps(static_cast<size_t>(frames - 1));
  auto measure = [&](int first, int last) {  // the steps from frames first..last-1 to the next
    forward_kinematics(skeleton, motion, first, previous, rotations);
    for (int f = first; f < last; ++f) {
      forward_kinematics(skeleton, motion, f + 1, positions, rotations);
      Step& s = steps[static_cast<size_t>(f)];
      for (int j = 0; j < joints; ++j) {
        const double d = (positions[static_cast<size_t>(j)] - previous[static_cast<size_t>(j)]).norm();
        if (d > s.largest_m) s.largest_m = d, s.joint = j;
      }
      std::swap(positions, previous);
    }
  };
  measure(0, head - 1);
  if (tail < frames) measure(tail, frames - 1);
  auto glitch = [&](int f) {
    const double jump = steps[static_cast<size_t>(f)].largest_m;
    if (jump < kGlitchJumpM || jump * motion.fps < kGlitchSpeedMps) return false;
    const bool calm_before = f == 0 || steps[static_cast<size_t>(f - 1)].largest_m < 0.2 * jump;
    const bool calm_after = f + 1 >= frames - 1 || steps[static_cast<size_t>(f + 1)].largest_m < 0.2 * jump;
    return calm_before && calm_after;
  };
  // Leading: the last glitch among the first `window` steps, two frames left after it.
  for (int f = std::min(window, frames - 3) - 1; f >= 0; --f) {
    if (glitch(f)) {
      out.leading = f + 1;
      out.leading_jump_m = steps[static_cast<size_t>(f)].largest_m;
      out.leading_joint = skeleton.joint(steps[static_cast<size_t>(f)].joint).name;
      break;
    }
  }
  // Trailing: the first glitch among the last `window` steps, after the leading ones.
  for (int f = std::max(out.leading + 1, frames - 1 - window); f < frames - 1; ++f) {
    if (glitch(f)) {
      out.trailing = frames - 1 - f;
      out.trailing_jump_m = steps[static_cast<size_t>(f)].largest_m;
      out.trailing_joint = skeleton.joint(steps[static_cast<size_t>(f)].joint).name;
      break;
    }
  }
  return out;
}

GlitchedEnds drop_glitched_ends(Clip& clip) {
  const GlitchedEnds found = find_glitched_ends(clip.skeleton, clip.motion);
  if (found.leading == 0 && found.trailing == 0) return found;
  clip.motion = clip.motion.slice(found.leading, clip.motion.frame_count - found.leading - found.trailing);
  clip.glitched_leading_frames += found.leading;
  clip.glitched_trailing_frames += found.trailing;
  return found;
}

}  // namespace mg
