// D along a diagonal run of pairs, (a + m, b + m) for m = 0..length-1, computed as the tiles
// compute it (distance_tiles.h) but for those pairs only: the pruned distance stage's exact
// evaluation of the candidates its bounds leave (DESIGN.md section 5c).
//
// Each frame pair on the diagonal is visited once: its three cross sums are float32 dot
// products of the centred clouds (as the tiles' BLAS products are), the references' offsets
// are added back in double (metric/closed_form.h), and the window sums slide along the
// diagonal (a uniform taper adds one frame pair and drops one per step; a Hann taper sums its
// k). A run of length L so costs L + k - 1 frame-pair products, not k L. The values agree with
// the tiles' to float rounding (the products' summation order differs from BLAS's).
#pragma once

#include <span>

#include "motiongraph/metric/frame_features.h"

namespace mg {

// out[m] = D(a + m, b + m), NaN where the pair is undefined (a window leaving its clip or the
// matrix). Needs 0 <= a, 0 <= b, a + out.size() <= frames and b + out.size() <= frames.
void diagonal_run_distances(const FrameFeatures& features, int a, int b, std::span<float> out);

}  // namespace mg
