// A walker made for the tests (walker.h).
#include "motion/walker.h"

#include <cmath>
#include <numbers>

namespace mg::test {

namespace {

constexpr double kStance = 0.6;  // share of a stride an ankle is planted

// How far along a stride's swing (0 to 1) the ankle is at `s` of it: eased in and out.
double eased(double s) { return s * s * (3.0 - 2.0 * s); }

}  // namespace

Walker walker(const WalkerSettings& settings) {
  Walker out;
  out.feet.left.ankle = 0;
  out.feet.right.ankle = 1;
  const double speed = settings.stride_m / settings.stride_s;
  // The walker's own time at frame f: the slowed stretch takes `slowdown` times as many frames.
  const double slowed = settings.slow_to_s - settings.slow_from_s, stretch = settings.slowdown;
  const auto time_at = [&](int f) {
    const double clock = f / settings.fps;
    if (clock < settings.slow_from_s) return clock;
    if (clock < settings.slow_from_s + stretch * slowed) {
      return settings.slow_from_s + (clock - settings.slow_from_s) / stretch;
    }
    return clock - (stretch - 1.0) * slowed;
  };
  const double end = settings.strides * settings.stride_s;
  for (int f = 0; time_at(f) < end - 1e-9; ++f) {
    const double t = time_at(f);
    ContactMask mask = 0;
    double along[2] = {0.0, 0.0};
    for (int side = 0; side < 2; ++side) {
      // Stride k of this ankle starts at (k + phase) strides: planted at its k-th plant, then swinging to the next.
      const double phase = side == 0 ? 0.0 : settings.right_phase;
      const double u = t / settings.stride_s - phase;
      const double k = std::floor(u), p = u - k;
      const auto plant = [&](double n) {
        return (n + phase) * settings.stride_m + (side == 0 && n == 3.0 ? settings.long_plant_m : 0.0);
      };
      double height = 0.0;
      along[side] = plant(k);
      if (p < kStance) {
        mask |= contact_bit(side == 0 ? FootSide::kLeft : FootSide::kRight, FootPart::kAnkle);
      } else {
        const double s = (p - kStance) / (1.0 - kStance);
        along[side] += eased(s) * (plant(k + 1.0) - plant(k));
        height = 0.1 * std::sin(std::numbers::pi * s);
      }
      out.positions.emplace_back(side == 0 ? -0.1 : 0.1, height, -along[side]);
    }
    const double apart = std::abs(along[0] - along[1]) / settings.stride_m;  // 0 together .. 0.5 at most
    const double lift = 0.03 * settings.vault * (1.0 - 2.0 * apart);
    const double cycle = 2.0 * std::numbers::pi * t / settings.stride_s;
    const double forward = speed * t + 0.3 * settings.stride_m + settings.surge_m * std::sin(2.0 * cycle);
    const double side = settings.sway_m * std::sin(cycle);
    for (int j = 0; j < kWalkerJoints - 2; ++j) {
      out.positions.emplace_back(side + (j % 2 == 0 ? -0.15 : 0.15), 0.9 + 0.1 * j + lift, -forward);
    }
    out.contacts.push_back(mask);
  }
  return out;
}

}  // namespace mg::test
