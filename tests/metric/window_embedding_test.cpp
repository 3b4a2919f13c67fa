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


TEST(WindowEmbedding, BoundsTheDistanceFromBelowAndTheProjectionBoundsTheBound) {
  for (const DistanceSettings::Taper taper : {DistanceSettings::Taper::kUniform, DistanceSettings::Taper::kHann}) {
    DistanceSettings settings;
    settings.taper = taper;
    const test::TileMatrix m = test::tile_matrix(test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_01.amc"}),
                               settings);
    auto embedding = make_window_embedding(m.features);
    ASSERT_TRUE(embedding) << embedding.error().to_string();
    EXPECT_EQ(embedding->dims, 24);
    const int n = m.features.frames, k = m.features.window;
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> frame(0, n - 1);
    int checked = 0;
    double tightest = 0.0;  // the largest share of D the projected bound reaches
    for (int trial = 0; trial < 20000; ++trial) {
      const int a = frame(rng), b = frame(rng);
      const float d = m.at(a, b);
      if (!std::isfinite(d)) continue;
      const double full = window_feature_bound(m.features, a, b);
      const double projected = embedding->bound(a, b - k + 1);
      // D is float32 from the tiles: a relative 1e-4 and a micro-unit spare.
      EXPECT_LE(full, d * (1.0 + 1e-4) + 1e-6) << a << "," << b;
      EXPECT_LE(projected, full * (1.0 + 1e-5) + 1e-9) << a << "," << b;
      if (d > 0.0f) tightest = std::max(tightest, projected / d);
      ++checked;
    }
    EXPECT_GT(checked, 10000);
    EXPECT_GT(tightest, 0.5);  // a bound, but not a vacuous one
  }
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
  EXPECT_EQ(automatic.per_frame_dims_for(10), 16);  // 30 fps
  EXPECT_EQ(automatic.per_frame_dims_for(40), 8);   // 120 fps
  EXPECT_EQ(automatic.per_frame_dims_for(1000), 8);
  automatic.per_frame_dims = 5;
  EXPECT_EQ(automatic.per_frame_dims_for(10), 5);
  FrameFeatures none;
  EXPECT_FALSE(make_window_embedding(none));
}

}  // namespace
}  // namespace mg
