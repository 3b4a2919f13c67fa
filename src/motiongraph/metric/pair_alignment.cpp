#include "motiongraph/metric/pair_alignment.h"

#include <cmath>

namespace mg {

FloorAlignment align_pair(const FrameFeatures& f, int a, int b) {
  const int k = f.window;
  const int p = f.points;
  const int b_first = b - k + 1;
  const double v = f.point_weight_sum;
  double c1 = 0.0, c2 = 0.0;
  for (int t = 0; t < k; ++t) {
    const size_t fa = static_cast<size_t>(a + t), fb = static_cast<size_t>(b_first + t);
    double g1 = 0.0, g2 = 0.0;
    const float* xa = f.xz.data() + fa * 2 * p;
    const float* xb = f.xz.data() + fb * 2 * p;
    const float* zb = f.zx.data() + fb * 2 * p;
    for (int i = 0; i < 2 * p; ++i) {
      g1 += static_cast<double>(xa[i]) * xb[i];
      g2 += static_cast<double>(xa[i]) * zb[i];
    }
    // Offsets added back as in the tiled path (DESIGN.md 3.3).
    const double rx = f.root_x[fa], rz = f.root_z[fa], mx = f.moment_x[fa], mz = f.moment_z[fa];
    const double sx = f.root_x[fb], sz = f.root_z[fb], nx = f.moment_x[fb], nz = f.moment_z[fb];
    c1 += f.taper[t] * (g1 + rx * nx + rz * nz + mx * sx + mz * sz + v * (rx * sx + rz * sz));
    c2 += f.taper[t] * (g2 + rx * nz - rz * nx + mx * sz - mz * sx + v * (rx * sz - rz * sx));
  }
  const double w = f.window_weight;
  const double x = f.window_x[a], z = f.window_z[a];
  const double x2 = f.window_x[b_first], z2 = f.window_z[b_first];
  FloorAlignment align;
  align.yaw_rad = std::atan2(c2 - (x * z2 - z * x2) / w, c1 - (x * x2 + z * z2) / w);
  const double c = std::cos(align.yaw_rad), s = std::sin(align.yaw_rad);
  align.x_m = (x - (c * x2 + s * z2)) / w;
  align.z_m = (z - (-s * x2 + c * z2)) / w;
  return align;
}

}  // namespace mg
