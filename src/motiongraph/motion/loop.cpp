#include "motiongraph/motion/loop.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

namespace {

constexpr int kMinSteps = 8;        // a clip of fewer steps of about 1/30 s does not loop
constexpr double kStepRate = 30.0;  // poses are compared this many times a second, whatever the rate
constexpr double kMinStepM = 0.002;
constexpr int kSamples = 200;      // frames the medians are taken over, evenly spread

// A frame's floor placement: the root's point on the floor and its heading (the yaw of one of
// its axes, the one that lies most level at the clip's first frame).
struct Placement {
  double yaw = 0.0;
  Vec3 floor = Vec3::Zero();
};

double wrapped(double angle) { return std::remainder(angle, 2.0 * std::numbers::pi); }

Quat yaw_rotation(double yaw) { return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitY())); }

// A frame's joints about its placement, and the placement.
struct LocalPose {
  Placement placement;
  std::vector<Vec3> joints;
};

// The root's axis (x or z) that lies most level at the first frame: its heading is the clip's.
Vec3 heading_axis(const Skeleton& skeleton, const Motion& motion) {
  std::vector<Vec3> positions(static_cast<size_t>(skeleton.joint_count()));
  std::vector<Quat> rotations(positions.size());
  forward_kinematics(skeleton, motion, 0, positions, rotations);
  const Vec3 x = rotations[0] * Vec3::UnitX(), z = rotations[0] * Vec3::UnitZ();
  return std::abs(x.y()) <= std::abs(z.y()) ? Vec3::UnitX() : Vec3::UnitZ();
}

LocalPose local_pose(const Skeleton& skeleton, const Motion& motion, int frame, const Vec3& axis) {
  std::vector<Vec3> positions(static_cast<size_t>(skeleton.joint_count()));
  std::vector<Quat> rotations(positions.size());
  forward_kinematics(skeleton, motion, frame, positions, rotations);
  const Vec3 x = rotations[0] * axis;
  LocalPose pose;
  pose.placement.yaw = std::atan2(-x.z(), x.x());
  pose.placement.floor = Vec3(positions[0].x(), 0.0, positions[0].z());
  const Quat unturn = yaw_rotation(-pose.placement.yaw);
  for (Vec3& p : positions) p = unturn * (p - pose.placement.floor);
  pose.joints = std::move(positions);
  return pose;
}

double rms_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double sum = 0.0;
  for (size_t j = 0; j < a.size(); ++j) sum += (a[j] - b[j]).squaredNorm();
  return std::sqrt(sum / static_cast<double>(a.size()));
}

}  // namespace

LoopChoice find_loop(const Skeleton& skeleton, const Motion& motion) {
  LoopChoice choice;
  const int frames = motion.frame_count;
  // Poses s frames apart, about 1/30 s whatever the rate, so the measures mean the same at 120 fps.
  const int s = std::max(1, static_cast<int>(std::lround(motion.fps / kStepRate)));
  if (frames < kMinSteps * s + 1 || skeleton.joint_count() == 0) return choice;
  const Vec3 axis = heading_axis(skeleton, motion);
  std::map<int, LocalPose> poses;  // local poses and placements, worked out once each
  const auto local = [&](int frame) -> const LocalPose& {
    auto it = poses.find(frame);
    if (it == poses.end()) it = poses.emplace(frame, local_pose(skeleton, motion, frame, axis)).first;
    return it->second;
  };
  const auto pose = [&](int frame) -> const std::vector<Vec3>& { return local(frame).joints; };
  // The pose a frame would have between its two neighbours either side (a cubic through them).
  const auto between = [&](int a, int b, int c, int d) {
    std::vector<Vec3> mid(pose(a).size());
    for (size_t j = 0; j < mid.size(); ++j) mid[j] = (4.0 * (pose(b)[j] + pose(c)[j]) - pose(a)[j] - pose(d)[j]) / 6.0;
    return mid;
  };
  const auto median = [](std::vector<double> values) {
    std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2), values.end());
    return values[values.size() / 2];
  };
  // The clip's median step, and its median departure from the cubic through the poses around
  // (how smooth it is), over evenly spread frames.
  std::vector<double> steps, frame_steps, departures;
  const int span = frames - 1 - 4 * s;  // frames f with f - 2s and f + 2s inside the clip
  const int samples = std::min(kSamples, span + 1);
  for (int i = 0; i < samples; ++i) {
    const int f = 2 * s + static_cast<int>(static_cast<long long>(i) * span / std::max(1, samples - 1));
    steps.push_back(rms_distance(pose(f), pose(f + s)));
    frame_steps.push_back(rms_distance(pose(f), pose(f + 1)));
    departures.push_back(rms_distance(pose(f), between(f - 2 * s, f - s, f + s, f + 2 * s)));
  }
  // The seam is one frame's step (or none): judged against a frame's; the motion against 1/30 s.
  choice.step_m = median(frame_steps);
  const double departure = median(departures);
  if (median(steps) < kMinStepM || choice.step_m <= 0.0) return choice;

  const int last = frames - 1;
  const double repeated = rms_distance(pose(0), pose(last)) / choice.step_m;  // also the seam's step
  // The frame after the last is the first again: its neighbours are s and 2s frames either side.
  const double following =
      rms_distance(pose(0), between(last + 1 - 2 * s, last + 1 - s, s, 2 * s)) / std::max(departure, 1e-12);
  if (repeated <= kRepeatedSeamRatio) {
    choice = {true, true, frames - 1, repeated, choice.step_m};
  } else if (following <= kFollowingSeamRatio && repeated <= kFollowingStepRatio) {
    choice = {true, false, frames, following, choice.step_m};
  } else {
    choice.seam_ratio = following;
    return choice;
  }
  // Where the next cycle starts: the last frame itself when it repeats the first, else one step
  // on from the last, as the step before it went. One cycle over the floor: p -> cycle p + shift.
  const Placement& start = local(0).placement;
  Placement next = local(last).placement;
  if (!choice.last_repeats_first) {
    const Placement& before = local(last - 1).placement;
    const double turn = wrapped(next.yaw - before.yaw);
    next.floor += yaw_rotation(turn) * (next.floor - before.floor);
    next.yaw += turn;
  }
  choice.cycle_yaw_rad = wrapped(next.yaw - start.yaw);
  choice.cycle_shift_m = next.floor - yaw_rotation(choice.cycle_yaw_rad) * start.floor;
  return choice;
}

Motion unrolled_loop(const Skeleton& skeleton, const Motion& motion, const LoopChoice& loop, int extra_frames) {
  if (!loop.loops || extra_frames <= 0) return motion;
  const int frames = motion.frame_count;
  extra_frames = std::min(extra_frames, loop.period);
  // The cycle's floor transform, on the root's world transform (joint 0's, a static ancestor of
  // the file's folded into it: skeleton.h).
  const Quat cycle = yaw_rotation(loop.cycle_yaw_rad);
  const Vec3& shift = loop.cycle_shift_m;

  Motion out(skeleton, frames + extra_frames, motion.fps);
  std::copy(motion.local_rotations.begin(), motion.local_rotations.end(), out.local_rotations.begin());
  std::copy(motion.local_translations_m.begin(), motion.local_translations_m.end(),
            out.local_translations_m.begin());
  const int root_slot = skeleton.translation_slot(0);
  for (int n = frames; n < frames + extra_frames; ++n) {
    const int m = n - loop.period;
    const auto from_rotations = motion.rotations(m);
    const auto from_translations = motion.translations(m);
    std::copy(from_rotations.begin(), from_rotations.end(), out.rotations(n).begin());
    std::copy(from_translations.begin(), from_translations.end(), out.translations(n).begin());
    out.rotations(n)[0] = (cycle * from_rotations[0]).normalized();
    if (root_slot >= 0) {  // a root without translation channels turns only
      const Vec3& root = from_translations[static_cast<size_t>(root_slot)];
      out.translations(n)[static_cast<size_t>(root_slot)] = cycle * root + shift;
    }
  }
  return out;
}

}  // namespace mg
