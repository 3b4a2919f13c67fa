// D along a diagonal run of pairs, (a + m, b + m) for m = 0..length-1, computed as the tiles
// compute it (distance_tiles.h) but for those pairs only: the pruned distance stage's exact
// evaluation of the candidates its bounds leave (DESIGN.md section 5c).
//
// Each frame pair on the diagonal is visited once. Its three cross sums are float32 dot
// products of the centred clouds, each a chain of fused multiply-adds in the coordinates'
// order, the order in which OpenBLAS's sgemm kernels sum most outputs of a tile (its kernels at
// a tile's edges sum otherwise), so that D comes as close to the tiles' as theirs with another
// tile size does (window sums still slide from other starts). They are
// taken 16 or 32 frame pairs at a time from copies of the clouds in blocks of frames,
// point-major within a block (AVX2 where the machine has it, the same chains in scalar code
// elsewhere). The references' offsets are added back in double (metric/closed_form.h), and the
// window sums slide along the diagonal (a uniform taper adds one frame pair and drops one per
// step; a Hann taper sums its k). A run of length L so costs L + k - 1 frame-pair products, not
// k L. The values agree with the tiles' to float rounding (tests: within 1e-4 of the larger of
// D and the median D).
#pragma once

#include <memory>
#include <span>

#include "motiongraph/metric/frame_features.h"

namespace mg {

struct BlockedOperand;  // diagonal_runs.cpp

class DiagonalRuns {
 public:
  // Keeps a reference to `features` and copies of its float operands in blocks of frames
  // (1.25 times the memory of xz, zx and y).
  explicit DiagonalRuns(const FrameFeatures& features);
  ~DiagonalRuns();

  // out[m] = D(a + m, b + m), NaN where the pair is undefined (a window leaving its clip or the
  // matrix). Needs 0 <= a, 0 <= b, a + out.size() <= frames and b + out.size() <= frames.
  // Thread-safe.
  void distances(int a, int b, std::span<float> out) const;

 private:
  const FrameFeatures& f_;
  std::unique_ptr<BlockedOperand> xz_, zx_, y_;
};

}  // namespace mg
