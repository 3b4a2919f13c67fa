// The yaw-invariant window embedding: per-frame heights and centroid distances, two principal-
// component projections.
#include "motiongraph/metric/window_embedding.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Dense>


namespace mg {

namespace {

// Each frame's 2P values: sqrt(v_p) y_p, then sqrt(v_p) r_p with r_p the floor distance of
// point p from the frame's weighted floor centroid.
void frame_values(const FrameFeatures& f, int frame, double* out) {
  const size_t P = static_cast<size_t>(f.points);
  const double cx = f.moment_x[frame] / f.point_weight_sum, cz = f.moment_z[frame] / f.point_weight_sum;
  const float* y = &f.y[frame * P];
  const float* xz = &f.xz[frame * 2 * P];
  for (size_t p = 0; p < P; ++p) {
    const double w = std::sqrt(f.point_weights[p]);
    out[p] = y[p];
    const double dx = xz[2 * p] - w * cx, dz = xz[2 * p + 1] - w * cz;
    out[P + p] = std::sqrt(dx * dx + dz * dz);
  }
}

// The top `dims` principal directions (as rows) of the rows sample(i, row) for i in 0..count-1
// (every one when count is small, else evenly strided), and the rows' mean.
struct Basis {
  Eigen::MatrixXd rows;  // dims x n
  Eigen::VectorXd mean;  // n
};

template <typename Sample>
Basis principal_basis(int count, int n, int dims, int max_samples, const Sample& sample) {
  const int step = std::max(1, (count + max_samples - 1) / max_samples);
  Eigen::MatrixXd sum_squares = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n);
  constexpr int kBlock = 1024;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block(kBlock, n);  // rows contiguous
  long long samples = 0;
  int filled = 0;
  auto flush = [&] {
    if (filled == 0) return;
    sum_squares.selfadjointView<Eigen::Lower>().rankUpdate(block.topRows(filled).transpose());
    sum += block.topRows(filled).colwise().sum().transpose();
    samples += filled;
    filled = 0;
  };
  for (int i = 0; i < count; i += step) {
    sample(i, block.row(filled).data(), block.cols());
    if (++filled == kBlock) flush();
  }
  flush();
  Basis basis;
  basis.mean = sum / static_cast<double>(std::max<long long>(samples, 1));
  Eigen::MatrixXd covariance = sum_squares.selfadjointView<Eigen::Lower>();
  covariance -= static_cast<double>(samples) * basis.mean * basis.mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
  // Eigenvalues ascend: the last `dims` eigenvectors, largest first. They are orthonormal
  // (a symmetric matrix's), which is all the bound needs.
  basis.rows = solver.eigenvectors().rightCols(dims).rowwise().reverse().transpose();
  return basis;
}

}  // namespace

Status WindowEmbeddingSettings::validate() const {
  if (per_frame_dims < 0) return Error{"", 0, "the embedding's dimensions per frame must be >= 0 (0: automatic)"};
  if (dims < 1) return Error{"", 0, "the embedding needs at least 1 dimension"};
  if (max_samples < 1) return Error{"", 0, "the embedding needs at least 1 sample"};
  return Ok{};
}

int WindowEmbeddingSettings::per_frame_dims_for(int window) const {
  return per_frame_dims > 0 ? per_frame_dims : std::clamp(320 / std::max(1, window), 8, 16);
}

double WindowEmbedding::bound(int s, int t) const {
  const float* x = &coords[static_cast<size_t>(s) * dims];
  const float* y = &coords[static_cast<size_t>(t) * dims];
  double sum = 0.0;
  for (int d = 0; d < dims; ++d) {
    const double diff = static_cast<double>(x[d]) - y[d];
    sum += diff * diff;
  }
  return sum;
}

Result<WindowEmbedding> make_window_embedding(const FrameFeatures& features, const WindowEmbeddingSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  const int k = features.window;
  if (k < 1 || features.frames < k || features.points < 1) {
    return Error{"", 0, "the embedding needs at least one window of frames and one point"};
  }
  const int n_frame = 2 * features.points;
  const int d1 = std::min(settings.per_frame_dims_for(k), n_frame);
  const Basis frame_basis = principal_basis(features.frames, n_frame, d1, settings.max_samples,
                                            [&](int f, double* out, Eigen::Index) { frame_values(features, f, out); });
  // Each frame projected: Q (f - mean).
  Eigen::MatrixXd projected(d1, features.frames);
  {
    Eigen::VectorXd values(n_frame);
    for (int f = 0; f < features.frames; ++f) {
      frame_values(features, f, values.data());
      projected.col(f) = frame_basis.rows * (values - frame_basis.mean);
    }
  }
  std::vector<double> root_taper(features.taper.size());
  std::transform(features.taper.begin(), features.taper.end(), root_taper.begin(), [](double u) { return std::sqrt(u); });
  const int windows = features.frames - k + 1;
  const int n_window = k * d1;
  auto window_values = [&](int s, double* out, Eigen::Index) {
    for (int t = 0; t < k; ++t) {
      for (int d = 0; d < d1; ++d) out[t * d1 + d] = root_taper[t] * projected(d, s + t);
    }
  };
  const int dims = std::min(settings.dims, n_window);
  const Basis window_basis = principal_basis(windows, n_window, dims, settings.max_samples, window_values);

  WindowEmbedding out;
  out.windows = windows;
  out.dims = dims;
  out.window = k;
  out.coords.resize(static_cast<size_t>(windows) * dims);
  Eigen::VectorXd values(n_window);
  for (int s = 0; s < windows; ++s) {
    window_values(s, values.data(), n_window);
    const Eigen::VectorXd e = window_basis.rows * (values - window_basis.mean);
    for (int d = 0; d < dims; ++d) out.coords[static_cast<size_t>(s) * dims + d] = static_cast<float>(e[d]);
  }
  return out;
}

double window_feature_bound(const FrameFeatures& features, int a, int b) {
  const int k = features.window;
  const int arrive = b - k + 1;
  const size_t n = 2 * static_cast<size_t>(features.points);
  std::vector<double> x(n), y(n);
  double sum = 0.0;
  for (int t = 0; t < k; ++t) {
    frame_values(features, a + t, x.data());
    frame_values(features, arrive + t, y.data());
    double frame_sum = 0.0;
    for (size_t i = 0; i < n; ++i) frame_sum += (x[i] - y[i]) * (x[i] - y[i]);
    sum += features.taper[t] * frame_sum;
  }
  return sum;
}

}  // namespace mg
