// How long a clip's walking strides take for their length (walk_pace.h).
#include "motiongraph/motion/walk_pace.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "motiongraph/core/quantile.h"
#include "motiongraph/motion/flight_fall.h"
#include "motiongraph/motion/length_unit.h"

namespace mg {

double WalkPace::slowdown() const { return measured() ? walk_ratio / kWalkRatio : 0.0; }

double WalkPace::usual_stride_s() const {
  return measured() ? kWalkRatio * figure_m / stride_m * std::sqrt(figure_m / kGravityMps2) : 0.0;
}

namespace {

struct Plant {
  int first = 0;   // its first frame: the ankle comes down
  Eigen::Vector2d floor;  // where it stands: the median of its frames' x and z
};

struct Stride {
  int first = 0, end = 0;  // frames: from one plant of the ankle to the next
  int side = 0;            // 0 left, 1 right
  double length_m = 0.0;
  bool walks = false;      // passes every rule of a stride on its own (not the agreement)
};

double horizontal_distance(const Vec3& a, const Vec3& b) { return std::hypot(a.x() - b.x(), a.z() - b.z()); }

// The plants of one ankle that start and end inside the clip (one cut off by its ends has no
// known first frame or floor position).
std::vector<Plant> plants(std::span<const Vec3> positions, int joint_count, std::span<const ContactMask> contacts,
                          int ankle, ContactMask bit) {
  std::vector<uint8_t> planted(contacts.size());
  for (size_t f = 0; f < contacts.size(); ++f) planted[f] = (contacts[f] & bit) != 0;
  std::vector<Plant> out;
  for (const ContactInterval& run : contact_intervals(planted)) {
    if (run.first_frame == 0 || run.first_frame + run.frame_count >= static_cast<int>(contacts.size())) continue;
    std::vector<double> xs, zs;
    for (int f = run.first_frame; f < run.first_frame + run.frame_count; ++f) {
      const Vec3& p = positions[static_cast<size_t>(f) * joint_count + ankle];
      xs.push_back(p.x());
      zs.push_back(p.z());
    }
    out.push_back({run.first_frame, Eigen::Vector2d(quantile(xs, 0.5), quantile(zs, 0.5))});
  }
  return out;
}

// Pearson's correlation of two equally long samples; 0 when either is constant.
double correlation(std::span<const double> a, std::span<const double> b) {
  const double n = static_cast<double>(a.size());
  double ma = 0.0, mb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= n, mb /= n;
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return aa > 0.0 && bb > 0.0 ? ab / std::sqrt(aa * bb) : 0.0;
}

}  // namespace

WalkPace measure_walk_pace(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                           std::span<const ContactMask> contacts, const FootJoints& feet) {
  WalkPace out;
  const auto joint = [&](int j) { return j >= 0 && j < joint_count; };
  if (joint_count <= 0 || !(fps > 0.0) || !joint(feet.left.ankle) || !joint(feet.right.ankle)) return out;
  const size_t frames = world_positions_m.size() / static_cast<size_t>(joint_count);
  if (frames == 0 || contacts.size() != frames) return out;
  const double figure = figure_size(world_positions_m, joint_count);
  if (!(figure > 0.0)) return out;
  // The mean of the joints: the body's travel and its height.
  std::vector<Vec3> centre(frames, Vec3::Zero());
  for (size_t f = 0; f < frames; ++f) {
    for (int j = 0; j < joint_count; ++j) centre[f] += world_positions_m[f * joint_count + j];
    centre[f] /= joint_count;
  }
  const std::array<int, 2> ankles = {feet.left.ankle, feet.right.ankle};
  const std::array<std::vector<Plant>, 2> by_side = {
      plants(world_positions_m, joint_count, contacts, ankles[0], contact_bit(FootSide::kLeft, FootPart::kAnkle)),
      plants(world_positions_m, joint_count, contacts, ankles[1], contact_bit(FootSide::kRight, FootPart::kAnkle))};

  // How far the body goes along the floor from frame a to frame b.
  const auto travel = [&](int a, int b) {
    return horizontal_distance(centre[static_cast<size_t>(b)], centre[static_cast<size_t>(a)]);
  };
  // Whether the frames [first, end) walk (see the header), the stride's length given.
  const auto walks = [&](int first, int end, double length_m) {
    if (end - first < 8 || length_m < kMinStrideFigures * figure) return false;
    // Steady: the pace over each eighth against the mean pace, and the straight line against the path.
    std::array<double, 8> pace{};
    for (int i = 0; i < 8; ++i) {
      const int a = first + (end - first) * i / 8, b = first + (end - first) * (i + 1) / 8;
      pace[static_cast<size_t>(i)] = travel(a, b) / (b - a);
    }
    const double mean_pace = std::accumulate(pace.begin(), pace.end(), 0.0) / 8.0;
    if (!(mean_pace > 0.0) || *std::min_element(pace.begin(), pace.end()) < kMinSteadiness * mean_pace) return false;
    double path = 0.0;
    for (int f = first; f < end; ++f) path += travel(f, f + 1);
    if (travel(first, end) < kMinStraightness * path) return false;
    // A walk's vault: the body highest where the feet are closest.
    std::vector<double> apart, height;
    for (int f = first; f < end; ++f) {
      const size_t row = static_cast<size_t>(f) * joint_count;
      apart.push_back(horizontal_distance(world_positions_m[row + ankles[0]], world_positions_m[row + ankles[1]]));
      height.push_back(centre[static_cast<size_t>(f)].y());
    }
    return correlation(apart, height) <= -kMinVault;
  };

  std::vector<Stride> strides;
  for (int side = 0; side < 2; ++side) {
    const std::vector<Plant>& own = by_side[static_cast<size_t>(side)];
    const std::vector<Plant>& other = by_side[static_cast<size_t>(1 - side)];
    for (size_t i = 0; i + 1 < own.size(); ++i) {
      const int first = own[i].first, end = own[i + 1].first;
      int between = 0, middle = 0;
      for (const Plant& p : other) {
        if (p.first > first && p.first < end) ++between, middle = p.first;
      }
      if (between != 1) continue;
      const double phase = static_cast<double>(middle - first) / (end - first);
      Stride s{first, end, side, (own[i + 1].floor - own[i].floor).norm(), false};
      s.walks = std::abs(phase - 0.5) <= kMaxPhaseOffset && walks(first, end, s.length_m);
      strides.push_back(s);
    }
  }
  std::sort(strides.begin(), strides.end(), [](const Stride& a, const Stride& b) { return a.first < b.first; });
  // A stride counts when it and the next (or the one before) walk, of the other ankle, and agree.
  const auto agree = [&](const Stride& a, const Stride& b) {
    const auto within = [](double x, double y) { return std::abs(std::log(x / y)) <= std::log1p(kMaxStrideChange); };
    return a.walks && b.walks && a.side != b.side && within(a.length_m, b.length_m) &&
           within(a.end - a.first, b.end - b.first);
  };
  std::vector<double> lengths, durations, ratios;
  for (size_t i = 0; i < strides.size(); ++i) {
    const bool before = i > 0 && agree(strides[i - 1], strides[i]);
    const bool after = i + 1 < strides.size() && agree(strides[i], strides[i + 1]);
    if (!before && !after) continue;
    const double length = strides[i].length_m, duration = (strides[i].end - strides[i].first) / fps;
    lengths.push_back(length);
    durations.push_back(duration);
    ratios.push_back(length / figure * duration * std::sqrt(kGravityMps2 / figure));
  }
  out.strides = static_cast<int>(ratios.size());
  out.figure_m = figure;
  if (out.strides >= kMinWalkStrides) {
    out.stride_m = quantile(lengths, 0.5);
    out.stride_s = quantile(durations, 0.5);
    out.walk_ratio = quantile(ratios, 0.5);
  }
  return out;
}

}  // namespace mg
