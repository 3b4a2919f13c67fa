// Foot contacts: the clip's floor per part (or each joint's resting height, where it rests on the
// lowest ground around or carries the body alone), planted by height and speed with
// hysteresis, short gaps filled, short contacts dropped.
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

// Per frame f, the q-quantile of the values of every series over frames f-half .. f+half
// (shortened at the ends).
std::vector<double> window_quantile(std::span<const std::vector<double>* const> series, int half, double q) {
  const int frames = static_cast<int>(series.front()->size());
  std::vector<double> result(static_cast<size_t>(frames));
  std::vector<double> window;
  for (int f = 0; f < frames; ++f) {
    window.clear();
    const int first = std::max(f - half, 0);
    const int end = std::min(f + half + 1, frames);
    for (const std::vector<double>* values : series) window.insert(window.end(), values->begin() + first, values->begin() + end);
    result[f] = quantile(window, q);
  }
  return result;
}

// Planted by height and speed with hysteresis.
std::vector<uint8_t> hysteresis(std::span<const double> height, std::span<const double> speed,
                                const FootContactSettings& settings) {
  std::vector<uint8_t> planted(height.size(), 0);
  bool on = false;
  for (size_t f = 0; f < height.size(); ++f) {
    on = on ? height[f] <= settings.leave_height_m && speed[f] <= settings.leave_speed_mps
            : height[f] <= settings.enter_height_m && speed[f] <= settings.enter_speed_mps;
    planted[f] = on ? 1 : 0;
  }
  return planted;
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
  if (!(local_window_s >= 0.0) || !std::isfinite(local_window_s)) {
    return Error{"", 0, "the local floor's window must be a finite duration >= 0 s (0: the clip's floor alone)"};
  }
  if (!(local_quantile >= 0.0 && local_quantile <= 0.5)) {
    return Error{"", 0, "the local floor's quantile must be within 0..0.5 (a low quantile of the joint's heights)"};
  }
  if (!(rest_tolerance_m >= 0.0) || !std::isfinite(rest_tolerance_m)) {
    return Error{"", 0, "the resting height's tolerance above the ground around must be a finite height >= 0 m"};
  }
  if (!(max_step_m >= 0.0) || !std::isfinite(max_step_m)) {
    return Error{"", 0, "the highest step a foot carries the body on must be a finite height >= 0 m"};
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

int FootContactSettings::local_window_frames(double fps) const {
  if (local_window_s <= 0.0) return 0;
  return std::max(1, static_cast<int>(std::lround(local_window_s * fps)));
}

bool FootContacts::foot_planted(FootSide side, int frame) const {
  for (const FootContactTrack& track : tracks) {
    if (track.side == side && track.planted[frame]) return true;
  }
  return false;
}

void fill_contact_gaps(std::span<ContactMask> contacts, int max_gap) {
  for (int bit = 0; bit < 8; ++bit) {
    const auto mask = static_cast<ContactMask>(1u << bit);
    long long last_planted = -1;
    for (size_t f = 0; f < contacts.size(); ++f) {
      if ((contacts[f] & mask) == 0) continue;
      const long long gap = static_cast<long long>(f) - last_planted - 1;
      if (last_planted >= 0 && gap > 0 && gap <= max_gap) {
        for (size_t g = static_cast<size_t>(last_planted) + 1; g < f; ++g) contacts[g] |= mask;
      }
      last_planted = static_cast<long long>(f);
    }
  }
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

  // Each joint's heights and speeds.
  const std::vector<Joint> list = foot_joint_list(feet);
  const int half_span = settings.speed_half_span_frames(fps);
  std::vector<std::vector<double>> heights(list.size()), speeds(list.size());
  for (size_t j = 0; j < list.size(); ++j) {
    assert(list[j].joint >= 0 && list[j].joint < joint_count);
    for (int f = 0; f < frames; ++f) {
      heights[j].push_back(world_positions_m[f * joints + list[j].joint].y());
      speeds[j].push_back(joint_speed(world_positions_m, joints, frames, list[j].joint, f, half_span, fps));
    }
  }
  // The joints of each part (both feet's), and the part's floor over the clip.
  auto part_series = [&](FootPart part) {
    std::vector<const std::vector<double>*> series;
    for (size_t j = 0; j < list.size(); ++j) {
      if (list[j].part == part) series.push_back(&heights[j]);
    }
    return series;
  };
  double floor[2] = {0.0, 0.0};
  for (FootPart part : {FootPart::kAnkle, FootPart::kToe}) {
    std::vector<double> pooled;
    for (const std::vector<double>* series : part_series(part)) pooled.insert(pooled.end(), series->begin(), series->end());
    floor[static_cast<int>(part)] = quantile(pooled, settings.floor_quantile);
  }

  // 1. Planted by height (above the clip's floor, or the joint's resting height) and speed, with
  // hysteresis.
  const int local_half = settings.local_window_frames(fps);
  // Per part, the lowest ground around each frame; none for a part on one foot only (a rig with
  // one toe): its own heights are no ground, so it counts by b. alone.
  std::vector<std::vector<double>> ground(2);
  if (local_half > 0) {
    for (FootPart part : {FootPart::kAnkle, FootPart::kToe}) {
      const auto series = part_series(part);
      if (series.size() >= 2) ground[static_cast<int>(part)] = window_quantile(series, local_half, settings.local_quantile);
    }
  }
  std::vector<std::vector<uint8_t>> stance(list.size());  // what 1 gives, before a. and b.
  for (size_t j = 0; j < list.size(); ++j) {
    FootContactTrack track;
    track.joint = list[j].joint;
    track.side = list[j].side;
    track.part = list[j].part;
    track.floor_height_m = floor[static_cast<int>(list[j].part)];
    std::vector<double> height(static_cast<size_t>(frames));
    if (local_half > 0) {
      const std::vector<double>* own[] = {&heights[j]};
      track.rest_height_m = window_quantile(own, local_half, settings.local_quantile);
      for (int f = 0; f < frames; ++f) height[f] = heights[j][f] - track.rest_height_m[f];
    } else {
      for (int f = 0; f < frames; ++f) height[f] = heights[j][f] - track.floor_height_m;
    }
    stance[j] = hysteresis(height, speeds[j], settings);
    track.planted = stance[j];
    contacts.tracks.push_back(std::move(track));
  }

  // a. Resting on the lowest ground around; b. carrying the body alone.
  const int min_frames = settings.min_frames(fps);
  if (local_half > 0) {
    // a. per frame, for the parts with a ground; a part without one takes its own foot's other
    // part's (a one-toe rig's toe its ankle's).
    auto within_step = [&](const FootContactTrack& track, int f) {
      return track.rest_height_m[f] - track.floor_height_m <= settings.max_step_m;
    };
    std::vector<std::vector<uint8_t>> on_ground(list.size());
    for (size_t j = 0; j < list.size(); ++j) {
      const FootContactTrack& track = contacts.tracks[j];
      const std::vector<double>& lowest = ground[static_cast<int>(track.part)];
      if (lowest.empty()) continue;
      on_ground[j].assign(static_cast<size_t>(frames), 0);
      for (int f = 0; f < frames; ++f) {
        on_ground[j][f] = track.rest_height_m[f] - lowest[f] <= settings.rest_tolerance_m && within_step(track, f);
      }
    }
    for (size_t j = 0; j < list.size(); ++j) {
      if (!on_ground[j].empty()) continue;
      // Every foot has an ankle, and both ankles make the ankles' ground.
      for (size_t k = 0; k < list.size(); ++k) {
        if (list[k].side == list[j].side && !on_ground[k].empty()) on_ground[j] = on_ground[k];
      }
      assert(!on_ground[j].empty());
    }
    // Per side, whether that foot (ankle or toe) is in a stance.
    std::vector<uint8_t> at_rest[2];
    for (std::vector<uint8_t>& rest : at_rest) rest.assign(static_cast<size_t>(frames), 0);
    for (size_t k = 0; k < list.size(); ++k) {
      for (int f = 0; f < frames; ++f) at_rest[static_cast<int>(list[k].side)][f] |= stance[k][f];
    }
    for (size_t j = 0; j < list.size(); ++j) {
      FootContactTrack& track = contacts.tracks[j];
      for (int f = 0; f < frames; ++f) track.planted[f] = stance[j][f] && on_ground[j][f];
      // b. a stance with 0.1 s in a row alone, planted where within max_step_m.
      const std::vector<uint8_t>& other = at_rest[track.side == FootSide::kLeft ? 1 : 0];
      for (const ContactInterval& run : contact_intervals(stance[j])) {
        int alone = 0, longest = 0;
        for (int f = run.first_frame; f < run.first_frame + run.frame_count; ++f) {
          alone = !other[f] && within_step(track, f) ? alone + 1 : 0;
          longest = std::max(longest, alone);
        }
        if (longest < min_frames) continue;
        for (int f = run.first_frame; f < run.first_frame + run.frame_count; ++f) {
          if (within_step(track, f)) track.planted[f] = 1;
        }
      }
    }
  }

  // 2. Short gaps filled; 3. short contacts dropped.
  const int max_gap = settings.max_gap_frames(fps);
  for (FootContactTrack& track : contacts.tracks) {
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
  }
  return contacts;
}

Result<FootContacts> detect_foot_contacts(const Skeleton& skeleton, const Motion& motion, const FootJoints& feet,
                                          const FootContactSettings& settings) {
  const std::vector<Vec3> positions = world_positions(skeleton, motion);
  return detect_foot_contacts(positions, skeleton.joint_count(), motion.fps, feet, settings);
}

}  // namespace mg
