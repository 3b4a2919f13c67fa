// Foot slide: horizontal speeds over planted steps, the largest joint step relative to the root.
#include "motiongraph/evaluation/foot_slide.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "motiongraph/core/quantile.h"
#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

namespace {

// Whether a track is measured: toes, ankles of feet without a toe, all ankles when asked.
bool measured(const FootContacts& contacts, const FootContactTrack& track, bool include_ankles) {
  if (track.part == FootPart::kToe || include_ankles) return true;
  for (const FootContactTrack& other : contacts.tracks) {
    if (other.side == track.side && other.part == FootPart::kToe) return false;
  }
  return true;
}

}  // namespace

FootContactSettings foot_slide_contact_settings() {
  FootContactSettings settings;
  settings.floor_quantile = 0.02;
  settings.enter_height_m = settings.leave_height_m = 0.02;
  settings.enter_speed_mps = settings.leave_speed_mps = std::numeric_limits<double>::infinity();
  settings.max_gap_s = 0.0;
  settings.min_duration_s = 0.0;
  settings.local_window_s = 0.0;
  return settings;
}

Status FootSlideSettings::validate() const {
  if (auto valid = joint_names.validate(); !valid) return valid;
  return contacts.validate();
}

void FootSlideSamples::add(const FootSlideSamples& other) {
  contact_speeds_mps.insert(contact_speeds_mps.end(), other.contact_speeds_mps.begin(),
                            other.contact_speeds_mps.end());
  frame_steps_m.insert(frame_steps_m.end(), other.frame_steps_m.begin(), other.frame_steps_m.end());
}

FootSlide FootSlideSamples::summary() const {
  FootSlide slide;
  slide.contact_steps = static_cast<long long>(contact_speeds_mps.size());
  if (slide.contact_steps > 0) {
    slide.mean_mps = std::accumulate(contact_speeds_mps.begin(), contact_speeds_mps.end(), 0.0) /
                     static_cast<double>(slide.contact_steps);
    slide.p95_mps = quantile(contact_speeds_mps, 0.95);
  }
  if (!frame_steps_m.empty()) {
    slide.max_joint_step_m = *std::max_element(frame_steps_m.begin(), frame_steps_m.end());
    slide.p999_joint_step_m = quantile(frame_steps_m, 0.999);
  }
  return slide;
}

FootSlideSamples foot_slide_samples(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                                    const FootContacts& contacts, bool include_ankles) {
  const size_t joints = static_cast<size_t>(joint_count);
  const int frames = static_cast<int>(world_positions_m.size() / joints);
  FootSlideSamples samples;
  for (const FootContactTrack& track : contacts.tracks) {
    if (!measured(contacts, track, include_ankles)) continue;
    for (int f = 1; f < frames; ++f) {
      if (!track.planted[f - 1] || !track.planted[f]) continue;
      const Vec3 step = world_positions_m[f * joints + track.joint] - world_positions_m[(f - 1) * joints + track.joint];
      samples.contact_speeds_mps.push_back(std::hypot(step.x(), step.z()) * fps);
    }
  }
  for (int f = 1; f < frames; ++f) {
    const Vec3 root_step = world_positions_m[f * joints] - world_positions_m[(f - 1) * joints];
    double most = 0.0;
    for (size_t j = 1; j < joints; ++j) {
      const Vec3 step = world_positions_m[f * joints + j] - world_positions_m[(f - 1) * joints + j] - root_step;
      most = std::max(most, step.norm());
    }
    samples.frame_steps_m.push_back(most);
  }
  return samples;
}

Result<FootSlideSamples> foot_slide_samples(const Skeleton& skeleton, const Motion& motion,
                                            const FootSlideSettings& settings) {
  if (auto valid = settings.validate(); !valid) return valid.error();
  auto feet = find_foot_joints(skeleton, settings.joint_names);
  if (!feet) return feet.error();
  const std::vector<Vec3> positions = world_positions(skeleton, motion);
  auto contacts = detect_foot_contacts(positions, skeleton.joint_count(), motion.fps, *feet, settings.contacts);
  if (!contacts) return contacts.error();
  return foot_slide_samples(positions, skeleton.joint_count(), motion.fps, *contacts, settings.include_ankles);
}

Result<FootSlide> measure_foot_slide(const Skeleton& skeleton, const Motion& motion,
                                     const FootSlideSettings& settings) {
  auto samples = foot_slide_samples(skeleton, motion, settings);
  if (!samples) return samples.error();
  return samples->summary();
}

}  // namespace mg
