// Foot contacts: the clip's floor per part, planted by height and speed with hysteresis,
// short gaps filled, short contacts dropped.
#include "motiongraph/motion/foot_contacts.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "motiongraph/core/quantile.h"
#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

namespace {

struct Joint {
  int joint;
  FootSide side;
  FootPart part;
};

std::vector<Joint> foot_joint_list(const FootJoints& feet) {
  std::vector<Joint> joints;
  for (const auto& [foot, side] : {std::pair{feet.left, FootSide::kLeft}, std::pair{feet.right, FootSide::kRight}}) {
    joints.push_back({foot.ankle, side, FootPart::kAnkle});
    if (foot.toe >= 0) joints.push_back({foot.toe, side, FootPart::kToe});
  }
  return joints;
}

// Speed (m/s) of `joint` at `frame`: central difference over +-half frames, shortened at the
// ends.
double joint_speed(std::span<const Vec3> positions, size_t joints, int frames, int joint, int frame, int half,
                   double fps) {
  if (frames < 2) return 0.0;
  const int before = std::max(frame - half, 0);
  const int after = std::min(frame + half, frames - 1);
  const Vec3 step = positions[after * joints + joint] - positions[before * joints + joint];
  return step.norm() * fps / (after - before);
}

}  // namespace

Status FootContactSettings::validate() const {
  if (!(floor_quantile >= 0.0 && floor_quantile <= 0.5)) {
    return Error{"", 0, "the floor quantile must be within 0..0.5 (a low quantile of the foot's heights)"};
  }
  if (!(enter_height_m >= 0.0) || !std::isfinite(enter_height_m)) {
    return Error{"", 0, "the contact height must be a finite height >= 0 m above the floor"};
  }
  if (!(leave_height_m >= enter_height_m) || !std::isfinite(leave_height_m)) {
    return Error{"", 0, "the height a contact ends above must be finite and at least the height it starts within"};
  }
  if (!(enter_speed_mps > 0.0)) return Error{"", 0, "the contact speed must be > 0 m/s (infinity: height alone)"};
  if (!(leave_speed_mps >= enter_speed_mps)) {
    return Error{"", 0, "the speed a contact ends above must be at least the speed it starts below"};
  }
  if (!(speed_span_s > 0.0) || !std::isfinite(speed_span_s)) {
    return Error{"", 0, "the span speeds are measured over must be a finite time > 0 s"};
  }
  if (!(max_gap_s >= 0.0) || !std::isfinite(max_gap_s)) {
    return Error{"", 0, "the longest gap filled between contacts must be a finite duration >= 0 s"};
  }
  if (!(min_duration_s >= 0.0) || !std::isfinite(min_duration_s)) {
    return Error{"", 0, "the shortest contact must be a finite duration >= 0 s"};
  }
  return Ok{};
}

int FootContactSettings::min_frames(double fps) const {
  // A tolerance so that 0.1 s at 30 fps is 3 frames, not 4 by rounding error.
  return std::max(1, static_cast<int>(std::ceil(min_duration_s * fps - 1e-9)));
}

int FootContactSettings::max_gap_frames(double fps) const {
  return std::max(0, static_cast<int>(std::floor(max_gap_s * fps + 1e-9)));
}

int FootContactSettings::speed_half_span_frames(double fps) const {
  return std::max(1, static_cast<int>(std::lround(speed_span_s * fps / 2.0)));
}

bool FootContacts::foot_planted(FootSide side, int frame) const {
  for (const FootContactTrack& track : tracks) {
    if (track.side == side && track.planted[frame]) return true;
  }
  return false;
}

ContactMask contact_mask(const FootContacts& contacts, int frame) {
  ContactMask mask = 0;
  for (const FootContactTrack& track : contacts.tracks) {
    if (track.planted[frame]) mask |= contact_bit(track.side, track.part);
  }
  return mask;
}

std::vector<ContactColumn> contact_columns(const FootJoints& feet) {
  std::vector<ContactColumn> columns;
  for (const auto& [foot, side] : {std::pair{feet.left, FootSide::kLeft}, std::pair{feet.right, FootSide::kRight}}) {
    for (const auto& [joint, part] : {std::pair{foot.ankle, FootPart::kAnkle}, std::pair{foot.toe, FootPart::kToe}}) {
      if (joint >= 0) columns.push_back({joint, contact_bit(side, part)});
    }
  }
  return columns;
}

std::vector<ContactInterval> contact_intervals(std::span<const uint8_t> planted) {
  std::vector<ContactInterval> intervals;
  const int frames = static_cast<int>(planted.size());
  for (int f = 0; f < frames;) {
    if (!planted[f]) {
      ++f;
      continue;
    }
    int end = f;
    while (end < frames && planted[end]) ++end;
    intervals.push_back({f, end - f});
    f = end;
  }
  return intervals;
}

Result<FootContacts> detect_foot_contacts(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                                          const FootJoints& feet, const FootContactSettings& settings) {
  if (auto valid = settings.validate(); !valid) return valid.error();
  if (!(fps > 0.0)) return Error{"", 0, "foot contacts need a frame rate > 0"};
  assert(joint_count > 0 && world_positions_m.size() % static_cast<size_t>(joint_count) == 0);
  const size_t joints = static_cast<size_t>(joint_count);
  const int frames = static_cast<int>(world_positions_m.size() / joints);
  FootContacts contacts;
  contacts.frame_count = frames;

  // The floor of each part, from both feet's heights.
  const std::vector<Joint> list = foot_joint_list(feet);
  for ([[maybe_unused]] const Joint& joint : list) assert(joint.joint >= 0 && joint.joint < joint_count);
  double floor[2] = {0.0, 0.0};
  for (FootPart part : {FootPart::kAnkle, FootPart::kToe}) {
    std::vector<double> heights;
    for (const Joint& joint : list) {
      if (joint.part != part) continue;
      for (int f = 0; f < frames; ++f) heights.push_back(world_positions_m[f * joints + joint.joint].y());
    }
    floor[static_cast<int>(part)] = quantile(heights, settings.floor_quantile);
  }

  // 1. Planted by height and speed, with hysteresis; 2. short gaps filled; 3. short contacts
  // dropped.
  const int half_span = settings.speed_half_span_frames(fps);
  const int max_gap = settings.max_gap_frames(fps);
  const int min_frames = settings.min_frames(fps);
  for (const Joint& joint : list) {
    FootContactTrack track;
    track.joint = joint.joint;
    track.side = joint.side;
    track.part = joint.part;
    track.floor_height_m = floor[static_cast<int>(joint.part)];
    track.planted.assign(static_cast<size_t>(frames), 0);
    bool planted = false;
    for (int f = 0; f < frames; ++f) {
      const double height = world_positions_m[f * joints + joint.joint].y() - track.floor_height_m;
      const double speed = joint_speed(world_positions_m, joints, frames, joint.joint, f, half_span, fps);
      planted = planted ? height <= settings.leave_height_m && speed <= settings.leave_speed_mps
                        : height <= settings.enter_height_m && speed <= settings.enter_speed_mps;
      track.planted[f] = planted ? 1 : 0;
    }
    const auto planted_runs = contact_intervals(track.planted);
    for (size_t i = 1; i < planted_runs.size(); ++i) {
      const int gap_start = planted_runs[i - 1].first_frame + planted_runs[i - 1].frame_count;
      const int gap = planted_runs[i].first_frame - gap_start;
      if (gap <= max_gap) std::fill_n(track.planted.begin() + gap_start, gap, 1);
    }
    for (const ContactInterval& interval : contact_intervals(track.planted)) {
      if (interval.frame_count >= min_frames) continue;
      std::fill_n(track.planted.begin() + interval.first_frame, interval.frame_count, 0);
    }
    contacts.tracks.push_back(std::move(track));
  }
  return contacts;
}

Result<FootContacts> detect_foot_contacts(const Skeleton& skeleton, const Motion& motion, const FootJoints& feet,
                                          const FootContactSettings& settings) {
  const std::vector<Vec3> positions = world_positions(skeleton, motion);
  return detect_foot_contacts(positions, skeleton.joint_count(), motion.fps, feet, settings);
}

}  // namespace mg
