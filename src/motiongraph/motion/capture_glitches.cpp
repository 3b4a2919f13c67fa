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
  const auto n = static_cast<size_t>(joints);
  // Frames f - 1, f and f + 1 as the loop reaches step f.
  std::vector<Vec3> positions(n), previous(n), before(n);
  std::vector<Quat> rotations(n);
  forward_kinematics(skeleton, motion, first, previous, rotations);
  for (int f = first; f < last; ++f) {
    forward_kinematics(skeleton, motion, f + 1, positions, rotations);
    JointStep& s = steps[static_cast<size_t>(f)];
    s = JointStep{};
    for (size_t j = 0; j < n; ++j) {
      const double d = (positions[j] - previous[j]).norm();
      if (d > s.largest_m) s.largest_m = d, s.joint = static_cast<int>(j);
    }
    if (f > first) {  // from frame f - 1 to f + 1
      double& over_two = steps[static_cast<size_t>(f - 1)].over_two_m;
      over_two = 0.0;
      for (size_t j = 0; j < n; ++j) over_two = std::max(over_two, (positions[j] - before[j]).norm());
    }
    std::swap(before, previous);
    std::swap(previous, positions);
  }
}

namespace {

// A step of `jump` metres fast enough to be a glitch.
bool glitch_sized(double jump, double fps) { return jump >= kGlitchJumpM && jump * fps >= kGlitchSpeedMps; }

// Steps f and f + 1 step a limb out and back: both at least kGlitchJumpM, whatever the rate (no
// limb swings so far and back within a frame), the steps before and after them calm, and no
// joint at f + 2 further from frame f than two calm steps take it.
bool out_and_back(std::span<const JointStep> steps, int f) {
  const int count = static_cast<int>(steps.size());
  if (f < 0 || f + 1 >= count) return false;
  const double jump = std::min(steps[static_cast<size_t>(f)].largest_m, steps[static_cast<size_t>(f + 1)].largest_m);
  if (jump < kGlitchJumpM) return false;
  const double calm = kGlitchCalmShare * jump;
  return steps[static_cast<size_t>(f)].over_two_m < 2.0 * calm &&
         (f == 0 || steps[static_cast<size_t>(f - 1)].largest_m < calm) &&
         (f + 2 >= count || steps[static_cast<size_t>(f + 2)].largest_m < calm);
}

}  // namespace

bool is_glitch_step(std::span<const JointStep> steps, int f, double fps) {
  if (out_and_back(steps, f) || out_and_back(steps, f - 1)) return true;
  const double jump = steps[static_cast<size_t>(f)].largest_m;
  if (!glitch_sized(jump, fps)) return false;
  const double calm = kGlitchCalmShare * jump;
  const bool calm_before = f == 0 || steps[static_cast<size_t>(f - 1)].largest_m < calm;
  const bool calm_after = f + 1 >= static_cast<int>(steps.size()) || steps[static_cast<size_t>(f + 1)].largest_m < calm;
  return calm_before && calm_after;
}

std::vector<CaptureGlitch> find_capture_glitches(const Skeleton& skeleton, const Motion& motion) {
  std::vector<CaptureGlitch> out;
  const int frames = motion.frame_count;
  if (frames < 4 || skeleton.joint_count() == 0 || !(motion.fps > 0.0)) return out;
  std::vector<JointStep> steps(static_cast<size_t>(frames - 1));
  measure_joint_steps(skeleton, motion, 0, frames - 1, steps);
  for (int f = 0; f + 1 < frames; ++f) {
    if (!is_glitch_step(steps, f, motion.fps)) continue;
    const JointStep& s = steps[static_cast<size_t>(f)];
    out.push_back({f, s.largest_m, skeleton.joint(s.joint).name});
  }
  return out;
}

std::vector<FileGlitch> in_file_frames(std::span<const CaptureGlitch> glitches, int first_file_frame, double fps) {
  std::vector<FileGlitch> out;
  for (const CaptureGlitch& g : glitches) {
    const int before = first_file_frame + g.frame;  // 1-based, so also the 0-based frame it lands on
    out.push_back({before, before / fps, g.joint, g.jump_m});
  }
  return out;
}

std::vector<FileGlitch> in_file_frames(const Clip& clip, std::span<const CaptureGlitch> glitches) {
  return in_file_frames(glitches, clip.dropped_leading_frames + clip.glitched_leading_frames + 1, clip.motion.fps);
}

int GlitchFreeParts::dropped_frames(int frame_count) const {
  int kept = 0;
  for (const auto& [first, count] : parts) kept += count;
  return frame_count - kept;
}

GlitchFreeParts glitch_free_parts(std::span<const CaptureGlitch> glitches, int first, int count, double fps) {
  GlitchFreeParts out;
  for (const CaptureGlitch& g : glitches) {  // the steps within frames first..first + count - 1
    if (g.frame >= first && g.frame + 1 < first + count) out.glitches.push_back({g.frame - first, g.jump_m, g.joint});
  }
  if (out.glitches.empty()) {
    if (count > 0) out.parts.emplace_back(0, count);
    return out;
  }
  // The parts between glitches: frames 0..g1, g1 + 1..g2, ..., gk + 1..count - 1.
  std::vector<std::pair<int, int>> between;
  int start = 0;
  for (const CaptureGlitch& g : out.glitches) {
    between.emplace_back(start, g.frame + 1 - start);
    start = g.frame + 1;
  }
  between.emplace_back(start, count - start);
  const int shortest = std::max(2, static_cast<int>(std::ceil(kGlitchFreeSeconds * fps - 1e-9)));
  for (const auto& part : between) {
    if (part.second >= shortest) out.parts.push_back(part);
  }
  if (out.parts.empty()) {
    // None lasts long enough: the longer of the clip's own ends (the first on a tie), not frames
    // between two glitches; a range's end with a glitch beyond it is between two. With no such
    // end, the longest part.
    const bool glitch_before =
        std::any_of(glitches.begin(), glitches.end(), [&](const CaptureGlitch& g) { return g.frame < first; });
    const bool glitch_after = std::any_of(glitches.begin(), glitches.end(),
                                          [&](const CaptureGlitch& g) { return g.frame + 1 >= first + count; });
    const std::pair<int, int> none{0, 0};
    const auto& head = glitch_before ? none : between.front();
    const auto& tail = glitch_after ? none : between.back();
    auto kept = tail.second > head.second ? tail : head;
    if (kept.second == 0) {
      kept = *std::max_element(between.begin(), between.end(),
                               [](const auto& a, const auto& b) { return a.second < b.second; });
    }
    if (kept.second >= 2) out.parts.push_back(kept);
  }
  return out;
}

GlitchFreeParts glitch_free_parts(const Skeleton& skeleton, const Motion& motion) {
  return glitch_free_parts(find_capture_glitches(skeleton, motion), 0, motion.frame_count, motion.fps);
}

}  // namespace mg
