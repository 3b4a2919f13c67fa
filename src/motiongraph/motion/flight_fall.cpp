// How fast a clip's flights fall (flight_fall.h).
#include "motiongraph/motion/flight_fall.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "motiongraph/core/quantile.h"

namespace mg {

double FlightFall::slowdown() const { return measured() ? std::sqrt(kGravityMps2 / fall_mps2) : 0.0; }

namespace {

// The downward acceleration of heights[first, last) as a parabola in time, with its rise; 0 when
// the run is not one (see the header).
struct Parabola {
  double fall_mps2 = 0.0;
  double rise_m = 0.0;
};

Parabola fit_flight(std::span<const double> heights, double fps) {
  const int n = static_cast<int>(heights.size());
  Eigen::MatrixXd a(n, 3);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    const double t = i / fps;
    a(i, 0) = t * t, a(i, 1) = t, a(i, 2) = 1.0;
    y(i) = heights[i];
  }
  const Eigen::Vector3d c = a.colPivHouseholderQr().solve(y);
  if (!(c(0) < 0.0)) return {};
  const double apex = -c(1) / (2.0 * c(0)), duration = (n - 1) / fps;
  if (!(apex > 0.0 && apex < duration)) return {};
  const double rise = y.maxCoeff() - std::min(heights.front(), heights.back());
  const double residual = std::sqrt((a * c - y).squaredNorm() / n);
  if (!(rise >= kMinFlightRiseM) || !(residual < kMaxFlightResidual * rise)) return {};
  return {-2.0 * c(0), rise};
}

}  // namespace

FlightFall measure_flight_fall(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                               std::span<const ContactMask> contacts) {
  FlightFall out;
  if (joint_count <= 0 || !(fps > 0.0)) return out;
  const size_t frames = world_positions_m.size() / static_cast<size_t>(joint_count);
  if (contacts.size() != frames) return out;
  std::vector<double> centre(frames, 0.0);
  for (size_t f = 0; f < frames; ++f) {
    for (int j = 0; j < joint_count; ++j) centre[f] += world_positions_m[f * joint_count + j].y();
    centre[f] /= joint_count;
  }
  std::vector<double> falls;
  for (size_t f = 0; f < frames;) {
    if (contacts[f] != 0) {
      ++f;
      continue;
    }
    size_t end = f;
    while (end < frames && contacts[end] == 0) ++end;
    if (end - f >= static_cast<size_t>(kMinFlightFrames)) {
      const Parabola p = fit_flight(std::span<const double>(centre).subspan(f, end - f), fps);
      if (p.fall_mps2 > 0.0) {
        falls.push_back(p.fall_mps2);
        out.highest_rise_m = std::max(out.highest_rise_m, p.rise_m);
      }
    }
    f = end;
  }
  out.flights = static_cast<int>(falls.size());
  if (out.flights >= 2 || out.highest_rise_m >= kMinSingleFlightRiseM) out.fall_mps2 = quantile(falls, 0.5);
  return out;
}

}  // namespace mg
