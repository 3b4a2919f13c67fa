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
// numbers per window: cheap to search by range (bounded_tiles.h).
#pragma once

#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/metric/frame_features.h"

namespace mg {

struct WindowEmbeddingSettings {
  // Principal components of each frame's 2P values kept; 0: 320 / k, from 8 to 16 (so that
  // the window's basis is found among at most 320 values). Measured on the 8-subject library
  // (docs/performance.md): at 30 fps 16 leave 16 % fewer tiles to the pruned stage than 8 did.
  int per_frame_dims = 0;
  int dims = 24;  // principal components of the window's kept
  // The covariances are estimated on at most this many frames and windows (evenly strided):
  // any orthonormal basis keeps the bound; more samples only fit it better.
  int max_samples = 2000;

  Status validate() const;
  int per_frame_dims_for(int window) const;
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

}  // namespace mg
