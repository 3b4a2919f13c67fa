// The fast tiled distance against the pair-by-pair reference, and the properties D must have.
#include "motiongraph/metric/distance_tiles.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "motiongraph/metric/reference_distance.h"
#include "test_data.h"

namespace mg {
namespace {

struct Computed {
  FrameFeatures features;
  std::vector<float> matrix;  // N x N from the tiles' inner regions
  std::vector<Vec3> clouds;   // N x P world points, double
};

Computed compute(const MotionDatabase& db, DistanceSettings settings, PointCloudSettings cloud_settings = {}) {
  Computed c;
  auto layout = make_cloud_layout(db.skeletons[0], cloud_settings);
  EXPECT_TRUE(layout);
  auto features = make_frame_features(db, *layout, settings);
  EXPECT_TRUE(features) << features.error().to_string();
  c.features = std::move(*features);
  const int n = c.features.frames;
  c.matrix.assign(static_cast<size_t>(n) * n, -1.0f);
  std::mutex mutex;
  for_each_distance_tile(c.features, settings, [&](const DistanceTile& tile) {
    std::lock_guard lock(mutex);
    for (int a = tile.leave_begin; a < tile.leave_begin + tile.leave_count; ++a) {
      for (int b = tile.arrive_begin; b < tile.arrive_begin + tile.arrive_count; ++b) {
        c.matrix[static_cast<size_t>(a) * n + b] = tile.at(a, b);
      }
    }
    // The halo agrees with what the neighbouring tiles hold for the same pairs (checked when
    // those have already been stored).
    for (int a = tile.row0; a < tile.row0 + tile.rows; ++a) {
      for (int b = tile.col0; b < tile.col0 + tile.cols; ++b) {
        const float stored = c.matrix[static_cast<size_t>(a) * n + b];
        if (stored != -1.0f && !(std::isnan(stored) && std::isnan(tile.at(a, b)))) {
          ASSERT_NEAR(stored, tile.at(a, b), 1e-3f * std::max(1.0f, stored)) << a << "," << b;
        }
      }
    }
  });
  c.clouds = database_clouds(db, *layout);
  return c;
}

double reference(const Computed& c, int a, int b) {
  return reference_distance(c.clouds, c.features.points, c.features.point_weights, c.features.taper, a, b).distance;
}

double median_finite(const std::vector<float>& values) {
  std::vector<float> finite;
  for (float v : values) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  std::nth_element(finite.begin(), finite.begin() + finite.size() / 2, finite.end());
  return finite[finite.size() / 2];
}

void expect_matches_reference(const Computed& c, int random_pairs) {
  const int n = c.features.frames;
  const double median = median_finite(c.matrix);
  ASSERT_GT(median, 0.0);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> frame(0, n - 1);
  int checked = 0;
  for (int trial = 0; trial < random_pairs; ++trial) {
    const int a = frame(rng), b = frame(rng);
    const float fast = c.matrix[static_cast<size_t>(a) * n + b];
    if (!c.features.can_leave[a] || !c.features.can_arrive[b]) {
      EXPECT_TRUE(std::isnan(fast)) << a << "," << b;
      continue;
    }
    EXPECT_NEAR(fast, reference(c, a, b), 1e-4 * median) << a << "," << b;
    ++checked;
  }
  EXPECT_GT(checked, random_pairs / 2);
  // Every pair near a local minimum (the ones transitions are made of): a row's smallest
  // entries away from the identity diagonal.
  for (int a = 0; a < n; a += 7) {
    if (!c.features.can_leave[a]) continue;
    int best = -1;
    for (int b = 0; b < n; ++b) {
      const float v = c.matrix[static_cast<size_t>(a) * n + b];
      const bool continuation = c.features.clip_of_frame[a] == c.features.clip_of_frame[b] &&
                                std::abs(b - (a + c.features.window - 1)) <= c.features.window;
      if (std::isfinite(v) && !continuation && (best < 0 || v < c.matrix[static_cast<size_t>(a) * n + best])) best = b;
    }
    if (best >= 0) {
      EXPECT_NEAR(c.matrix[static_cast<size_t>(a) * n + best], reference(c, a, best), 1e-4 * median);
    }
  }
}

TEST(Distance, TiledMatchesTheReference) {
  const auto db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_01.amc"});
  DistanceSettings settings;
  settings.tile_frames = 64;  // many tiles, many borders
  settings.threads = 2;
  expect_matches_reference(compute(db, settings), 400);
}

TEST(Distance, TaperAndJointCloudsMatchTheReference) {
  const auto db = test::small_database({"cmu/16/16_11.amc", "cmu/16/16_41.amc"});
  DistanceSettings settings;
  settings.tile_frames = 100;
  settings.taper = DistanceSettings::Taper::kHann;
  PointCloudSettings joints;
  joints.kind = PointCloudSettings::Kind::kJoints;
  joints.joint_weights = {{"head", 3.0}, {"ltoes", 0.5}};
  expect_matches_reference(compute(db, settings, joints), 300);
}

TEST(Distance, UndefinedExactlyWhereAWindowLeavesItsClip) {
  const auto db = test::small_database({"cmu/16/16_35.amc", "cmu/16/16_39.amc"});
  DistanceSettings settings;
  settings.tile_frames = 50;
  const Computed c = compute(db, settings);
  const int n = c.features.frames;
  const int k = c.features.window;
  EXPECT_EQ(k, 10);
  for (int a = 0; a < n; ++a) {
    const int clip_a = db.clip_of(a);
    const bool leave = a + k - 1 < db.clips[clip_a].first_frame + db.clips[clip_a].frame_count;
    for (int b = 0; b < n; ++b) {
      const int clip_b = db.clip_of(b);
      const bool arrive = b - k + 1 >= db.clips[clip_b].first_frame;
      ASSERT_EQ(std::isnan(c.matrix[static_cast<size_t>(a) * n + b]), !(leave && arrive)) << a << "," << b;
    }
  }
}

TEST(Distance, ClipTurnedAndMovedIsTheSameClip) {
  // The first clip again, turned 2 rad about the vertical and moved 40 m: its frames are at
  // distance ~0 from the original's, and its rows and columns are the original's.
  const auto db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_57.amc"}, true, 2.0, Vec3(30.0, 0.0, -26.0));
  DistanceSettings settings;
  settings.tile_frames = 128;
  const Computed c = compute(db, settings);
  const int n = c.features.frames;
  const int copy_first = db.clips.back().first_frame;
  const int k = c.features.window;
  const double median = median_finite(c.matrix);
  for (int a = 0; a + k <= db.clips[0].frame_count; ++a) {
    // Leaving the original at a and arriving in the copy at the end of the same window.
    EXPECT_NEAR(c.matrix[static_cast<size_t>(a) * n + copy_first + a + k - 1], 0.0, 1e-4 * median);
    for (int b = 0; b < n; ++b) {
      const float original_row = c.matrix[static_cast<size_t>(a) * n + b];
      const float copy_row = c.matrix[static_cast<size_t>(copy_first + a) * n + b];
      if (std::isnan(original_row)) {
        ASSERT_TRUE(std::isnan(copy_row));
      } else {
        ASSERT_NEAR(original_row, copy_row, 1e-4 * median) << a << "," << b;
      }
      const float original_column = c.matrix[static_cast<size_t>(b) * n + a + k - 1];
      const float copy_column = c.matrix[static_cast<size_t>(b) * n + copy_first + a + k - 1];
      if (!std::isnan(original_column)) {
        ASSERT_NEAR(original_column, copy_column, 1e-4 * median) << b << "," << a;
      }
    }
  }
}

// Items and sides: a subset of the items, each visiting one or both of its tiles, gives those
// tiles with the values of the whole run, bit for bit, and nothing else.
TEST(Distance, ItemsAndSidesVisitTheirTilesWithTheSameValues) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc"});
  DistanceSettings settings;
  settings.tile_frames = 16;
  settings.threads = 2;
  auto layout = make_cloud_layout(db.skeletons[0], {});
  const FrameFeatures f = *make_frame_features(db, *layout, settings);
  const int n = f.frames;
  std::vector<float> whole(static_cast<size_t>(n) * n);
  std::mutex mutex;
  auto keep = [&](std::vector<float>& into, std::vector<std::pair<int, int>>* seen) {
    return [&into, seen, &mutex, n](const DistanceTile& tile) {
      std::lock_guard lock(mutex);
      if (seen != nullptr) seen->emplace_back(tile.leave_begin, tile.arrive_begin);
      for (int a = tile.leave_begin; a < tile.leave_begin + tile.leave_count; ++a) {
        for (int b = tile.arrive_begin; b < tile.arrive_begin + tile.arrive_count; ++b) {
          into[static_cast<size_t>(a) * n + b] = tile.at(a, b);
        }
      }
    };
  };
  for_each_distance_tile(f, settings, keep(whole, nullptr));
  const TileItems grid = tile_items(f, settings);
  std::vector<long long> items;
  std::vector<unsigned char> sides;
  std::vector<std::pair<int, int>> expected;
  std::mt19937 rng(9);
  for (long long item = 0; item < grid.count(); ++item) {
    const auto side = static_cast<unsigned char>(rng() % 4);
    if (side == 0) continue;
    const auto [i, j] = grid.tiles_of(item);
    if (i == j && (side & 1) == 0) continue;
    items.push_back(item);
    sides.push_back(side);
    if ((side & 1) != 0) expected.emplace_back(i * grid.tile, j * grid.tile);
    if (i != j && (side & 2) != 0) expected.emplace_back(j * grid.tile, i * grid.tile);
  }
  ASSERT_GT(items.size(), 10u);
  std::vector<float> part(static_cast<size_t>(n) * n, std::numeric_limits<float>::infinity());
  std::vector<std::pair<int, int>> seen;
  const TileRunStatistics stats = for_each_distance_tile(f, settings, keep(part, &seen), {}, items, sides);
  std::sort(seen.begin(), seen.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(seen, expected);
  EXPECT_EQ(stats.tiles, static_cast<long long>(expected.size()));
  long long pairs = 0;
  for (size_t i = 0; i < items.size(); ++i) pairs += grid.pairs(items[i], sides[i]);
  EXPECT_EQ(stats.pairs, pairs);
  for (size_t i = 0; i < part.size(); ++i) {
    if (part[i] == std::numeric_limits<float>::infinity()) continue;  // a tile not visited
    const bool same = std::memcmp(&part[i], &whole[i], sizeof(float)) == 0;
    EXPECT_TRUE(same) << "pair " << i / n << "," << i % n;
  }
}

TEST(Distance, ReferenceAlignmentIsOptimal) {
  // Perturbing the closed-form alignment in any direction never lowers the sum.
  const auto db = test::small_database({"cmu/16/16_17.amc", "cmu/16/16_43.amc"});
  const Computed c = compute(db, DistanceSettings{});
  const int k = c.features.window;
  const int a = 20, b = db.clips[1].first_frame + 40;
  const ReferenceDistance best = reference_distance(c.clouds, c.features.points, c.features.point_weights,
                                                    c.features.taper, a, b);
  auto cost = [&](const FloorAlignment& align) {
    double sum = 0.0;
    for (int t = 0; t < k; ++t) {
      for (int i = 0; i < c.features.points; ++i) {
        const Vec3& p = c.clouds[static_cast<size_t>(a + t) * c.features.points + i];
        const Vec3& q = c.clouds[static_cast<size_t>(b - k + 1 + t) * c.features.points + i];
        sum += c.features.taper[t] * c.features.point_weights[i] * (p - align.apply(q)).squaredNorm();
      }
    }
    return sum;
  };
  EXPECT_NEAR(cost(best.alignment), best.distance, 1e-9 * best.distance);
  for (double step : {1e-3, 1e-2, 0.3, 3.0}) {
    for (int dim = 0; dim < 3; ++dim) {
      for (double sign : {-1.0, 1.0}) {
        FloorAlignment moved = best.alignment;
        (dim == 0 ? moved.yaw_rad : dim == 1 ? moved.x_m : moved.z_m) += sign * step;
        EXPECT_GE(cost(moved), best.distance * (1 - 1e-12));
      }
    }
  }
}

}  // namespace
}  // namespace mg
