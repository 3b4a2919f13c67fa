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

// A float operand (xz, zx or y) in frame blocks: block B holds frames 64 B .. 64 B + 79 (zeros
// past the last), point-major within it (coordinate m of its 80 frames side by side). Sixteen
// consecutive frames from any frame on are so side by side in every coordinate row, and the
// rows a group reads lie close together (where a whole-matrix row would be a page apart).
constexpr int kBlockFrames = 64;
constexpr int kRowFrames = kBlockFrames + 16;

struct BlockedOperand {
  std::vector<float> data;
  int width = 0;  // coordinates per frame

  BlockedOperand(const std::vector<float>& rows, int frames, int w) : width(w) {
    const int blocks = (frames + kBlockFrames - 1) / kBlockFrames;
    data.assign(static_cast<size_t>(blocks) * width * kRowFrames, 0.0f);
    for (int block = 0; block < blocks; ++block) {
      float* out = &data[static_cast<size_t>(block) * width * kRowFrames];
      for (int c = 0; c < kRowFrames && block * kBlockFrames + c < frames; ++c) {
        const float* in = &rows[static_cast<size_t>(block * kBlockFrames + c) * width];
        for (int m = 0; m < width; ++m) out[static_cast<size_t>(m) * kRowFrames + c] = in[m];
      }
    }
  }
  // Coordinate 0 of `frame`; coordinate m is m * kRowFrames further, frame + 1 one further.
  const float* at(int frame) const {
    return &data[static_cast<size_t>(frame / kBlockFrames) * width * kRowFrames + frame % kBlockFrames];
  }
};

namespace {

struct Operands {
  const BlockedOperand& xz;
  const BlockedOperand& zx;
  const BlockedOperand& y;
};

// The three float products of the frame pairs (i + t, j + t), t = 0 .. count - 1, each a chain
// of fused multiply-adds over the coordinates in order: how BLAS's sgemm kernels accumulate an
// output (OpenBLAS's on x86-64, for most of a tile), so that D rounds close to the tiles'.
void products_scalar(const Operands& o, int i, int j, int count, float* g1, float* g2, float* g3) {
  for (int t = 0; t < count; ++t) {
    const float* xi = o.xz.at(i + t);
    const float* xj = o.xz.at(j + t);
    const float* zj = o.zx.at(j + t);
    float s1 = 0.0f, s2 = 0.0f, s3 = 0.0f;
    for (int m = 0; m < o.xz.width; ++m) {
      const size_t c = static_cast<size_t>(m) * kRowFrames;
      s1 = std::fma(xi[c], xj[c], s1);
      s2 = std::fma(xi[c], zj[c], s2);
    }
    const float* yi = o.y.at(i + t);
    const float* yj = o.y.at(j + t);
    for (int m = 0; m < o.y.width; ++m) {
      const size_t c = static_cast<size_t>(m) * kRowFrames;
      s3 = std::fma(yi[c], yj[c], s3);
    }
    g1[t] = s1;
    g2[t] = s2;
    g3[t] = s3;
  }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// Frame pairs t .. t + 8 L - 1, one per lane of L AVX registers per product: the same chains, in
// order. A group may read past `count` pairs (into the block's next frames or its zeros): it
// stores only those.
template <int L>
__attribute__((target("avx2,fma"))) inline void products_group(const Operands& o, int i, int j, int t, int count,
                                                               float* g1, float* g2, float* g3) {
  __m256 s1[L], s2[L], s3[L];
  for (int l = 0; l < L; ++l) s1[l] = s2[l] = s3[l] = _mm256_setzero_ps();
  const float* xi = o.xz.at(i + t);
  const float* xj = o.xz.at(j + t);
  const float* zj = o.zx.at(j + t);
  for (int m = 0; m < o.xz.width; ++m, xi += kRowFrames, xj += kRowFrames, zj += kRowFrames) {
    for (int l = 0; l < L; ++l) {
      const __m256 x = _mm256_loadu_ps(xi + 8 * l);
      s1[l] = _mm256_fmadd_ps(x, _mm256_loadu_ps(xj + 8 * l), s1[l]);
      s2[l] = _mm256_fmadd_ps(x, _mm256_loadu_ps(zj + 8 * l), s2[l]);
    }
  }
  const float* yi = o.y.at(i + t);
  const float* yj = o.y.at(j + t);
  for (int m = 0; m < o.y.width; ++m, yi += kRowFrames, yj += kRowFrames) {
    for (int l = 0; l < L; ++l) s3[l] = _mm256_fmadd_ps(_mm256_loadu_ps(yi + 8 * l), _mm256_loadu_ps(yj + 8 * l), s3[l]);
  }
  alignas(32) float lanes[3][8 * L];
  for (int l = 0; l < L; ++l) {
    _mm256_store_ps(&lanes[0][8 * l], s1[l]);
    _mm256_store_ps(&lanes[1][8 * l], s2[l]);
    _mm256_store_ps(&lanes[2][8 * l], s3[l]);
  }
  for (int l = 0; l < 8 * L && t + l < count; ++l) {
    g1[t + l] = lanes[0][l];
    g2[t + l] = lanes[1][l];
    g3[t + l] = lanes[2][l];
  }
}

// 32 pairs a group where more than 16 are left (eight independent chains keep the FMA units
// busy), else 16 (a block's 16 spare frames bound a group's reach).
__attribute__((target("avx2,fma"))) void products_avx2(const Operands& o, int i, int j, int count, float* g1,
                                                       float* g2, float* g3) {
  int t = 0;
  for (; count - t > 16; t += 32) {
    if ((i + t) % kBlockFrames <= kBlockFrames - 16 && (j + t) % kBlockFrames <= kBlockFrames - 16) {
      products_group<4>(o, i, j, t, count, g1, g2, g3);
    } else {
      products_group<2>(o, i, j, t, count, g1, g2, g3);
      products_group<2>(o, i, j, t + 16, count, g1, g2, g3);
    }
  }
  if (t < count) products_group<2>(o, i, j, t, count, g1, g2, g3);
}

const bool kHasAvx2Fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#endif

void pair_products(const Operands& o, int i, int j, int count, float* g1, float* g2, float* g3) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  if (kHasAvx2Fma) return products_avx2(o, i, j, count, g1, g2, g3);
#endif
  products_scalar(o, i, j, count, g1, g2, g3);
}

}  // namespace

DiagonalRuns::DiagonalRuns(const FrameFeatures& features)
    : f_(features),
      xz_(std::make_unique<BlockedOperand>(features.xz, features.frames, 2 * features.points)),
      zx_(std::make_unique<BlockedOperand>(features.zx, features.frames, 2 * features.points)),
      y_(std::make_unique<BlockedOperand>(features.y, features.frames, features.points)) {}

DiagonalRuns::~DiagonalRuns() = default;

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
  const size_t count = static_cast<size_t>(std::max(0, last - inside));
  std::vector<float> g(3 * count);
  float* g1 = g.data();
  float* g2 = count > 0 ? g1 + count : g1;
  float* g3 = count > 0 ? g2 + count : g1;
  const Operands operands{*xz_, *zx_, *y_};
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
