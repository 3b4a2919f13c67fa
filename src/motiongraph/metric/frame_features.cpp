#include "motiongraph/metric/frame_features.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "motiongraph/core/default_window.h"

namespace mg {

Status DistanceSettings::validate() const {
  if (window_frames < 0 || window_frames > 10000) return Error{"", 0, "window must be 0 (automatic) to 10000 frames"};
  if (tile_frames < 16 || tile_frames > 16384) return Error{"", 0, "tile size must be 16 to 16384 frames"};
  if (threads < 0 || threads > 256) return Error{"", 0, "threads must be 0 (all cores) to 256"};
  return Ok{};
}

int DistanceSettings::window_for(double fps) const {
  return window_frames > 0 ? window_frames : default_window_frames(fps);
}

std::vector<double> window_weights(int k, DistanceSettings::Taper taper) {
  std::vector<double> u(k, 1.0);
  if (taper == DistanceSettings::Taper::kHann) {
    for (int t = 0; t < k; ++t) u[t] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * (t + 1) / (k + 1));
  }
  return u;
}

Result<FrameFeatures> make_frame_features(const MotionDatabase& db, const CloudLayout& layout,
                                          const DistanceSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  FrameFeatures f;
  f.frames = db.frame_count();
  f.points = layout.point_count();
  f.window = settings.window_for(db.fps);
  f.taper = window_weights(f.window, settings.taper);
  for (const DatabaseClip& clip : db.clips) {
    if (!layout_fits(layout, db.skeletons[clip.skeleton])) {
      return Error{clip.source, 0, "its skeleton does not have the joint topology of the database's first skeleton"};
    }
  }
  const size_t n = static_cast<size_t>(f.frames);
  const size_t p = static_cast<size_t>(f.points);
  f.point_weights.assign(layout.weight.begin(), layout.weight.end());
  f.point_weight_sum = 0.0;
  for (double v : f.point_weights) f.point_weight_sum += v;
  if (!(f.point_weight_sum > 0.0)) return Error{"", 0, "all point weights are zero"};
  std::vector<double> sqrt_v(p);
  for (size_t i = 0; i < p; ++i) sqrt_v[i] = std::sqrt(f.point_weights[i]);

  f.xz.resize(n * 2 * p);
  f.zx.resize(n * 2 * p);
  f.y.resize(n * p);
  f.root_x.resize(n);
  f.root_z.resize(n);
  f.moment_x.resize(n);
  f.moment_z.resize(n);
  f.square_sum.resize(n);
  f.can_leave.assign(n, 0);
  f.can_arrive.assign(n, 0);
  f.clip_of_frame.resize(n);
  std::vector<Vec3> points(p);
  for (size_t c = 0; c < db.clips.size(); ++c) {
    const DatabaseClip& clip = db.clips[c];
    const Skeleton& skeleton = db.skeletons[clip.skeleton];
    CloudEvaluator evaluator(skeleton, layout);
    for (int local = 0; local < clip.frame_count; ++local) {
      const size_t frame = static_cast<size_t>(clip.first_frame + local);
      f.clip_of_frame[frame] = static_cast<int>(c);
      f.can_leave[frame] = local + f.window <= clip.frame_count;
      f.can_arrive[frame] = local + 1 >= f.window;
      evaluator.points(clip.motion, local, points);
      // The root's floor position (the root is joint 0: its world position is its translation).
      const int slot = skeleton.translation_slot(0);
      const Vec3 root_position = slot >= 0 ? clip.motion.translations(local)[slot] : skeleton.joint(0).rest_offset_m;
      const double rx = root_position.x();
      const double rz = root_position.z();
      double mx = 0.0, mz = 0.0, q = 0.0;
      for (size_t i = 0; i < p; ++i) {
        const double cx = points[i].x() - rx;
        const double cy = points[i].y();
        const double cz = points[i].z() - rz;
        const double w = f.point_weights[i];
        mx += w * cx;
        mz += w * cz;
        q += w * (cx * cx + cy * cy + cz * cz);
        f.xz[frame * 2 * p + 2 * i] = static_cast<float>(sqrt_v[i] * cx);
        f.xz[frame * 2 * p + 2 * i + 1] = static_cast<float>(sqrt_v[i] * cz);
        f.zx[frame * 2 * p + 2 * i] = static_cast<float>(sqrt_v[i] * cz);
        f.zx[frame * 2 * p + 2 * i + 1] = static_cast<float>(-sqrt_v[i] * cx);
        f.y[frame * p + i] = static_cast<float>(sqrt_v[i] * cy);
      }
      f.root_x[frame] = rx;
      f.root_z[frame] = rz;
      f.moment_x[frame] = mx;
      f.moment_z[frame] = mz;
      f.square_sum[frame] = q;
    }
  }

  // The tags each whole window carries.
  const std::vector<TagMask> tags = db.frame_tags();
  f.leave_tags.assign(n, 0);
  f.arrive_tags.assign(n, 0);
  for (size_t a = 0; a < n && tags.size() == n; ++a) {
    if (!f.can_leave[a]) continue;
    TagMask all = ~TagMask{0};
    for (int t = 0; t < f.window; ++t) all &= tags[a + t];
    f.leave_tags[a] = all;
    f.arrive_tags[a + f.window - 1] = all;  // the window arriving at its last frame
  }

  // Window sums, uncentred: sum_t u_t sum_i v_i p for the window starting at each frame.
  const double v_sum = f.point_weight_sum;
  double u_sum = 0.0;
  for (double u : f.taper) u_sum += u;
  f.window_weight = u_sum * v_sum;
  f.window_x.assign(n, 0.0);
  f.window_z.assign(n, 0.0);
  f.window_square.assign(n, 0.0);
  for (size_t a = 0; a < n; ++a) {
    if (!f.can_leave[a]) continue;
    double x = 0.0, z = 0.0, s = 0.0;
    for (int t = 0; t < f.window; ++t) {
      const size_t g = a + t;
      const double u = f.taper[t];
      x += u * (f.moment_x[g] + v_sum * f.root_x[g]);
      z += u * (f.moment_z[g] + v_sum * f.root_z[g]);
      s += u * (f.square_sum[g] + 2.0 * (f.root_x[g] * f.moment_x[g] + f.root_z[g] * f.moment_z[g]) +
                v_sum * (f.root_x[g] * f.root_x[g] + f.root_z[g] * f.root_z[g]));
    }
    f.window_x[a] = x;
    f.window_z[a] = z;
    f.window_square[a] = s;
  }
  return f;
}

}  // namespace mg
