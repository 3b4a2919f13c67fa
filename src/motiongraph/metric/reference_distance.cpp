#include "motiongraph/metric/reference_distance.h"

#include <cmath>

namespace mg {

Vec3 FloorAlignment::apply(const Vec3& q) const {
  const double c = std::cos(yaw_rad);
  const double s = std::sin(yaw_rad);
  // Rotation about +y: x' = c x + s z, z' = -s x + c z.
  return Vec3(c * q.x() + s * q.z() + x_m, q.y(), -s * q.x() + c * q.z() + z_m);
}

std::vector<Vec3> database_clouds(const MotionDatabase& db, const CloudLayout& layout) {
  const size_t points = static_cast<size_t>(layout.point_count());
  std::vector<Vec3> clouds(static_cast<size_t>(db.frame_count()) * points);
  for (const DatabaseClip& clip : db.clips) {
    CloudEvaluator evaluator(db.skeletons[clip.skeleton], layout);
    for (int f = 0; f < clip.frame_count; ++f) {
      evaluator.points(clip.motion, f, std::span(clouds.data() + static_cast<size_t>(clip.first_frame + f) * points, points));
    }
  }
  return clouds;
}

ReferenceDistance reference_distance(std::span<const Vec3> clouds, int points, std::span<const double> point_weights,
                                     std::span<const double> taper, int a, int b) {
  const int k = static_cast<int>(taper.size());
  const int b_first = b - k + 1;
  double w_sum = 0.0, x = 0.0, z = 0.0, x2 = 0.0, z2 = 0.0, c1 = 0.0, c2 = 0.0;
  for (int t = 0; t < k; ++t) {
    for (int i = 0; i < points; ++i) {
      const double w = taper[t] * point_weights[i];
      const Vec3& p = clouds[static_cast<size_t>(a + t) * points + i];
      const Vec3& q = clouds[static_cast<size_t>(b_first + t) * points + i];
      w_sum += w;
      x += w * p.x();
      z += w * p.z();
      x2 += w * q.x();
      z2 += w * q.z();
      c1 += w * (p.x() * q.x() + p.z() * q.z());
      c2 += w * (p.x() * q.z() - p.z() * q.x());
    }
  }
  ReferenceDistance result;
  FloorAlignment& align = result.alignment;
  const double big_a = c1 - (x * x2 + z * z2) / w_sum;
  const double big_b = c2 - (x * z2 - z * x2) / w_sum;
  align.yaw_rad = std::atan2(big_b, big_a);
  const double c = std::cos(align.yaw_rad);
  const double s = std::sin(align.yaw_rad);
  // The translation moves the rotated arrival centroid onto the departure centroid.
  align.x_m = (x - (c * x2 + s * z2)) / w_sum;
  align.z_m = (z - (-s * x2 + c * z2)) / w_sum;
  double distance = 0.0;
  for (int t = 0; t < k; ++t) {
    for (int i = 0; i < points; ++i) {
      const double w = taper[t] * point_weights[i];
      const Vec3& p = clouds[static_cast<size_t>(a + t) * points + i];
      const Vec3& q = clouds[static_cast<size_t>(b_first + t) * points + i];
      distance += w * (p - align.apply(q)).squaredNorm();
    }
  }
  result.distance = distance;
  return result;
}

}  // namespace mg
