// Exact D along a diagonal run: float products, double offsets, sliding window sums.
#include "motiongraph/metric/diagonal_runs.h"

#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

#include "motiongraph/metric/closed_form.h"

namespace mg {

namespace {

// A float dot product in 8 independent lanes (so that it vectorises, as BLAS's kernels do).
float dot(const float* x, const float* y, int n) {
  float lanes[8] = {};
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    for (int l = 0; l < 8; ++l) lanes[l] += x[i + l] * y[i + l];
  }
  for (; i < n; ++i) lanes[0] += x[i] * y[i];
  return ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) + ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
}

}  // namespace

void diagonal_run_distances(const FrameFeatures& f, int a, int b, std::span<float> out) {
  const int length = static_cast<int>(out.size());
  const int n = f.frames, k = f.window, p = f.points;
  assert(a >= 0 && b >= 0 && a + length <= n && b + length <= n);
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  // The frame pairs (a + t, b - k + 1 + t) for t = 0 .. length + k - 2; those before the
  // matrix's first frame or past its last belong to undefined pairs only.
  const int pairs = length + k - 1;
  std::vector<double> e1(static_cast<size_t>(pairs)), e2(e1.size()), e3(e1.size());
  const double v = f.point_weight_sum;
  for (int t = 0; t < pairs; ++t) {
    const int i = a + t, j = b - k + 1 + t;
    if (i >= n || j < 0) {
      e1[t] = e2[t] = e3[t] = 0.0;
      continue;
    }
    const float* xz_i = &f.xz[static_cast<size_t>(i) * 2 * p];
    const float g1 = dot(xz_i, &f.xz[static_cast<size_t>(j) * 2 * p], 2 * p);
    const float g2 = dot(xz_i, &f.zx[static_cast<size_t>(j) * 2 * p], 2 * p);
    const float g3 = dot(&f.y[static_cast<size_t>(i) * p], &f.y[static_cast<size_t>(j) * p], p);
    const Offsets o{f.root_x[i], f.root_z[i], f.moment_x[i], f.moment_z[i]};
    const double nvx = f.moment_x[j] + v * f.root_x[j], nvz = f.moment_z[j] + v * f.root_z[j];
    e1[t] = uncentred_e1(o, g1, f.root_x[j], f.root_z[j], nvx, nvz);
    e2[t] = uncentred_e2(o, g2, f.root_x[j], f.root_z[j], nvx, nvz);
    e3[t] = g3;
  }
  const double inv_w = 1.0 / f.window_weight;
  const bool uniform = uniform_taper(f.taper);
  double s1 = 0.0, s2 = 0.0, s3 = 0.0;  // uniform: the running sums of the current window
  if (uniform) {
    for (int t = 0; t < k - 1; ++t) {
      s1 += e1[t];
      s2 += e2[t];
      s3 += e3[t];
    }
  }
  for (int m = 0; m < length; ++m) {
    double c1 = 0.0, c2 = 0.0, c3 = 0.0;
    if (uniform) {
      s1 += e1[m + k - 1];
      s2 += e2[m + k - 1];
      s3 += e3[m + k - 1];
      c1 = f.taper[0] * s1;
      c2 = f.taper[0] * s2;
      c3 = f.taper[0] * s3;
    } else {
      for (int t = 0; t < k; ++t) {
        c1 += f.taper[t] * e1[m + t];
        c2 += f.taper[t] * e2[m + t];
        c3 += f.taper[t] * e3[m + t];
      }
    }
    const int leave = a + m, arrive = b + m, first = arrive - k + 1;
    if (leave > n - k || first < 0 || !f.can_leave[leave] || !f.can_arrive[arrive]) {
      out[m] = kNaN;
    } else {
      const double x = f.window_x[leave], z = f.window_z[leave];
      const double x2 = f.window_x[first], z2 = f.window_z[first];
      const RowTerms row{x, z, centred_window_square(f.window_square[leave], x, z, inv_w), inv_w};
      out[m] = closed_form(c1, c2, c3, row, x2, z2, centred_window_square(f.window_square[first], x2, z2, inv_w));
    }
    if (uniform) {
      s1 -= e1[m];
      s2 -= e2[m];
      s3 -= e3[m];
    }
  }
}

}  // namespace mg
