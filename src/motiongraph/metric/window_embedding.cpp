// The window embedding: each frame's floor coordinates (complex) and heights projected on
// principal components, then each window's.
#include "motiongraph/metric/window_embedding.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include <Eigen/Dense>

#include "motiongraph/core/parallel_for.h"

namespace mg {

namespace {

using Complex = std::complex<double>;

// The top `dims` principal directions (as rows, orthonormal) of the rows sample(i, row) for i
// in 0..count-1 (every one when count is small, else evenly strided), and the rows' mean: the
// eigenvectors of their covariance about the mean (centred) or of their second moments about
// zero (not centred: the projection is then linear, as the complex part needs). Complex rows
// give a Hermitian matrix; the rows of the basis are its eigenvectors' adjoints.
template <typename Scalar>
struct Basis {
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> rows;  // dims x n
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> mean;               // n (zero when not centred)
};

template <typename Scalar, typename Sample>
Basis<Scalar> principal_basis(int count, int n, int dims, int max_samples, bool centred, const Sample& sample) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const int step = std::max(1, (count + max_samples - 1) / max_samples);
  Matrix sum_squares = Matrix::Zero(n, n);
  Vector sum = Vector::Zero(n);
  constexpr int kBlock = 1024;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block(kBlock, n);  // rows contiguous
  long long samples = 0;
  int filled = 0;
  auto flush = [&] {
    if (filled == 0) return;
    // Adds the sum of x x^H over the block's rows x.
    sum_squares.template selfadjointView<Eigen::Lower>().rankUpdate(block.topRows(filled).transpose());
    sum += block.topRows(filled).colwise().sum().transpose();
    samples += filled;
    filled = 0;
  };
  for (int i = 0; i < count; i += step) {
    sample(i, block.row(filled).data());
    if (++filled == kBlock) flush();
  }
  flush();
  Basis<Scalar> basis;
  basis.mean = centred ? Vector(sum / static_cast<double>(std::max<long long>(samples, 1))) : Vector(Vector::Zero(n));
  Matrix covariance = sum_squares.template selfadjointView<Eigen::Lower>();
  covariance -= static_cast<double>(samples) * basis.mean * basis.mean.adjoint();
  Eigen::SelfAdjointEigenSolver<Matrix> solver(covariance);
  // Eigenvalues ascend: the last `dims` eigenvectors, largest first.
  basis.rows = solver.eigenvectors().rightCols(dims).rowwise().reverse().adjoint();
  return basis;
}

}  // namespace

Status WindowEmbeddingSettings::validate() const {
  if (per_frame_dims < 0) return Error{"", 0, "the embedding's dimensions per frame must be >= 0 (0: automatic)"};
  if (dims < 1) return Error{"", 0, "the embedding needs at least 1 dimension"};
  if (max_samples < 1) return Error{"", 0, "the embedding needs at least 1 sample"};
  if (threads < 0) return Error{"", 0, "threads must be >= 0 (0: one per core)"};
  return Ok{};
}

int WindowEmbeddingSettings::per_frame_dims_for(int window) const {
  return per_frame_dims > 0 ? per_frame_dims : std::clamp(240 / std::max(1, window), 6, 12);
}

double WindowEmbedding::bound(int s, int t) const {
  return rotation_distance_squared(&coords[static_cast<size_t>(s) * stride()], norms[static_cast<size_t>(s)],
                                   &coords[static_cast<size_t>(t) * stride()], norms[static_cast<size_t>(t)], dims);
}

Result<WindowEmbedding> make_window_embedding(const FrameFeatures& f, const WindowEmbeddingSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  const int k = f.window, n = f.frames, points = f.points;
  if (k < 1 || n < k || points < 1) {
    return Error{"", 0, "the embedding needs at least one window of frames and one point"};
  }
  const size_t P = static_cast<size_t>(points);
  const int d1 = std::min(settings.per_frame_dims_for(k), points);
  // Per frame: the centred floor coordinates sqrt(v) (cx + i cz) and the heights sqrt(v) y.
  auto frame_floor = [&](int frame, Complex* out) {
    const float* xz = &f.xz[static_cast<size_t>(frame) * 2 * P];
    for (size_t p = 0; p < P; ++p) out[p] = Complex(xz[2 * p], xz[2 * p + 1]);
  };
  auto frame_heights = [&](int frame, double* out) {
    const float* y = &f.y[static_cast<size_t>(frame) * P];
    for (size_t p = 0; p < P; ++p) out[p] = y[p];
  };
  const Basis<Complex> floor_basis = principal_basis<Complex>(n, points, d1, settings.max_samples, false, frame_floor);
  const Basis<double> height_basis = principal_basis<double>(n, points, d1, settings.max_samples, true, frame_heights);
  // Every frame projected, and the projection of the weights' square roots (a translation of
  // the frame's floor coordinates by c adds c times it).
  Eigen::MatrixXcd floor(d1, n);
  Eigen::MatrixXd heights(d1, n);
  parallel_for(n, worker_threads(settings.threads), 256, [&](int, long long i) {
    const int frame = static_cast<int>(i);
    Eigen::VectorXcd values(points);
    Eigen::VectorXd y(points);
    frame_floor(frame, values.data());
    frame_heights(frame, y.data());
    floor.col(frame) = floor_basis.rows * values;
    heights.col(frame) = height_basis.rows * (y - height_basis.mean);
  });
  Eigen::VectorXcd root_weights(points);
  for (int p = 0; p < points; ++p) root_weights[p] = std::sqrt(f.point_weights[static_cast<size_t>(p)]);
  const Eigen::VectorXcd shift = floor_basis.rows * root_weights;
  std::vector<double> root_taper(f.taper.size());
  std::transform(f.taper.begin(), f.taper.end(), root_taper.begin(), [](double u) { return std::sqrt(u); });
  // Window s: frame s + t's values times sqrt(u_t), its floor coordinates moved from the
  // frame's reference (root) to the window's weighted centroid.
  const int windows = n - k + 1;
  const int n_window = k * d1;
  auto window_floor = [&](int s, Complex* out) {
    const Complex centroid(f.window_x[static_cast<size_t>(s)] / f.window_weight,
                           f.window_z[static_cast<size_t>(s)] / f.window_weight);
    for (int t = 0; t < k; ++t) {
      const int frame = s + t;
      const Complex offset =
          Complex(f.root_x[static_cast<size_t>(frame)], f.root_z[static_cast<size_t>(frame)]) - centroid;
      for (int d = 0; d < d1; ++d) out[t * d1 + d] = root_taper[t] * (floor(d, frame) + offset * shift[d]);
    }
  };
  auto window_heights = [&](int s, double* out) {
    for (int t = 0; t < k; ++t) {
      for (int d = 0; d < d1; ++d) out[t * d1 + d] = root_taper[t] * heights(d, s + t);
    }
  };
  const int dims = std::min(settings.dims, n_window);
  const Basis<Complex> window_floor_basis =
      principal_basis<Complex>(windows, n_window, dims, settings.max_samples, false, window_floor);
  const Basis<double> window_height_basis =
      principal_basis<double>(windows, n_window, dims, settings.max_samples, true, window_heights);

  WindowEmbedding out;
  out.windows = windows;
  out.dims = dims;
  out.window = k;
  out.coords.resize(static_cast<size_t>(windows) * out.stride());
  out.norms.resize(static_cast<size_t>(windows));
  parallel_for(windows, worker_threads(settings.threads), 256, [&](int, long long i) {
    const int s = static_cast<int>(i);
    Eigen::VectorXcd floor_values(n_window);
    Eigen::VectorXd height_values(n_window);
    window_floor(s, floor_values.data());
    window_heights(s, height_values.data());
    const Eigen::VectorXcd e = window_floor_basis.rows * floor_values;
    const Eigen::VectorXd h = window_height_basis.rows * (height_values - window_height_basis.mean);
    float* row = &out.coords[static_cast<size_t>(s) * out.stride()];
    double norm = 0.0;
    for (int d = 0; d < dims; ++d) {
      row[2 * d] = static_cast<float>(e[d].real());
      row[2 * d + 1] = static_cast<float>(e[d].imag());
      norm += static_cast<double>(row[2 * d]) * row[2 * d] + static_cast<double>(row[2 * d + 1]) * row[2 * d + 1];
      row[2 * dims + d] = static_cast<float>(h[d]);
    }
    out.norms[static_cast<size_t>(s)] = norm;
  });
  return out;
}

}  // namespace mg
