// A yaw-invariant embedding of frame windows whose distances bound the frame distance from
// below (DESIGN.md section 5c): the groundwork of a distance stage that computes only the
// pairs that can be transitions.
//
// For the window W_s of the k frames starting at s, F_s stacks, over its frames s+t and the
// cloud's points p, sqrt(u_t v_p) (y, r): the point's height and its floor distance from the
// frame's weighted floor centroid. Aligning each frame on its own can only lower the cost, and
// a rotation about y keeps y and r, so D(a, b) >= |F_a - F_{b-k+1}|^2 (D as the tiles compute
// it: pair a leaves, b arrives; DESIGN.md 3.1). A projection with orthonormal rows only
// shrinks distances, so it keeps the bound. Two are composed here, each a principal-component
// basis: per frame, the 2P values to per_frame_dims; per window, the k per_frame_dims values
// (each frame's times sqrt(u_t)) to dims. The bound is then |E_a - E_{b-k+1}|^2 in dims
// numbers per window: cheap to search by range.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/metric/frame_features.h"

namespace mg {

struct WindowEmbeddingSettings {
  int per_frame_dims = 8;  // principal components of each frame's 2P values kept
  int dims = 16;           // principal components of the window's kept
  // The covariances are estimated on at most this many frames and windows (evenly strided):
  // any orthonormal basis keeps the bound; more samples only fit it better.
  int max_samples = 20000;

  Status validate() const;
};

struct WindowEmbedding {
  int windows = 0;            // window starts 0..windows-1 (frames - k + 1)
  int dims = 0;
  int window = 0;             // k
  std::vector<float> coords;  // windows x dims, row s = E_s

  // |E_s - E_t|^2, in double.
  double bound(int s, int t) const;
};

Result<WindowEmbedding> make_window_embedding(const FrameFeatures& features,
                                              const WindowEmbeddingSettings& settings = {});

// The unprojected bound |F_a - F_{b-k+1}|^2 of pair (a, b), computed from its definition:
// the reference the embedding is tested against. O(k P).
double window_feature_bound(const FrameFeatures& features, int a, int b);

// Every pair (a, b) whose embedded bound is at most `ceiling` (D units), a able to leave and
// b able to arrive (FrameFeatures::can_leave, can_arrive): the pairs that can have D <= ceiling.
// Found by balls of consecutive windows (a fifth of the window, at least 4, and 8 such: the
// motion is smooth, so they are small), pairs of balls too far apart for any pair within
// sqrt(ceiling) skipped by the triangle inequality, the pairs of the rest summed with an
// early exit.
struct BoundedPairStatistics {
  long long pairs = 0;    // visited
  long long scanned = 0;  // windows whose bound was (partly) summed
};
// The search runs on `threads` threads (0: one per core); visit is called on the caller's,
// once per leaving frame a with any, with its arrival frames b in increasing order.
using BoundedPairVisitor = std::function<void(int a, std::span<const int> arrivals)>;
BoundedPairStatistics for_each_bounded_pair(const FrameFeatures& features, const WindowEmbedding& embedding,
                                            double ceiling, const BoundedPairVisitor& visit, int threads = 0);

}  // namespace mg
