// Clips animated in place, and their travel recovered from the planted feet (in_place.h).
#include "motiongraph/motion/in_place.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "motiongraph/core/quantile.h"
#include "motiongraph/core/text.h"
#include "motiongraph/motion/forward_kinematics.h"

namespace mg {
namespace {

// The foot joints looked at, and per frame interval which of them are low at both ends.
struct FootTrack {
  std::vector<int> joints;            // ankles and toes
  int frames = 0;
  std::vector<unsigned char> low;     // (frames - 1) x joints: low at both ends of the interval
  std::vector<Vec3> step;             // (frames - 1) x joints: floor displacement (y = 0)
  std::vector<unsigned char> ground;  // frames - 1: some joint low
};

FootTrack track_feet(std::span<const Vec3> world, int joint_count, const FootJoints& feet,
                     const InPlaceSettings& settings) {
  FootTrack t;
  for (int j : {feet.left.ankle, feet.left.toe, feet.right.ankle, feet.right.toe}) {
    if (j >= 0 && j < joint_count) t.joints.push_back(j);
  }
  t.frames = joint_count > 0 ? static_cast<int>(world.size() / static_cast<size_t>(joint_count)) : 0;
  const size_t n = t.joints.size();
  if (t.frames < 2 || n == 0) return t;
  const auto at = [&](int f, int j) -> const Vec3& { return world[static_cast<size_t>(f) * joint_count + j]; };
  std::vector<unsigned char> low_at(static_cast<size_t>(t.frames) * n);
  std::vector<double> heights(static_cast<size_t>(t.frames));
  for (size_t k = 0; k < n; ++k) {
    for (int f = 0; f < t.frames; ++f) heights[f] = at(f, t.joints[k]).y();
    const double level = quantile(heights, settings.floor_quantile) + settings.contact_height_m;
    for (int f = 0; f < t.frames; ++f) low_at[static_cast<size_t>(f) * n + k] = heights[f] <= level;
  }
  const int intervals = t.frames - 1;
  t.low.assign(static_cast<size_t>(intervals) * n, 0);
  t.step.assign(static_cast<size_t>(intervals) * n, Vec3::Zero());
  t.ground.assign(static_cast<size_t>(intervals), 0);
  for (int i = 0; i < intervals; ++i) {
    for (size_t k = 0; k < n; ++k) {
      const size_t slot = static_cast<size_t>(i) * n + k;
      t.low[slot] = low_at[static_cast<size_t>(i) * n + k] && low_at[static_cast<size_t>(i + 1) * n + k];
      Vec3 d = at(i + 1, t.joints[k]) - at(i, t.joints[k]);
      d.y() = 0.0;
      t.step[slot] = d;
      if (t.low[slot]) t.ground[i] = 1;
    }
  }
  return t;
}

// The root's path over the floor sampled every half second (and at the last frame), its length.
double sampled_path_length(std::span<const Vec3> points, double fps) {
  if (points.size() < 2) return 0.0;
  const size_t every = std::max<size_t>(1, static_cast<size_t>(std::lround(0.5 * fps)));
  double length = 0.0;
  size_t last = 0;
  const auto floor_distance = [&](size_t a, size_t b) {
    Vec3 d = points[b] - points[a];
    d.y() = 0.0;
    return d.norm();
  };
  for (size_t f = every; f < points.size(); f += every) {
    length += floor_distance(last, f);
    last = f;
  }
  if (last + 1 < points.size()) length += floor_distance(last, points.size() - 1);
  return length;
}

// World positions of every `stride`-th frame (frame-major), as world_positions gives them all.
std::vector<Vec3> positions_every(const Skeleton& skeleton, const Motion& motion, int stride) {
  const int joints = skeleton.joint_count();
  std::vector<Vec3> out;
  std::vector<Quat> rotations(static_cast<size_t>(joints));
  for (int f = 0; f < motion.frame_count; f += stride) {
    out.resize(out.size() + static_cast<size_t>(joints));
    forward_kinematics(skeleton, motion, f, std::span(out).last(static_cast<size_t>(joints)), rotations);
  }
  return out;
}

std::vector<Vec3> root_path(std::span<const Vec3> world, int joint_count) {
  std::vector<Vec3> out;
  if (joint_count <= 0) return out;
  const size_t frames = world.size() / static_cast<size_t>(joint_count);
  out.reserve(frames);
  for (size_t f = 0; f < frames; ++f) out.push_back(world[f * joint_count]);
  return out;
}

}  // namespace

Status InPlaceSettings::validate() const {
  if (!(contact_height_m > 0.0) || !std::isfinite(contact_height_m)) {
    return Error{"", 0, fmt::format("the contact height must be positive, not {}", contact_height_m)};
  }
  if (!(floor_quantile >= 0.0 && floor_quantile <= 1.0)) {
    return Error{"", 0, fmt::format("the floor quantile must lie in [0, 1], not {}", floor_quantile)};
  }
  if (!(min_slide_speed > 0.0) || !std::isfinite(min_slide_speed)) {
    return Error{"", 0, fmt::format("the slowest slide in place must be positive, not {}", min_slide_speed)};
  }
  if (!(root_speed_ratio >= 0.0) || !std::isfinite(root_speed_ratio)) {
    return Error{"", 0, fmt::format("the slide's ratio to the root's speed must be >= 0, not {}", root_speed_ratio)};
  }
  if (!(direction_window_s >= 0.0) || !std::isfinite(direction_window_s)) {
    return Error{"", 0, fmt::format("the direction window must be >= 0 s, not {}", direction_window_s)};
  }
  return Ok{};
}

std::string_view travel_source_name(TravelSource source) {
  switch (source) {
    case TravelSource::kRoot:
      return "root";
    case TravelSource::kFeet:
      return "feet";
    case TravelSource::kAuto:
      break;
  }
  return "auto";
}

std::optional<TravelSource> parse_travel_source(std::string_view text) {
  const std::string lower = ascii_lower(text);
  for (TravelSource s : {TravelSource::kAuto, TravelSource::kRoot, TravelSource::kFeet}) {
    if (lower == travel_source_name(s)) return s;
  }
  return std::nullopt;
}

InPlaceChoice judge_in_place(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                             const FootJoints& feet, const InPlaceSettings& settings) {
  InPlaceChoice choice;
  const FootTrack t = track_feet(world_positions_m, joint_count, feet, settings);
  if (t.frames < 2 || t.joints.empty() || !(fps > 0.0)) return choice;
  const size_t n = t.joints.size();
  std::vector<double> stillest;
  for (int i = 0; i + 1 < t.frames; ++i) {
    if (!t.ground[i]) continue;
    double least = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < n; ++k) {
      const size_t slot = static_cast<size_t>(i) * n + k;
      if (t.low[slot]) least = std::min(least, t.step[slot].norm() * fps);
    }
    stillest.push_back(least);
  }
  choice.ground_share = static_cast<double>(stillest.size()) / (t.frames - 1);
  choice.slide_speed_m_s = quantile(stillest, 0.5);
  const double duration = (t.frames - 1) / fps;
  choice.root_speed_m_s = sampled_path_length(root_path(world_positions_m, joint_count), fps) / duration;
  choice.in_place = choice.slide_speed_m_s >= settings.min_slide_speed &&
                    choice.slide_speed_m_s >= settings.root_speed_ratio * choice.root_speed_m_s;
  return choice;
}

std::vector<Vec3> travel_from_feet(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                                   const FootJoints& feet, bool in_place, const InPlaceSettings& settings) {
  const FootTrack t = track_feet(world_positions_m, joint_count, feet, settings);
  std::vector<Vec3> travel(static_cast<size_t>(std::max(t.frames, 0)), Vec3::Zero());
  const int intervals = t.frames - 1;
  const size_t n = t.joints.size();
  if (intervals < 1 || n == 0) return travel;

  // The low joints' mean displacement per ground interval, summed for windows.
  std::vector<Vec3> mean_sum(static_cast<size_t>(intervals) + 1, Vec3::Zero());
  for (int i = 0; i < intervals; ++i) {
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (size_t k = 0; k < n; ++k) {
      const size_t slot = static_cast<size_t>(i) * n + k;
      if (t.low[slot]) {
        sum += t.step[slot];
        ++count;
      }
    }
    mean_sum[i + 1] = mean_sum[i] + (count > 0 ? Vec3(sum / count) : Vec3::Zero());
  }
  const int half = std::max(0, static_cast<int>(std::lround(0.5 * settings.direction_window_s * fps)));

  // Each ground interval: minus the displacement of the joint moving furthest backwards.
  std::vector<Vec3> step(static_cast<size_t>(intervals), Vec3::Zero());
  std::vector<int> grounded;
  for (int i = 0; i < intervals; ++i) {
    if (!t.ground[i]) continue;
    const int a = std::max(0, i - half), b = std::min(intervals, i + half + 1);
    const Vec3 backwards = mean_sum[b] - mean_sum[a];
    int best = -1;
    double best_along = -std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < n; ++k) {
      const size_t slot = static_cast<size_t>(i) * n + k;
      if (!t.low[slot]) continue;
      // In place: furthest backwards. Else the stillest (a capture's planted foot stays put).
      const double along = in_place ? t.step[slot].dot(backwards) : -t.step[slot].norm();
      if (best < 0 || along > best_along) {
        best = static_cast<int>(k);
        best_along = along;
      }
    }
    step[i] = -t.step[static_cast<size_t>(i) * n + best];
    grounded.push_back(i);
  }
  // Off the ground: linear between the ground intervals either side (held at the ends).
  if (!grounded.empty()) {
    size_t next = 0;
    for (int i = 0; i < intervals; ++i) {
      if (t.ground[i]) {
        ++next;
        continue;
      }
      if (next == 0) {
        step[i] = step[grounded.front()];
      } else if (next == grounded.size()) {
        step[i] = step[grounded.back()];
      } else {
        const int before = grounded[next - 1], after = grounded[next];
        const double w = static_cast<double>(i - before) / (after - before);
        step[i] = (1.0 - w) * step[before] + w * step[after];
      }
    }
  }
  for (int i = 0; i < intervals; ++i) travel[i + 1] = travel[i] + step[i];
  return travel;
}

Status recover_travel(Clip& clip, TravelSource source, const FootJointNames& names,
                      const InPlaceSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  if (source == TravelSource::kRoot) return Ok{};
  auto feet = find_foot_joints(clip.skeleton, names);
  if (!feet) {
    if (source == TravelSource::kAuto) return Ok{};
    return Error{"", 0, "cannot recover its travel from the feet: " + feet.error().message};
  }
  const Skeleton& skeleton = clip.skeleton;
  Motion& motion = clip.motion;
  // Judged at about 30 fps (a capture at 120 is looked at every 4th frame: loading stays cheap
  // for the clips that travel), recovered at the clip's own rate.
  const int stride = std::max(1, static_cast<int>(std::floor(motion.fps / kJudgedFps + 1e-9)));
  std::vector<Vec3> world = positions_every(skeleton, motion, stride);
  InPlaceChoice choice = judge_in_place(world, skeleton.joint_count(), motion.fps / stride, *feet, settings);
  const bool recover = source == TravelSource::kFeet || choice.in_place;
  const int slot = skeleton.joint_count() > 0 ? skeleton.translation_slot(0) : -1;
  if (recover && slot < 0) {
    if (source == TravelSource::kAuto) {
      clip.in_place = choice;
      return Ok{};
    }
    return Error{"", 0,
                 fmt::format("cannot recover its travel from the feet: its root joint '{}' has no translation "
                             "channels to carry it",
                             skeleton.joint(0).name)};
  }
  if (recover) {
    if (stride > 1) world = world_positions(skeleton, motion);
    const std::vector<Vec3> travel =
        travel_from_feet(world, skeleton.joint_count(), motion.fps, *feet, choice.in_place, settings);
    for (int f = 0; f < motion.frame_count; ++f) motion.translations(f)[slot] += travel[f];
    choice.recovered = true;
    choice.recovered_m = sampled_path_length(travel, motion.fps);
  }
  clip.in_place = choice;
  return Ok{};
}

}  // namespace mg
