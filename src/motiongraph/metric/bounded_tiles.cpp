// The tiles the window embedding's bound cannot rule out: balls of windows, tile by tile.
#include "motiongraph/metric/bounded_tiles.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "motiongraph/core/parallel_for.h"

namespace mg {

namespace {

// Windows [begin, end) in a ball: their mean as centre (any point of the space will do: the
// distance up to rotation obeys the triangle inequality; consecutive windows face alike, so
// their mean lies close to them all) and the radius that holds them.
struct Ball {
  std::vector<double> centre;
  double norm = 0.0;  // the centre's complex part's squared norm
  double radius = 0.0;
};

Ball ball_of(const WindowEmbedding& e, int begin, int end) {
  const int stride = e.stride();
  Ball ball;
  ball.centre.assign(static_cast<size_t>(stride), 0.0);
  if (begin >= end) return ball;
  for (int s = begin; s < end; ++s) {
    const float* row = &e.coords[static_cast<size_t>(s) * stride];
    for (int d = 0; d < stride; ++d) ball.centre[static_cast<size_t>(d)] += row[d];
  }
  for (double& c : ball.centre) c /= end - begin;
  for (int d = 0; d < 2 * e.dims; ++d) ball.norm += ball.centre[static_cast<size_t>(d)] * ball.centre[static_cast<size_t>(d)];
  for (int s = begin; s < end; ++s) {
    const double squared = rotation_distance_squared(ball.centre.data(), ball.norm, &e.coords[static_cast<size_t>(s) * stride],
                                         e.norms[static_cast<size_t>(s)], e.dims);
    ball.radius = std::max(ball.radius, std::sqrt(squared));
  }
  return ball;
}

// Whether two balls can hold a pair within `reach` of each other (a hair of slack: exact
// decisions are the pairs' own).
bool may_meet(const Ball& x, const Ball& y, double reach, int dims) {
  const double squared = rotation_distance_squared(x.centre.data(), x.norm, y.centre.data(), y.norm, dims);
  const double r = reach + x.radius + y.radius;
  return squared <= r * r * (1.0 + 1e-9) + 1e-12;
}

}  // namespace

long long BoundedTiles::count() const {
  return std::accumulate(flags.begin(), flags.end(), 0LL, [](long long n, char f) { return n + (f != 0); });
}

BoundedTiles find_bounded_tiles(const FrameFeatures& f, const WindowEmbedding& e, int tile, double ceiling,
                                int threads) {
  const int n = f.frames, k = e.window, windows = e.windows, dims = e.dims, stride = e.stride();
  BoundedTiles out;
  out.tile = std::max(1, tile);
  out.per_side = (n + out.tile - 1) / out.tile;
  const int per_side = out.per_side, t = out.tile;
  out.flags.assign(static_cast<size_t>(per_side) * per_side, 0);
  if (per_side == 0 || !(ceiling >= 0.0)) return out;
  const double reach = std::sqrt(ceiling);
  // Tile I's leaving windows start at its rows a; its arrival windows at b - k + 1 for its
  // columns b (those that start inside the matrix).
  auto leaving = [&](int i) {
    return std::pair{std::min(i * t, windows), std::min(std::min(n, i * t + t), windows)};
  };
  auto arriving = [&](int j) {
    return std::pair{std::max(0, j * t - k + 1), std::max(0, std::min(n, j * t + t) - k + 1)};
  };
  // Small balls: a fifth of the window, at least 3 windows, and middle ones of 8 small, all
  // aligned on multiples of their size (so that small ones nest in middle ones). On four
  // subjects of the 8-subject library at 30 fps, small balls of 3 windows searched in 1.6 s,
  // of 4 in 2.2 s, of 8 in 5.8 s (middle ones of 4 or 8 small alike, of 16 slower).
  const int size = std::max(3, k / 5), middle_size = 8 * size;
  auto balls_of_size = [&](int ball_size) {
    std::vector<Ball> balls(static_cast<size_t>((windows + ball_size - 1) / ball_size));
    parallel_for(static_cast<long long>(balls.size()), worker_threads(threads), 64, [&](int, long long b) {
      const int s = static_cast<int>(b) * ball_size;
      balls[static_cast<size_t>(b)] = ball_of(e, s, std::min(windows, s + ball_size));
    });
    return balls;
  };
  const std::vector<Ball> small = balls_of_size(size), middle = balls_of_size(middle_size);
  std::vector<Ball> leave_ball(static_cast<size_t>(per_side)), arrive_ball(static_cast<size_t>(per_side));
  parallel_for(per_side, worker_threads(threads), 1, [&](int, long long i) {
    const auto [a0, a1] = leaving(static_cast<int>(i));
    const auto [s0, s1] = arriving(static_cast<int>(i));
    leave_ball[static_cast<size_t>(i)] = ball_of(e, a0, a1);
    arrive_ball[static_cast<size_t>(i)] = ball_of(e, s0, s1);
  });
  const int workers = worker_threads(threads);
  std::vector<long long> summed(static_cast<size_t>(workers), 0);
  // Whether windows [a0, a1) x [s0, s1) hold a pair (leaving, arriving) within the ceiling.
  // |<E_a, E_s>| <= |E_a| |E_s|, so (|E_a| - |E_s|)^2 plus the heights' part bounds a pair's
  // bound from below: most pairs are ruled out by it, or by the heights, before the complex
  // product.
  std::vector<double> lengths(e.norms.size());
  std::transform(e.norms.begin(), e.norms.end(), lengths.begin(), [](double norm) { return std::sqrt(norm); });
  auto pair_within = [&](int a0, int a1, int s0, int s1, long long& pairs) {
    for (int a = a0; a < a1; ++a) {
      if (!f.can_leave[static_cast<size_t>(a)]) continue;
      const float* ea = &e.coords[static_cast<size_t>(a) * stride];
      const double la = lengths[static_cast<size_t>(a)];
      for (int s = s0; s < s1; ++s) {
        if (!f.can_arrive[static_cast<size_t>(s + k - 1)]) continue;
        ++pairs;
        const double gap = la - lengths[static_cast<size_t>(s)];
        double lower = gap * gap;
        const float* es = &e.coords[static_cast<size_t>(s) * stride];
        for (int d = 2 * dims; d < 3 * dims && lower <= ceiling; ++d) {
          const double diff = static_cast<double>(ea[d]) - es[d];
          lower += diff * diff;
        }
        if (lower > ceiling) continue;
        const double bound =
            rotation_distance_squared(ea, e.norms[static_cast<size_t>(a)], es, e.norms[static_cast<size_t>(s)], dims);
        if (bound <= ceiling) return true;
      }
    }
    return false;
  };
  auto holds_pair = [&](int i, int j, long long& pairs) {
    const auto [a0, a1] = leaving(i);
    const auto [s0, s1] = arriving(j);
    if (a0 >= a1 || s0 >= s1) return false;
    const Ball& arrivals = arrive_ball[static_cast<size_t>(j)];
    if (!may_meet(leave_ball[static_cast<size_t>(i)], arrivals, reach, dims)) return false;
    for (int mi = a0 / middle_size; mi * middle_size < a1; ++mi) {
      const Ball& mx = middle[static_cast<size_t>(mi)];
      if (!may_meet(mx, arrivals, reach, dims)) continue;
      const int ma0 = std::max(a0, mi * middle_size), ma1 = std::min(a1, mi * middle_size + middle_size);
      for (int mj = s0 / middle_size; mj * middle_size < s1; ++mj) {
        const Ball& my = middle[static_cast<size_t>(mj)];
        if (!may_meet(mx, my, reach, dims)) continue;
        const int ms0 = std::max(s0, mj * middle_size), ms1 = std::min(s1, mj * middle_size + middle_size);
        for (int bi = ma0 / size; bi * size < ma1; ++bi) {
          const Ball& x = small[static_cast<size_t>(bi)];
          if (!may_meet(x, my, reach, dims)) continue;
          for (int bj = ms0 / size; bj * size < ms1; ++bj) {
            if (!may_meet(x, small[static_cast<size_t>(bj)], reach, dims)) continue;
            if (pair_within(std::max(ma0, bi * size), std::min(ma1, bi * size + size), std::max(ms0, bj * size),
                            std::min(ms1, bj * size + size), pairs)) {
              return true;
            }
          }
        }
      }
    }
    return false;
  };
  parallel_for(static_cast<long long>(per_side) * per_side, workers, 16, [&](int w, long long item) {
    const int i = static_cast<int>(item / per_side), j = static_cast<int>(item % per_side);
    out.flags[static_cast<size_t>(item)] = holds_pair(i, j, summed[static_cast<size_t>(w)]) ? 1 : 0;
  });
  out.pairs = std::accumulate(summed.begin(), summed.end(), 0LL);
  return out;
}

}  // namespace mg
