// What the frame distance needs from each frame, computed once for the whole database
// (DESIGN.md sections 3.2-3.3).
//
// For frame f with cloud points p_i (metres, world) and point weights v_i, the reference r_f
// is the root's floor position (x, z). The points are centred on it in the floor plane,
// c_i = p_i - r_f (y kept), and stored as float32 matrices for BLAS:
//   xz row f = sqrt(v_i) * (cx_i, cz_i) interleaved  (N x 2P)
//   zx row f = sqrt(v_i) * (cz_i, -cx_i)             (N x 2P)
//   y  row f = sqrt(v_i) * y_i                        (N x P)
// so that xz*xz^T, xz*zx^T and y*y^T give the centred cross sums. Beside them, in double:
// r_f, the centred first moments M_f = sum v c (x, z), Q_f = sum v |c|^2, and per window
// (frames a..a+k-1, taper u_t) the uncentred sums W, X, Z, S of the closed form.
#pragma once

#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/metric/point_cloud.h"

namespace mg {

struct DistanceSettings {
  enum class Taper { kUniform, kHann };
  int window_frames = 0;       // k, the blend length; 0 = a third of a second at the db's fps
  Taper taper = Taper::kUniform;
  int tile_frames = 1024;      // side of the square tiles of the pair matrix
  int threads = 0;             // worker threads; 0 = one per core

  Status validate() const;
  int window_for(double fps) const;
};

// The taper u_t over a window of k frames (all 1 for kUniform; a raised cosine, never 0, for
// kHann).
std::vector<double> window_weights(int k, DistanceSettings::Taper taper);

struct FrameFeatures {
  int frames = 0;
  int points = 0;
  int window = 0;                       // k
  std::vector<double> taper;            // u_t, k values
  std::vector<double> point_weights;    // v_i, P values
  double point_weight_sum = 0.0;        // V
  std::vector<float> xz, zx, y;         // BLAS operands, see above
  std::vector<double> root_x, root_z, moment_x, moment_z, square_sum;  // per frame
  std::vector<char> can_leave;          // a..a+k-1 inside a's clip
  std::vector<char> can_arrive;         // b-k+1..b inside b's clip
  // Sums over the window starting at frame f (f..f+k-1), uncentred, weights u_t v_i:
  std::vector<double> window_x, window_z, window_square;  // X, Z, S
  double window_weight = 0.0;                              // W = (sum u) V
  std::vector<int> clip_of_frame;
  // The tags every frame of the leaving window a..a+k-1 carries (0 where it cannot leave), and
  // of the arriving window b-k+1..b: the distance stage's per-tag histograms (candidates.h).
  std::vector<TagMask> leave_tags, arrive_tags;
};

Result<FrameFeatures> make_frame_features(const MotionDatabase& db, const CloudLayout& layout,
                                          const DistanceSettings& settings);

}  // namespace mg
