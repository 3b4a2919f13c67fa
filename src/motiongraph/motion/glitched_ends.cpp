// Frames cut off by a capture glitch at a clip's ends.
#include "motiongraph/motion/glitched_ends.h"

#include <algorithm>
#include <cmath>
#include <vector>


namespace mg {

GlitchedEnds find_glitched_ends(const Skeleton& skeleton, const Motion& motion) {
  GlitchedEnds out;
  const int frames = motion.frame_count;
  const int joints = skeleton.joint_count();
  if (frames < 4 || joints == 0 || !(motion.fps > 0.0)) return out;
  const int window = std::max(1, static_cast<int>(std::floor(kGlitchEndSeconds * motion.fps)));
  // The steps within a window of either end (each needs the two either side, and the steps over
  // two frames from the one before), FK on those frames only: steps 0..head-2 and tail..frames-2,
  // which overlap by a step in a short clip (measure_joint_steps fills over_two_m from its first
  // frame to its last but one).
  const int head = std::min(frames, window + 3), tail = std::max(head - 2, frames - window - 3);
  std::vector<JointStep> steps(static_cast<size_t>(frames - 1));
  measure_joint_steps(skeleton, motion, 0, head - 1, steps);
  if (tail < frames) measure_joint_steps(skeleton, motion, tail, frames - 1, steps);
  auto glitch = [&](int f) { return is_glitch_step(steps, f, motion.fps); };
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
  // Again on what is left until nothing is found: a second glitch that the first one's cut
  // brings within the new ends' quarter second is cut now, not when the clip is written out and
  // read again (reading is then the same on its own output).
  GlitchedEnds all;
  for (;;) {
    const GlitchedEnds found = find_glitched_ends(clip.skeleton, clip.motion);
    if (found.leading == 0 && found.trailing == 0) break;
    clip.motion = clip.motion.slice(found.leading, clip.motion.frame_count - found.leading - found.trailing);
    clip.glitched_leading_frames += found.leading;
    clip.glitched_trailing_frames += found.trailing;
    all.leading += found.leading;
    all.trailing += found.trailing;
    if (found.leading > 0 && found.leading_jump_m > all.leading_jump_m) {
      all.leading_jump_m = found.leading_jump_m;
      all.leading_joint = found.leading_joint;
    }
    if (found.trailing > 0 && found.trailing_jump_m > all.trailing_jump_m) {
      all.trailing_jump_m = found.trailing_jump_m;
      all.trailing_joint = found.trailing_joint;
    }
  }
  return all;
}

}  // namespace mg
