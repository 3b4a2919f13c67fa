// The window embedding's bound against the tiles' D.
#include "motiongraph/metric/window_embedding.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "metric/tile_matrix.h"
#include "test_data.h"

namespace mg {
namespace {


// D of every pair from the tiles, for a cloud and window of our choosing.
test::TileMatrix matrix_of(const MotionDatabase& db, const PointCloudSettings& cloud,
                           const DistanceSettings& settings) {
  test::TileMatrix m;
  auto layout = make_cloud_layout(db.skeletons[0], cloud);
  EXPECT_TRUE(layout);
  m.features = *make_frame_features(db, *layout, settings);
  const int n = m.features.frames;
  m.d.assign(static_cast<size_t>(n) * n, 0.0f);
  for_each_distance_tile(m.features, settings, [&](const DistanceTile& tile) {
    for (int a = tile.leave_begin; a < tile.leave_begin + tile.leave_count; ++a) {
      for (int b = tile.arrive_begin; b < tile.arrive_begin + tile.arrive_count; ++b) {
        m.d[static_cast<size_t>(a) * n + b] = tile.at(a, b);
      }
    }
  });
  return m;
}

TEST(WindowEmbedding, BoundsTheDistanceFromBelowOnEveryPairAndIsTight) {
  for (const DistanceSettings::Taper taper : {DistanceSettings::Taper::kUniform, DistanceSettings::Taper::kHann}) {
    for (const double fps : {30.0, 60.0}) {
      DistanceSettings settings;
      settings.taper = taper;
      const test::TileMatrix m = test::tile_matrix(
          test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_01.amc"}, false, 0.0,
                               Vec3::Zero(), fps),
          settings);
      auto embedding = make_window_embedding(m.features);
      ASSERT_TRUE(embedding) << embedding.error().to_string();
      EXPECT_EQ(embedding->dims, 24);
      const int n = m.features.frames, k = m.features.window;
      const double median = test::quantile_of(m, 0.5);
      long long checked = 0, above_median = 0;
      double share = 0.0;  // the mean share of D the bound reaches, over pairs above the median
      for (int a = 0; a < n; ++a) {
        for (int b = k - 1; b < n; ++b) {
          const float d = m.at(a, b);
          if (!std::isfinite(d)) continue;
          const double bound = embedding->bound(a, b - k + 1);
          // D is float32 from the tiles, a difference of large sums: 1e-4 of the larger of D
          // and the median D.
          ASSERT_LE(bound, d + 1e-4 * std::max<double>(d, median)) << a << "," << b << " fps " << fps;
          ++checked;
          if (d > median) {
            share += bound / d;
            ++above_median;
          }
        }
      }
      EXPECT_GT(checked, 40000);
      // A bound, and a tight one: measured 0.82-0.87 on subject 16.
      EXPECT_GT(share / static_cast<double>(above_median), 0.7) << "fps " << fps;
    }
  }
}

// With every component kept (no projection: a window of 2 frames over the joints' points), the
// bound is D itself: the floor part is the rotation-aligned distance, not a looser one.
TEST(WindowEmbedding, KeepingEveryComponentGivesTheDistanceItself) {
  PointCloudSettings joints;
  joints.kind = PointCloudSettings::Kind::kJoints;
  DistanceSettings settings;
  settings.window_frames = 2;
  const test::TileMatrix m =
      matrix_of(test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc"}), joints, settings);
  WindowEmbeddingSettings full;
  full.per_frame_dims = m.features.points;
  full.dims = 2 * m.features.points;
  auto embedding = make_window_embedding(m.features, full);
  ASSERT_TRUE(embedding);
  ASSERT_EQ(embedding->dims, 2 * m.features.points);
  const int n = m.features.frames, k = m.features.window;
  const double median = test::quantile_of(m, 0.5);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> frame(0, n - 1);
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int a = frame(rng), b = frame(rng);
    const float d = m.at(a, b);
    if (!std::isfinite(d)) continue;
    EXPECT_NEAR(embedding->bound(a, b - k + 1), d, 1e-4 * std::max<double>(d, median)) << a << "," << b;
    ++checked;
  }
  EXPECT_GT(checked, 10000);
}

TEST(WindowEmbedding, SettingsAndTooFewFramesAreErrors) {
  WindowEmbeddingSettings bad;
  bad.dims = 0;
  EXPECT_FALSE(bad.validate());
  bad = {};
  bad.per_frame_dims = -1;
  EXPECT_FALSE(bad.validate());
  bad = {};
  bad.max_samples = 0;
  EXPECT_FALSE(bad.validate());
  WindowEmbeddingSettings automatic;
  EXPECT_TRUE(automatic.validate());
  EXPECT_EQ(automatic.per_frame_dims_for(10), 12);  // 30 fps
  EXPECT_EQ(automatic.per_frame_dims_for(40), 6);  // 120 fps
  EXPECT_EQ(automatic.per_frame_dims_for(1000), 6);
  automatic.per_frame_dims = 5;
  EXPECT_EQ(automatic.per_frame_dims_for(10), 5);
  FrameFeatures none;
  EXPECT_FALSE(make_window_embedding(none));
}

}  // namespace
}  // namespace mg
