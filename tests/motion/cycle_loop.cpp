#include "motion/cycle_loop.h"

#include <stdexcept>

namespace mg::test {

Clip loop_of(const Clip& clip, int first, int period, bool repeat_first) {
  if (first < 0 || period < 2 || first + period >= clip.motion.frame_count) {
    throw std::runtime_error("loop_of: the cycle must lie inside the clip, one frame to spare");
  }
  const Motion& m = clip.motion;
  const int frames = period + (repeat_first ? 1 : 0);
  Clip out = clip;
  out.name = clip.name + "_loop";
  out.motion = Motion(clip.skeleton, frames, m.fps);
  const int root_slot = clip.skeleton.translation_slot(0);
  for (int t = 0; t < frames; ++t) {
    const double u = static_cast<double>(t) / period;
    const auto from = m.rotations(first + t);
    auto to = out.motion.rotations(t);
    for (size_t j = 0; j < from.size(); ++j) {
      // What frame first + period lacks of frame first, made up a little each frame.
      const Quat missing = m.rotations(first + period)[j].conjugate() * m.rotations(first)[j];
      to[j] = (from[j] * Quat::Identity().slerp(u, missing)).normalized();
    }
    const auto translations = m.translations(first + t);
    auto moved = out.motion.translations(t);
    for (size_t i = 0; i < translations.size(); ++i) {
      const Vec3 missing = m.translations(first)[i] - m.translations(first + period)[i];
      moved[i] = translations[i] + u * missing;
      // The root still travels over the floor: only its height is made periodic.
      if (static_cast<int>(i) == root_slot) moved[i] = Vec3(translations[i].x(), moved[i].y(), translations[i].z());
    }
  }
  return out;
}

}  // namespace mg::test
