// Capture glitches anywhere in a clip, and the parts free of them.
#include "motiongraph/motion/capture_glitches.h"

#include <algorithm>
#include <cmath>

#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

void measure_joint_steps(const Skeleton& skeleton, const Motion& motion, int first, int last,
                         std::span<JointStep> steps) {
  const int joints = skeleton.joint_count();
  if (first >= last || joints == 0) return;
  std::vector<Vec3> positions(static_cast<size_t>(joints)), previous(static_cast<size_t>(joints));
  std::vector<Quat> rotations(static_cast<size_t>(joints));
  forward_kinematics(skeleton, motion, first, previous, rotations);
  for (int f = first; f < last; ++f) {
    forward_kinematics(skeleton, motion, f + 1, positions, rotations);
    JointStep& s = steps[static_cast<size_t>(f)];
    s = JointStep{};
    for (int j = 0; j < joints; ++j) {
      const double d = (positions[static_cast<size_t>(j)] - previous[static_cast<size_t>(j)]).norm();
      if (d > s.largest_m) s.largest_m = d, s.joint = j;
    }
    std::swap(positions, previous);
  }
}

bool is_glitch_step(std::span<const JointStep> steps, int f, double fps) {
  const double jump = steps[static_cast<size_t>(f)].largest_m;
  if (jump < kGlitchJumpM || jump * fps < kGlitchSpeedMps) return false;
  const double calm = kGlitchCalmShare * jump;
  const bool calm_before = f == 0 || steps[static_cast<size_t>(f - 1)].largest_m < calm;
  const bool calm_after = f + 1 >= static_cast<int>(steps.size()) || steps[static_cast<size_t>(f + 1)].largest_m < calm;
  return calm_before && calm_after;
}

int GlitchFreeParts::dropped_frames(int frame_count) const {
  int kept = 0;
  for (const auto& [first, count] : parts) kept += count;
  return frame_count - kept;
}

GlitchFreeParts glitch_free_parts(const Skeleton& skeleton, const Motion& motion) {
  GlitchFreeParts out;
  const int frames = motion.frame_count;
  if (frames < 4 || skeleton.joint_count() == 0 || !(motion.fps > 0.0)) {
    if (frames > 0) out.parts.emplace_back(0, frames);
    return out;
  }
  std::vector<JointStep> steps(static_cast<size_t>(frames - 1));
  measure_joint_steps(skeleton, motion, 0, frames - 1, steps);
  for (int f = 0; f + 1 < frames; ++f) {
    if (!is_glitch_step(steps, f, motion.fps)) continue;
    const JointStep& s = steps[static_cast<size_t>(f)];
    out.glitches.push_back({f, s.largest_m, skeleton.joint(s.joint).name});
  }
  if (out.glitches.empty()) {
    out.parts.emplace_back(0, frames);
    return out;
  }
  // The parts between glitches: frames 0..g1, g1 + 1..g2, ..., gk + 1..frames - 1.
  std::vector<std::pair<int, int>> between;
  int start = 0;
  for (const CaptureGlitch& g : out.glitches) {
    between.emplace_back(start, g.frame + 1 - start);
    start = g.frame + 1;
  }
  between.emplace_back(start, frames - start);
  const int shortest = std::max(2, static_cast<int>(std::ceil(kGlitchFreeSeconds * motion.fps - 1e-9)));
  for (const auto& part : between) {
    if (part.second >= shortest) out.parts.push_back(part);
  }
  if (out.parts.empty()) {
    const auto longest = std::max_element(between.begin(), between.end(),
                                          [](const auto& a, const auto& b) { return a.second < b.second; });
    if (longest->second >= 2) out.parts.push_back(*longest);
  }
  return out;
}

}  // namespace mg
