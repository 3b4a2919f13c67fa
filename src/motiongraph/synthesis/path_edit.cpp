#include "motiongraph/synthesis/path_edit.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "motiongraph/synthesis/floor_transform.h"

namespace mg {

Status PathEditSettings::validate() const {
  auto refused = [](const std::string& what) { return Error{"", 0, "path edit: " + what}; };
  if (!(smooth_s >= 0.0) || !std::isfinite(smooth_s)) {
    return refused(fmt::format("the smoothing must be finite and >= 0 s, not {:g}", smooth_s));
  }
  if (!(tangent_m > 0.0 && std::isfinite(tangent_m)) || !(lookahead_m > 0.0 && std::isfinite(lookahead_m))) {
    return refused(fmt::format("the tangent's chord and the look-ahead must be finite and > 0 m, not {:g} and {:g}",
                               tangent_m, lookahead_m));
  }
  if (!(max_turn_deg_per_m >= 0.0) || !std::isfinite(max_turn_deg_per_m)) {
    return refused(fmt::format("the turning it may add must be finite and >= 0 degrees per metre, not {:g}",
                               max_turn_deg_per_m));
  }
  if (!(round_corners_m >= 0.0) || !std::isfinite(round_corners_m)) {
    return refused(fmt::format("the corners' rounding must be finite and >= 0 m, not {:g}", round_corners_m));
  }
  return Ok{};
}

FloorPath round_corners(const FloorPath& path, double half_window_m) {
  constexpr double kSpacingM = 0.05;
  const double length = path.length_m();
  const int half = static_cast<int>(std::lround(half_window_m / kSpacingM));
  if (half < 1 || !(length > 0.0)) return path;
  const int n = static_cast<int>(std::ceil(length / kSpacingM)) + 1;
  std::vector<Vec2> points(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) points[i] = path.point_at(length * i / (n - 1));
  // Centred averages over +- half samples, by prefix sums.
  auto average = [&](const std::vector<Vec2>& in) {
    std::vector<Vec2> prefix(in.size() + 1, Vec2::Zero());
    for (size_t i = 0; i < in.size(); ++i) prefix[i + 1] = prefix[i] + in[i];
    std::vector<Vec2> out(in.size());
    for (int i = 0; i < n; ++i) {
      const int w = std::min({half, i, n - 1 - i});
      out[i] = (prefix[i + w + 1] - prefix[i - w]) / static_cast<double>(2 * w + 1);
    }
    return out;
  };
  std::vector<Vec2> once = average(points);
  const std::vector<Vec2> twice = average(once);
  for (int i = 0; i < n; ++i) once[i] = 2.0 * once[i] - twice[i];
  auto rounded = FloorPath::create(once);
  return rounded ? *rounded : path;
}

namespace {

// v turned by yaw (FloorTransform::rotate on the floor).
Vec2 turned(const Vec2& v, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {c * v.x() + s * v.y(), -s * v.x() + c * v.y()};
}

// The path asked for at arc length s, continued straight past its end (and before its start).
Vec2 target_at(const FloorPath& path, double s) {
  const double length = path.length_m();
  if (s < 0.0) return path.points().front() + s * path.direction_at(0.0);
  if (s <= length) return path.point_at(s);
  return path.point_at(length) + (s - length) * path.direction_at(length);
}

// A polyline parametrised by its arc length (non-decreasing), clamped at its ends.
struct ArcCurve {
  std::vector<double> arc;
  std::vector<Vec2> points;

  Vec2 at(double s) const {
    const auto it = std::upper_bound(arc.begin(), arc.end(), s);
    if (it == arc.begin()) return points.front();
    if (it == arc.end()) return points.back();
    const auto i = static_cast<size_t>(it - arc.begin());  // arc[i - 1] <= s < arc[i]
    const double u = (s - arc[i - 1]) / (arc[i] - arc[i - 1]);
    return points[i - 1] + u * (points[i] - points[i - 1]);
  }
};

}  // namespace

Result<PathEditStats> plan_path_edit(std::span<const Vec2> roots, double fps, const FloorPath& path,
                                     const PathEditSettings& settings, std::vector<FloorTransform>& moves) {
  if (auto s = settings.validate(); !s) return s.error();
  PathEditStats stats;
  const int frames = static_cast<int>(roots.size());
  moves.assign(roots.size(), FloorTransform{});
  if (frames < 2) return stats;

  // 1. The motion's own path, and each frame's arc along it.
  std::vector<Vec2> prefix(static_cast<size_t>(frames) + 1, Vec2::Zero());
  for (int f = 0; f < frames; ++f) prefix[f + 1] = prefix[f] + roots[f];
  const int half = static_cast<int>(std::lround(settings.smooth_s * fps / 2.0));
  ArcCurve own;
  for (int f = 0; f < frames; ++f) {
    const int h = std::min({half, f, frames - 1 - f});
    const Vec2 q = (prefix[f + h + 1] - prefix[f - h]) / static_cast<double>(2 * h + 1);
    own.arc.push_back(f == 0 ? 0.0 : own.arc.back() + (q - own.points.back()).norm());
    own.points.push_back(q);
  }
  const double end = own.arc.back();
  if (end < PathEditSettings::kStepM) return stats;  // the root does not travel

  // 2. The added angle, steered along a grid of arc: a[k] turns Q's step from grid[k] to
  // grid[k + 1], and edited[k] is Q' at grid[k]; along[k] is the arc length of P's point nearest
  // it, searched near the last one (a path that crosses itself is followed, not jumped across).
  const auto steps = static_cast<size_t>(std::ceil(end / PathEditSettings::kStepM - 1e-9));
  std::vector<double> grid(steps + 1);
  for (size_t k = 0; k <= steps; ++k) grid[k] = std::min(end, static_cast<double>(k) * PathEditSettings::kStepM);
  std::vector<double> a(grid.size(), 0.0);
  std::vector<Vec2> edited(grid.size());
  edited[0] = own.points.front();
  const double h = settings.tangent_m;
  const double limit = settings.max_turn_deg_per_m * std::numbers::pi / 180.0;
  constexpr double kReachM = 1.0;  // how far the nearest point is looked for from the last one
  // Going back along P: the nearest point moved back more than kBackM over kBackLookM of arc.
  constexpr double kBackLookM = 0.2, kBackM = 0.05;
  const auto back_steps = static_cast<size_t>(std::lround(kBackLookM / PathEditSettings::kStepM));
  double along = 0.0, limited_arc = 0.0;
  std::vector<double> along_at(grid.size(), 0.0);
  for (size_t k = 0; k < steps; ++k) {
    const double s = grid[k];
    const double step = grid[k + 1] - s;
    along = path.nearest_arc(edited[k], along - kReachM, along + kReachM + step, along + step);
    along_at[k] = along;
    const Vec2 own_chord = turned(own.at(std::min(end, s + h)) - own.at(std::max(0.0, s - h)), a[k]);
    const Vec2 path_chord = target_at(path, along + h) - target_at(path, along - h);
    double angle = a[k];
    if (own_chord.norm() > 1e-9 && path_chord.norm() > 1e-9) {
      // Along the path, or back along it while the motion goes that way (a step back): heading
      // against P's direction with its nearest point on P moved back over the last kBackLookM
      // of arc. Heading against P is no sign alone: past a corner of 90 degrees or more a walk
      // that has not turned yet heads square to the next leg or against it (and was steered
      // back the way it came when that was the rule).
      Vec2 t = path_chord.normalized();
      const bool going_back = k >= back_steps && along < along_at[k - back_steps] - kBackM && own_chord.dot(t) < 0.0;
      if (going_back) t = -t;
      const Vec2 n(-t.y(), t.x());
      const double offset = n.dot(edited[k] - target_at(path, along));
      const Vec2 wanted = settings.lookahead_m * t - offset * n;
      const double change = yaw_between(own_chord, wanted);
      const double room = limit * step;
      if (std::abs(change) > room) limited_arc += step;
      angle = a[k] + std::clamp(change, -room, room);
    }
    edited[k + 1] = edited[k] + turned(own.at(grid[k + 1]) - own.at(s), a[k]);
    a[k + 1] = angle;
  }

  // 3. Each frame moved rigidly on the floor, from Q(s_i) to Q'(s_i), turned by a(s_i).
  for (int f = 0; f < frames; ++f) {
    const double s = own.arc[f];
    const auto k = std::min(steps - 1, static_cast<size_t>(std::upper_bound(grid.begin(), grid.end(), s) -
                                                           grid.begin() - 1));
    const double span = grid[k + 1] - grid[k];
    const double u = span > 0.0 ? std::clamp((s - grid[k]) / span, 0.0, 1.0) : 0.0;
    const Vec2& q = own.points[f];
    const Vec2 moved = edited[k] + turned(q - own.at(grid[k]), a[k]);
    FloorTransform& move = moves[f];
    move.yaw_rad = a[k] + u * (a[k + 1] - a[k]);
    const Vec3 q_turned = move.rotate(Vec3(q.x(), 0.0, q.y()));
    move.x_m = moved.x() - q_turned.x();
    move.z_m = moved.y() - q_turned.z();
    stats.max_added_turn_deg = std::max(stats.max_added_turn_deg, std::abs(move.yaw_rad) * 180.0 / std::numbers::pi);
    stats.max_shift_m = std::max(stats.max_shift_m, (moved - q).norm());
  }
  stats.edited = true;
  stats.limited_share = limited_arc / end;
  return stats;
}

Result<PathEditStats> edit_onto_path(Motion& motion, const FloorPath& path, const PathEditSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  if (motion.frame_count < 2 || motion.translated_count < 1 || motion.joint_count < 1) return PathEditStats{};
  std::vector<Vec2> roots(static_cast<size_t>(motion.frame_count));
  for (int f = 0; f < motion.frame_count; ++f) {
    const Vec3& p = motion.translations(f)[0];
    roots[f] = Vec2(p.x(), p.z());
  }
  std::vector<FloorTransform> moves;
  auto stats = plan_path_edit(roots, motion.fps, round_corners(path, settings.round_corners_m), settings, moves);
  if (!stats || !stats->edited) return stats;
  for (int f = 0; f < motion.frame_count; ++f) {
    Vec3& root = motion.translations(f)[0];
    root = moves[f].apply(root);
    Quat& rotation = motion.rotations(f)[0];
    rotation = (moves[f].rotation() * rotation).normalized();
  }
  return stats;
}

}  // namespace mg
