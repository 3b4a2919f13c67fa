// Exact D along a diagonal run: float products, double offsets, sliding window sums.
#include "motiongraph/metric/diagonal_runs.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "motiongraph/metric/closed_form.h"

namespace mg {

namespace {

// The three float products of the frame pairs (i + t, j + t), t = 0 .. count - 1, from the
// point-major operands (row m holds coordinate m of every frame, `stride` apart), each a chain
// of fused multiply-adds over the coordinates in order: how BLAS's sgemm kernels accumulate an
// output (OpenBLAS's on x86-64, for most of a tile), so that D rounds close to the tiles'.
struct Operands {
  const float* xz;
  const float* zx;
  const float* y;
  size_t stride;
  int xz_rows, y_rows;  // 2P, P
};

void products_scalar(const Operands& o, int i, int j, int count, float* g1, float* g2, float* g3) {
  for (int t = 0; t < count; ++t) {
    float s1 = 0.0f, s2 = 0.0f, s3 = 0.0f;
    for (int m = 0; m < o.xz_rows; ++m) {
      const size_t row = static_cast<size_t>(m) * o.stride;
      const float x = o.xz[row + static_cast<size_t>(i + t)];
      s1 = std::fma(x, o.xz[row + static_cast<size_t>(j + t)], s1);
      s2 = std::fma(x, o.zx[row + static_cast<size_t>(j + t)], s2);
    }
    for (int m = 0; m < o.y_rows; ++m) {
      const size_t row = static_cast<size_t>(m) * o.stride;
      s3 = std::fma(o.y[row + static_cast<size_t>(i + t)], o.y[row + static_cast<size_t>(j + t)], s3);
    }
    g1[t] = s1;
    g2[t] = s2;
    g3[t] = s3;
  }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// Sixteen frame pairs at a time, one per lane of two AVX registers: the same chains, in order.
// The rows are padded (kPadding zeros past the last frame), so the last group may read past
// `count` pairs: it stores only those.
__attribute__((target("avx2,fma"))) void products_avx2(const Operands& o, int i, int j, int count, float* g1,
                                                       float* g2, float* g3) {
  for (int t = 0; t < count; t += 16) {
    __m256 a1 = _mm256_setzero_ps(), b1 = a1, a2 = a1, b2 = a1, a3 = a1, b3 = a1;
    const float* xz = o.xz;
    const float* zx = o.zx;
    for (int m = 0; m < o.xz_rows; ++m, xz += o.stride, zx += o.stride) {
      const __m256 xi0 = _mm256_loadu_ps(xz + i + t), xi1 = _mm256_loadu_ps(xz + i + t + 8);
      a1 = _mm256_fmadd_ps(xi0, _mm256_loadu_ps(xz + j + t), a1);
      b1 = _mm256_fmadd_ps(xi1, _mm256_loadu_ps(xz + j + t + 8), b1);
      a2 = _mm256_fmadd_ps(xi0, _mm256_loadu_ps(zx + j + t), a2);
      b2 = _mm256_fmadd_ps(xi1, _mm256_loadu_ps(zx + j + t + 8), b2);
    }
    const float* y = o.y;
    for (int m = 0; m < o.y_rows; ++m, y += o.stride) {
      a3 = _mm256_fmadd_ps(_mm256_loadu_ps(y + i + t), _mm256_loadu_ps(y + j + t), a3);
      b3 = _mm256_fmadd_ps(_mm256_loadu_ps(y + i + t + 8), _mm256_loadu_ps(y + j + t + 8), b3);
    }
    alignas(32) float lanes[6][8];
    _mm256_store_ps(lanes[0], a1);
    _mm256_store_ps(lanes[1], b1);
    _mm256_store_ps(lanes[2], a2);
    _mm256_store_ps(lanes[3], b2);
    _mm256_store_ps(lanes[4], a3);
    _mm256_store_ps(lanes[5], b3);
    for (int l = 0; l < 16 && t + l < count; ++l) {
      g1[t + l] = lanes[l / 8][l % 8];
      g2[t + l] = lanes[2 + l / 8][l % 8];
      g3[t + l] = lanes[4 + l / 8][l % 8];
    }
  }
}

const bool kHasAvx2Fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#endif

void pair_products(const Operands& o, int i, int j, int count, float* g1, float* g2, float* g3) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  if (kHasAvx2Fma) return products_avx2(o, i, j, count, g1, g2, g3);
#endif
  products_scalar(o, i, j, count, g1, g2, g3);
}

constexpr int kPadding = 16;  // zeros after each point-major row

std::vector<float> point_major(const std::vector<float>& rows, int frames, int width) {
  const size_t stride = static_cast<size_t>(frames) + kPadding;
  std::vector<float> out(stride * static_cast<size_t>(width), 0.0f);
  constexpr int kBlock = 64;  // frames per block: both sides stay in cache
  for (int f0 = 0; f0 < frames; f0 += kBlock) {
    const int f1 = std::min(frames, f0 + kBlock);
    for (int m = 0; m < width; ++m) {
      for (int f = f0; f < f1; ++f) out[m * stride + static_cast<size_t>(f)] = rows[static_cast<size_t>(f) * width + m];
    }
  }
  return out;
}

}  // namespace

DiagonalRuns::DiagonalRuns(const FrameFeatures& features)
    : f_(features),
      xz_(point_major(features.xz, features.frames, 2 * features.points)),
      zx_(point_major(features.zx, features.frames, 2 * features.points)),
      y_(point_major(features.y, features.frames, features.points)) {}

void DiagonalRuns::distances(int a, int b, std::span<float> out) const {
  const FrameFeatures& f = f_;
  const int length = static_cast<int>(out.size());
  const int n = f.frames, k = f.window;
  assert(a >= 0 && b >= 0 && a + length <= n && b + length <= n);
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  // The frame pairs (a + t, b - k + 1 + t) for t = 0 .. length + k - 2; those before the
  // matrix's first frame or past its last belong to undefined pairs only.
  const int pairs = length + k - 1;
  std::vector<double> e1(static_cast<size_t>(pairs)), e2(e1.size()), e3(e1.size());
  // The frame pairs inside the matrix: t = inside .. last - 1.
  const int inside = std::max(0, k - 1 - b), last = std::min(pairs, n - a);
  std::vector<float> g(3 * static_cast<size_t>(std::max(0, last - inside)));
  float* g1 = g.data();
  float* g2 = g1 + (last - inside);
  float* g3 = g2 + (last - inside);
  const Operands operands{xz_.data(), zx_.data(), y_.data(), static_cast<size_t>(n) + kPadding, 2 * f.points, f.points};
  if (last > inside) pair_products(operands, a + inside, b - k + 1 + inside, last - inside, g1, g2, g3);
  const double v = f.point_weight_sum;
  for (int t = 0; t < pairs; ++t) {
    const int i = a + t, j = b - k + 1 + t;
    if (t < inside || t >= last) {
      e1[t] = e2[t] = e3[t] = 0.0;
      continue;
    }
    const Offsets o{f.root_x[i], f.root_z[i], f.moment_x[i], f.moment_z[i]};
    const double nvx = f.moment_x[j] + v * f.root_x[j], nvz = f.moment_z[j] + v * f.root_z[j];
    e1[t] = uncentred_e1(o, g1[t - inside], f.root_x[j], f.root_z[j], nvx, nvz);
    e2[t] = uncentred_e2(o, g2[t - inside], f.root_x[j], f.root_z[j], nvx, nvz);
    e3[t] = g3[t - inside];
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
