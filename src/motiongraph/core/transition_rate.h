// Transitions per second of motion: the rate at which blends come, in a synthesized motion (walk,
// path and steer reports) or in the motion a graph keeps (the automatic threshold's rate).
#pragma once

namespace mg {

// 0 when there are no frames or no frame rate.
inline double transitions_per_second(int transitions, long long frames, double fps) {
  return frames > 0 && fps > 0.0 ? transitions / (static_cast<double>(frames) / fps) : 0.0;
}

}  // namespace mg
