// The tiles the window embedding's bound cannot rule out: balls of windows, tile by tile.
#include "motiongraph/metric/bounded_tiles.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <span>

#include "motiongraph/core/parallel_for.h"
#include "motiongraph/core/vector_clones.h"

namespace mg {

namespace {

// Windows [begin, end) in a ball: their mean as centre (any point of the space will do: the
// distance up to rotation obeys the triangle inequality; consecutive windows face alike, so
// their mean lies close to them all), kept in float as the windows are (the embedding's
// layout), and the radius that holds them.
struct Ball {
  std::vector<float> centre;  // WindowEmbedding::stride() values
  double norm = 0.0;          // the complex part's squared norm, of the floats
  double scale = 0.0;         // norm plus the heights' squared norm: what rounding is relative to
  double radius = 0.0;
};

Ball ball_of(const WindowEmbedding& e, int begin, int end) {
  const int stride = e.stride(), dims = e.dims;
  Ball ball;
  ball.centre.assign(static_cast<size_t>(stride), 0.0f);
  if (begin >= end) return ball;
  std::vector<double> sum(static_cast<size_t>(stride), 0.0);
  for (int s = begin; s < end; ++s) {
    const float* row = &e.coords[static_cast<size_t>(s) * stride];
    for (int d = 0; d < stride; ++d) sum[static_cast<size_t>(d)] += row[d];
  }
  for (int d = 0; d < stride; ++d) {
    const float c = static_cast<float>(sum[static_cast<size_t>(d)] / (end - begin));
    ball.centre[static_cast<size_t>(d)] = c;
    (d < 2 * dims ? ball.norm : ball.scale) += static_cast<double>(c) * c;
  }
  ball.scale += ball.norm;
  for (int s = begin; s < end; ++s) {
    const double squared = rotation_distance_squared(ball.centre.data(), ball.norm,
                                                     &e.coords[static_cast<size_t>(s) * stride],
                                                     e.norms[static_cast<size_t>(s)], dims);
    ball.radius = std::max(ball.radius, std::sqrt(squared));
  }
  return ball;
}

// Whether two balls can hold a pair within `reach` of each other (in double, as the pairs'
// bound; a hair of slack: exact decisions are the pairs' own).
bool may_meet(const Ball& x, const Ball& y, double reach, int dims) {
  const double squared = rotation_distance_squared(x.centre.data(), x.norm, y.centre.data(), y.norm, dims);
  const double r = reach + x.radius + y.radius;
  return squared <= r * r * (1.0 + 1e-9) + 1e-12;
}

// kLanes balls side by side (structure of arrays: for each value of the centre, the balls'
// values), so that one ball is tested against all of them in one vectorised pass.
constexpr int kLanes = 8;
constexpr int kSmallPerMiddle = kLanes;

struct Group {
  std::vector<float> centres;  // stride values x kLanes balls
  float norm[kLanes] = {};
  double scale[kLanes] = {}, radius[kLanes] = {};
};

Group group_of(std::span<const Ball> balls, int stride) {
  Group g;
  g.centres.assign(static_cast<size_t>(stride * kLanes), 0.0f);
  for (size_t l = 0; l < balls.size() && l < static_cast<size_t>(kLanes); ++l) {
    for (int v = 0; v < stride; ++v) {
      g.centres[static_cast<size_t>(v) * kLanes + l] = balls[l].centre[static_cast<size_t>(v)];
    }
    g.norm[l] = static_cast<float>(balls[l].norm);
    g.scale[l] = balls[l].scale;
    g.radius[l] = balls[l].radius;
  }
  return g;
}

// out[l] = rotation_distance_squared of centre x and the group's ball l, in float, for all
// kLanes at once (a vector of kLanes floats per sum: GCC's and Clang's vector extension). A
// first pass over the heights alone, to skip the floor part when no ball is near, measured
// slower (3.1 s against 2.2 s on the 8-subject library): rarely are all kLanes far.
using Lanes = float __attribute__((vector_size(kLanes * sizeof(float))));

MG_VECTOR_CLONES void group_distances_squared(int dims, const float* __restrict x, float nx,
                                              const float* __restrict centres, const float* __restrict norms,
                                              float* __restrict out) {
  Lanes re = {}, im = {}, heights = {};
  for (int d = 0; d < dims; ++d) {
    Lanes yr, yi, yh;
    std::memcpy(&yr, centres + static_cast<size_t>(2 * d) * kLanes, sizeof(Lanes));
    std::memcpy(&yi, centres + static_cast<size_t>(2 * d + 1) * kLanes, sizeof(Lanes));
    std::memcpy(&yh, centres + static_cast<size_t>(2 * dims + d) * kLanes, sizeof(Lanes));
    const float xr = x[2 * d], xi = x[2 * d + 1];
    re += xr * yr + xi * yi;
    im += xr * yi - xi * yr;
    const Lanes diff = x[2 * dims + d] - yh;
    heights += diff * diff;
  }
  for (int l = 0; l < kLanes; ++l) {
    out[l] = std::max(0.0f, nx + norms[l] - 2.0f * std::sqrt(re[l] * re[l] + im[l] * im[l])) + heights[l];
  }
}

// Which of the group's balls may hold a pair within `reach` of ball x's (bit l for ball l).
// The float distance errs by a few units in the last place of the squared norms; 1e-5 of them
// is spared, so a pair that can meet is never ruled out.
unsigned group_may_meet(const Ball& x, const Group& g, double reach, int dims) {
  float squared[kLanes];
  group_distances_squared(dims, x.centre.data(), static_cast<float>(x.norm), g.centres.data(), g.norm, squared);
  unsigned meets = 0;
  for (int l = 0; l < kLanes; ++l) {
    const double r = reach + x.radius + g.radius[l];
    if (squared[l] <= r * r + 1e-5 * (x.scale + g.scale[l]) + 1e-12) meets |= 1u << l;
  }
  return meets;
}

}  // namespace

long long BoundedTiles::count() const {
  return std::accumulate(flags.begin(), flags.end(), 0LL, [](long long n, char f) { return n + (f != 0); });
}

BoundedTiles find_bounded_tiles(const FrameFeatures& f, const WindowEmbedding& e, int tile, double ceiling,
                                int threads, std::span<const char> only) {
  const int n = f.frames, k = e.window, windows = e.windows, dims = e.dims, stride = e.stride();
  BoundedTiles out;
  out.tile = std::max(1, tile);
  out.per_side = (n + out.tile - 1) / out.tile;
  const int per_side = out.per_side, t = out.tile;
  out.flags.assign(static_cast<size_t>(per_side) * per_side, 0);
  if (per_side == 0 || !(ceiling >= 0.0)) return out;
  const double reach = std::sqrt(ceiling);
  const int workers = worker_threads(threads);
  // Tile I's leaving windows start at its rows a; its arrival windows at b - k + 1 for its
  // columns b (those that start inside the matrix).
  auto leaving = [&](int i) {
    return std::pair{std::min(i * t, windows), std::min(std::min(n, i * t + t), windows)};
  };
  auto arriving = [&](int j) {
    return std::pair{std::max(0, j * t - k + 1), std::max(0, std::min(n, j * t + t) - k + 1)};
  };
  // Small balls: a fifth of the window, at least 2 windows, and middle ones of kLanes small,
  // all aligned on multiples of their size (so that small ones nest in middle ones). Measured on
  // the 8-subject library at 30 fps: small balls of 2 windows searched in 1.36 s, of 3 in 1.62 s
  // (one ball against 8 at a time); with one test per pair of balls, 3 had beaten 4 and 8.
  const int size = std::max(2, k / 5), middle_size = kSmallPerMiddle * size;
  auto balls_of_size = [&](int ball_size) {
    std::vector<Ball> balls(static_cast<size_t>((windows + ball_size - 1) / ball_size));
    parallel_for(static_cast<long long>(balls.size()), workers, 64, [&](int, long long b) {
      const int s = static_cast<int>(b) * ball_size;
      balls[static_cast<size_t>(b)] = ball_of(e, s, std::min(windows, s + ball_size));
    });
    return balls;
  };
  const std::vector<Ball> small = balls_of_size(size), middle = balls_of_size(middle_size);
  static_assert(kSmallPerMiddle == kLanes);
  // groups[m]: middle ball m's small balls; middle_groups[g]: middle balls kLanes g on.
  auto groups_of = [&](const std::vector<Ball>& balls) {
    std::vector<Group> out_groups((balls.size() + kLanes - 1) / kLanes);
    parallel_for(static_cast<long long>(out_groups.size()), workers, 64, [&](int, long long g) {
      const size_t first = static_cast<size_t>(g) * kLanes;
      out_groups[static_cast<size_t>(g)] =
          group_of(std::span<const Ball>(balls).subspan(first, std::min<size_t>(kLanes, balls.size() - first)), stride);
    });
    return out_groups;
  };
  const std::vector<Group> groups = groups_of(small), middle_groups = groups_of(middle);
  std::vector<Ball> leave_ball(static_cast<size_t>(per_side)), arrive_ball(static_cast<size_t>(per_side));
  parallel_for(per_side, workers, 1, [&](int, long long i) {
    const auto [a0, a1] = leaving(static_cast<int>(i));
    const auto [s0, s1] = arriving(static_cast<int>(i));
    leave_ball[static_cast<size_t>(i)] = ball_of(e, a0, a1);
    arrive_ball[static_cast<size_t>(i)] = ball_of(e, s0, s1);
  });
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
    const int mj_first = s0 / middle_size, mj_last = (s1 - 1) / middle_size;
    for (int mi = a0 / middle_size; mi * middle_size < a1; ++mi) {
      const Ball& mx = middle[static_cast<size_t>(mi)];
      if (!may_meet(mx, arrivals, reach, dims)) continue;
      const int ma0 = std::max(a0, mi * middle_size), ma1 = std::min(a1, mi * middle_size + middle_size);
      unsigned near_mx = 0;
      for (int mj = mj_first; mj <= mj_last; ++mj) {
        if (mj == mj_first || mj % kLanes == 0) {
          near_mx = group_may_meet(mx, middle_groups[static_cast<size_t>(mj / kLanes)], reach, dims);
        }
        if ((near_mx >> (mj % kLanes) & 1u) == 0) continue;
        const Ball& my = middle[static_cast<size_t>(mj)];
        const int ms0 = std::max(s0, mj * middle_size), ms1 = std::min(s1, mj * middle_size + middle_size);
        // The small balls of mx that may meet my, then for each the small balls of my it may
        // meet: kLanes tests in one pass each.
        const unsigned near_my = group_may_meet(my, groups[static_cast<size_t>(mi)], reach, dims);
        for (int bi = ma0 / size; bi * size < ma1; ++bi) {
          if ((near_my >> (bi - mi * kSmallPerMiddle) & 1u) == 0) continue;
          const unsigned near_x =
              group_may_meet(small[static_cast<size_t>(bi)], groups[static_cast<size_t>(mj)], reach, dims);
          for (int bj = ms0 / size; bj * size < ms1; ++bj) {
            if ((near_x >> (bj - mj * kSmallPerMiddle) & 1u) == 0) continue;
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
    if (!only.empty() && (static_cast<size_t>(item) >= only.size() || !only[static_cast<size_t>(item)])) return;
    const int i = static_cast<int>(item / per_side), j = static_cast<int>(item % per_side);
    out.flags[static_cast<size_t>(item)] = holds_pair(i, j, summed[static_cast<size_t>(w)]) ? 1 : 0;
  });
  out.pairs = std::accumulate(summed.begin(), summed.end(), 0LL);
  return out;
}

}  // namespace mg
