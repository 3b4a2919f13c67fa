// An embedding of frame windows whose distances bound the frame distance from below (DESIGN.md
// section 5c): what lets the pruned distance stage skip the tiles that cannot hold a transition.
//
// D(a, b) aligns the arriving window on the leaving one by one rotation about y and one floor
// translation (DESIGN.md 3.1-3.2). Write a window's floor coordinates, centred on its weighted
// floor centroid, as complex numbers sqrt(u_t v_p) (x + i z), and its heights as real numbers
// sqrt(u_t v_p) y: then D(a, b) = min over theta of |X_a - e^(i theta) X_b|^2 + |Y_a - Y_b|^2
// (the translation is the centroids'). A complex-linear map commutes with e^(i theta), and a
// map with orthonormal rows only shrinks distances, so projecting X with such a map and Y with
// a real one keeps a lower bound:
//   D(a, b) >= min_theta |E_a - e^(i theta) E_b|^2 + |F_a - F_b|^2
//            = |E_a|^2 + |E_b|^2 - 2 |<E_a, E_b>| + |F_a - F_b|^2.
// Its square root is a distance between windows up to rotation (the triangle inequality holds),
// so balls of windows prune a range search (bounded_tiles.h). Two principal-component bases
// are composed for each part: per frame, the P points to per_frame_dims; per window, the k
// frames' values to dims (the complex ones uncentred, so that the map stays linear). Unlike a
// rotation-invariant embedding (each frame's heights and distances from its centroid, the first
// version here), this one keeps how the points lie around each other and that one rotation
// serves the whole window: on the 8-subject library it leaves half the tiles that one did
// (docs/performance.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/metric/frame_features.h"

namespace mg {

struct WindowEmbeddingSettings {
  // Principal components of each frame's P values kept (for the floor coordinates and for the
  // heights each); 0: 240 / k, from 6 to 12 (the window's bases are then found among at most
  // 240 values; measured in docs/performance.md).
  int per_frame_dims = 0;
  int dims = 24;  // principal components of the window's kept, for each part
  // The covariances are estimated on at most this many frames and windows (evenly strided):
  // any basis with orthonormal rows keeps the bound; more samples only fit it better.
  int max_samples = 2000;
  int threads = 0;  // for projecting the frames and windows; 0: one per core

  Status validate() const;
  int per_frame_dims_for(int window) const;
};

struct WindowEmbedding {
  int windows = 0;  // window starts 0..windows-1 (frames - k + 1)
  int dims = 0;     // complex coordinates E (floor) and real coordinates F (heights), each
  int window = 0;   // k
  // Row s: E_s as dims (real, imaginary) pairs, then F_s; stride() floats.
  std::vector<float> coords;
  std::vector<double> norms;  // |E_s|^2 from the stored floats

  int stride() const { return 3 * dims; }
  // The bound above for windows s and t, in double from the stored floats (>= 0).
  double bound(int s, int t) const;
};

// The squared distance up to rotation of two points x, y of the embedding's space (dims
// complex coordinates as (real, imaginary) pairs, then dims real ones; nx, ny their complex
// parts' squared norms): min over theta of |x - e^(i theta) y|^2 for the complex part, plus
// the real part's squared distance. In double, whatever the points are stored in.
template <typename X, typename Y>
double rotation_distance_squared(const X* x, double nx, const Y* y, double ny, int dims) {
  double re = 0.0, im = 0.0, heights = 0.0;
  for (int d = 0; d < dims; ++d) {
    // <x, y> = sum conj(x) y.
    const double xr = x[2 * d], xi = x[2 * d + 1], yr = y[2 * d], yi = y[2 * d + 1];
    re += xr * yr + xi * yi;
    im += xr * yi - xi * yr;
  }
  for (int d = 2 * dims; d < 3 * dims; ++d) {
    const double diff = static_cast<double>(x[d]) - static_cast<double>(y[d]);
    heights += diff * diff;
  }
  return std::max(0.0, nx + ny - 2.0 * std::sqrt(re * re + im * im)) + heights;
}

Result<WindowEmbedding> make_window_embedding(const FrameFeatures& features,
                                              const WindowEmbeddingSettings& settings = {});

}  // namespace mg
