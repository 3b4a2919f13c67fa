// The tiles the window embedding's bound cannot rule out: balls of windows, tile by tile.
#include "motiongraph/metric/bounded_tiles.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "motiongraph/core/parallel_for.h"

namespace mg {

namespace {

// Windows [begin, end) in a ball: a centre and the radius that holds them.
struct Ball {
  std::vector<double> centre;
  double radius = 0.0;
};

Ball ball_of(const WindowEmbedding& e, int begin, int end) {
  const int dims = e.dims;
  Ball ball;
  ball.centre.assign(static_cast<size_t>(dims), 0.0);
  if (begin >= end) return ball;
  for (int s = begin; s < end; ++s) {
    for (int d = 0; d < dims; ++d) ball.centre[static_cast<size_t>(d)] += e.coords[static_cast<size_t>(s) * dims + d];
  }
  for (double& c : ball.centre) c /= end - begin;
  for (int s = begin; s < end; ++s) {
    double sum = 0.0;
    for (int d = 0; d < dims; ++d) {
      const double diff = e.coords[static_cast<size_t>(s) * dims + d] - ball.centre[static_cast<size_t>(d)];
      sum += diff * diff;
    }
    ball.radius = std::max(ball.radius, std::sqrt(sum));
  }
  return ball;
}

// Whether two balls can hold a pair within `reach` of each other (a hair of slack: exact
// decisions are the pairs' own).
bool may_meet(const Ball& x, const Ball& y, double reach) {
  double sum = 0.0;
  for (size_t d = 0; d < x.centre.size(); ++d) sum += (x.centre[d] - y.centre[d]) * (x.centre[d] - y.centre[d]);
  const double r = reach + x.radius + y.radius;
  return sum <= r * r * (1.0 + 1e-9) + 1e-12;
}

}  // namespace

long long BoundedTiles::count() const {
  return std::accumulate(flags.begin(), flags.end(), 0LL, [](long long n, char f) { return n + (f != 0); });
}

BoundedTiles find_bounded_tiles(const FrameFeatures& f, const WindowEmbedding& e, int tile, double ceiling,
                                int threads) {
  const int n = f.frames, k = e.window, windows = e.windows, dims = e.dims;
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
  // Small balls: a fifth of the window, at least 4 windows (the ball search's measured best
  // on the 8-subject library at 30 fps), aligned on multiples of their size.
  const int size = std::max(4, k / 5);
  std::vector<Ball> small;
  for (int s = 0; s < windows; s += size) small.push_back(ball_of(e, s, std::min(windows, s + size)));
  std::vector<Ball> leave_ball(static_cast<size_t>(per_side)), arrive_ball(static_cast<size_t>(per_side));
  parallel_for(per_side, worker_threads(threads), 1, [&](int, long long i) {
    const auto [a0, a1] = leaving(static_cast<int>(i));
    const auto [s0, s1] = arriving(static_cast<int>(i));
    leave_ball[static_cast<size_t>(i)] = ball_of(e, a0, a1);
    arrive_ball[static_cast<size_t>(i)] = ball_of(e, s0, s1);
  });
  const int workers = worker_threads(threads);
  std::vector<long long> summed(static_cast<size_t>(workers), 0);
  auto holds_pair = [&](int i, int j, long long& pairs) {
    const auto [a0, a1] = leaving(i);
    const auto [s0, s1] = arriving(j);
    if (a0 >= a1 || s0 >= s1) return false;
    if (!may_meet(leave_ball[static_cast<size_t>(i)], arrive_ball[static_cast<size_t>(j)], reach)) return false;
    for (int bi = a0 / size; bi * size < a1; ++bi) {
      const Ball& x = small[static_cast<size_t>(bi)];
      if (!may_meet(x, arrive_ball[static_cast<size_t>(j)], reach)) continue;
      for (int bj = s0 / size; bj * size < s1; ++bj) {
        if (!may_meet(x, small[static_cast<size_t>(bj)], reach)) continue;
        for (int a = std::max(a0, bi * size); a < std::min(a1, bi * size + size); ++a) {
          if (!f.can_leave[static_cast<size_t>(a)]) continue;
          const float* ea = &e.coords[static_cast<size_t>(a) * dims];
          for (int s = std::max(s0, bj * size); s < std::min(s1, bj * size + size); ++s) {
            if (!f.can_arrive[static_cast<size_t>(s + k - 1)]) continue;
            ++pairs;
            const float* es = &e.coords[static_cast<size_t>(s) * dims];
            double sum = 0.0;
            for (int d = 0; d < dims && sum <= ceiling; ++d) {
              const double diff = static_cast<double>(ea[d]) - es[d];
              sum += diff * diff;
            }
            if (sum <= ceiling) return true;
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
