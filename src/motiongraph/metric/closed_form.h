// The closed form of the floor-aligned window distance (DESIGN.md 3.2-3.3), the tiles'
// (distance_tiles) per-pair step, kept apart from them so that the offsets and the closed form
// read as the design states them.
#pragma once

#include <cmath>
#include <span>

namespace mg {

// The departure window's terms of the closed form.
struct RowTerms {
  double x = 0.0, z = 0.0;  // X, Z
  double square = 0.0;      // S - (X^2 + Z^2) / W
  double inv_w = 0.0;       // 1 / W
};

// A window's one-window term S - (X^2 + Z^2) / W, from its uncentred sums.
inline double centred_window_square(double square, double x, double z, double inv_w) {
  return square - (x * x + z * z) * inv_w;
}

// Whether every weight of the taper is the same (then window sums can slide: one frame pair
// in, one out).
inline bool uniform_taper(std::span<const double> taper) {
  for (double u : taper) {
    if (u != taper[0]) return false;
  }
  return true;
}

// DESIGN.md 3.2, with the one-window terms S - (X^2 + Z^2) / W precomputed (square2 for the
// arrival window). Branch-free, so that the loops calling it vectorise: max(0, d) is written
// (d + |d|) / 2, exact in floating point (a select would need -fno-trapping-math).
inline float closed_form(double c1, double c2, double c3, const RowTerms& row, double x2, double z2, double square2) {
  const double big_a = c1 - (row.x * x2 + row.z * z2) * row.inv_w;
  const double big_b = c2 - (row.x * z2 - row.z * x2) * row.inv_w;
  const double d = row.square + square2 - 2.0 * c3 - 2.0 * std::sqrt(big_a * big_a + big_b * big_b);
  return static_cast<float>(0.5 * (d + std::fabs(d)));
}

// A departure frame's reference r and centred first moment m.
struct Offsets {
  double rx = 0.0, rz = 0.0, mx = 0.0, mz = 0.0;
};

// The uncentred cross sums of one frame pair (DESIGN.md 3.3) from the float products of the
// centred clouds g1, g2 and the arrival frame's reference (sx, sz) and n + V s (nvx, nvz):
// r.n' + m.s' + V r.s' = r.(n' + V s') + m.s', and likewise for the cross term.
inline double uncentred_e1(const Offsets& o, float g1, double sx, double sz, double nvx, double nvz) {
  return g1 + (o.rx * nvx + o.rz * nvz) + (o.mx * sx + o.mz * sz);
}
inline double uncentred_e2(const Offsets& o, float g2, double sx, double sz, double nvx, double nvz) {
  return g2 + (o.rx * nvz - o.rz * nvx) + (o.mx * sz - o.mz * sx);
}

}  // namespace mg
