// The yaw-invariant window embedding: per-frame heights and centroid distances, two principal-
// component projections, and a range search over the first coordinate.
#include "motiongraph/metric/window_embedding.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

#include <Eigen/Dense>

#include "motiongraph/core/parallel_for.h"

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
    out[P + p] = std::hypot(xz[2 * p] - w * cx, xz[2 * p + 1] - w * cz);
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
  if (per_frame_dims < 1) return Error{"", 0, "the embedding needs at least 1 dimension per frame"};
  if (dims < 1) return Error{"", 0, "the embedding needs at least 1 dimension"};
  if (max_samples < 1) return Error{"", 0, "the embedding needs at least 1 sample"};
  return Ok{};
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
  const int d1 = std::min(settings.per_frame_dims, n_frame);
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

namespace {

// Consecutive windows in balls: a centre and the radius that holds them.
struct Ball {
  int begin = 0, end = 0;       // window starts
  std::vector<double> centre;   // dims
  double radius = 0.0;
};

std::vector<Ball> balls_of(const WindowEmbedding& e, int size) {
  std::vector<Ball> balls;
  const int dims = e.dims;
  for (int begin = 0; begin < e.windows; begin += size) {
    Ball ball;
    ball.begin = begin;
    ball.end = std::min(e.windows, begin + size);
    ball.centre.assign(dims, 0.0);
    for (int s = ball.begin; s < ball.end; ++s) {
      for (int d = 0; d < dims; ++d) ball.centre[d] += e.coords[static_cast<size_t>(s) * dims + d];
    }
    for (double& c : ball.centre) c /= ball.end - ball.begin;
    for (int s = ball.begin; s < ball.end; ++s) {
      double sum = 0.0;
      for (int d = 0; d < dims; ++d) {
        const double diff = e.coords[static_cast<size_t>(s) * dims + d] - ball.centre[d];
        sum += diff * diff;
      }
      ball.radius = std::max(ball.radius, std::sqrt(sum));
    }
    balls.push_back(std::move(ball));
  }
  return balls;
}

// Whether two balls can hold a pair within `radius` of each other (a hair of slack: exact
// decisions are the pairs' own).
bool may_meet(const Ball& x, const Ball& y, double radius) {
  double sum = 0.0;
  for (size_t d = 0; d < x.centre.size(); ++d) sum += (x.centre[d] - y.centre[d]) * (x.centre[d] - y.centre[d]);
  const double reach = radius + x.radius + y.radius;
  return sum <= reach * reach * (1.0 + 1e-9) + 1e-12;
}

constexpr int kBallsPerGroup = 8;  // small balls per large one

}  // namespace

BoundedPairStatistics for_each_bounded_pair(const FrameFeatures& features, const WindowEmbedding& embedding,
                                            double ceiling, const BoundedPairVisitor& visit, int threads) {
  const int dims = embedding.dims;
  const int k = embedding.window;
  const double radius = std::sqrt(std::max(ceiling, 0.0));
  // Consecutive windows lie close together (the motion is smooth): small balls of a fifth of
  // the window, at least 4 (8 windows at 120 fps, 4 at 30 fps: on the 8-subject set at 30 fps
  // 2 made the search 1.7x slower, 8 1.3x), large ones of 8 small, pruned pairwise by the
  // triangle inequality before any pair is summed.
  const int ball = std::max(4, k / 5);
  const std::vector<Ball> small = balls_of(embedding, ball);
  const std::vector<Ball> large = balls_of(embedding, ball * kBallsPerGroup);
  // The arrivals of each leaving window of large ball gi (found in increasing order).
  struct GroupResult {
    std::vector<std::vector<int>> arrivals;
    long long scanned = 0;
  };
  auto search_group = [&](size_t gi, GroupResult& r) {
    const Ball& leaving = large[gi];
    r.arrivals.assign(static_cast<size_t>(leaving.end - leaving.begin), {});
    r.scanned = 0;
    for (size_t gj = 0; gj < large.size(); ++gj) {
      if (!may_meet(leaving, large[gj], radius)) continue;
      for (size_t i = gi * kBallsPerGroup; i < std::min(small.size(), (gi + 1) * kBallsPerGroup); ++i) {
        for (size_t j = gj * kBallsPerGroup; j < std::min(small.size(), (gj + 1) * kBallsPerGroup); ++j) {
          if (!may_meet(small[i], small[j], radius)) continue;
          for (int a = small[i].begin; a < small[i].end; ++a) {
            if (!features.can_leave[a]) continue;
            const float* ea = &embedding.coords[static_cast<size_t>(a) * dims];
            for (int s = small[j].begin; s < small[j].end; ++s) {
              if (!features.can_arrive[s + k - 1]) continue;
              ++r.scanned;
              const float* es = &embedding.coords[static_cast<size_t>(s) * dims];
              double sum = 0.0;
              for (int d = 0; d < dims && sum <= ceiling; ++d) {
                const double diff = static_cast<double>(ea[d]) - es[d];
                sum += diff * diff;
              }
              if (sum <= ceiling) r.arrivals[a - leaving.begin].push_back(s + k - 1);
            }
          }
        }
      }
    }
  };
  // Large balls are searched on the threads a batch at a time, then visited in order.
  const int workers = worker_threads(threads);
  const size_t batch = static_cast<size_t>(4 * workers);
  BoundedPairStatistics stats;
  std::vector<GroupResult> results(batch);
  for (size_t first = 0; first < large.size(); first += batch) {
    const size_t end = std::min(large.size(), first + batch);
    parallel_for(static_cast<long long>(end - first), workers, 1,
                 [&](int, long long i) { search_group(first + static_cast<size_t>(i), results[static_cast<size_t>(i)]); });
    for (size_t g = first; g < end; ++g) {
      GroupResult& r = results[g - first];
      stats.scanned += r.scanned;
      for (size_t i = 0; i < r.arrivals.size(); ++i) {
        std::vector<int>& list = r.arrivals[i];
        if (list.empty()) continue;
        // Already in increasing order: large balls, small balls and windows are each scanned
        // in order of their frames.
        assert(std::is_sorted(list.begin(), list.end()));
        visit(large[g].begin + static_cast<int>(i), list);
        stats.pairs += static_cast<long long>(list.size());
      }
    }
  }
  return stats;
}

}  // namespace mg
