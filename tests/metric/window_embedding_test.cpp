// The window embedding's bound against the tiles' D, and its range search against a scan.
#include "motiongraph/metric/window_embedding.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "metric/tile_matrix.h"
#include "test_data.h"

namespace mg {
namespace {

using test::quantile_of;

TEST(WindowEmbedding, BoundsTheDistanceFromBelowAndTheProjectionBoundsTheBound) {
  for (const DistanceSettings::Taper taper : {DistanceSettings::Taper::kUniform, DistanceSettings::Taper::kHann}) {
    DistanceSettings settings;
    settings.taper = taper;
    const test::TileMatrix m = test::tile_matrix(test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_01.amc"}),
                               settings);
    auto embedding = make_window_embedding(m.features);
    ASSERT_TRUE(embedding) << embedding.error().to_string();
    EXPECT_EQ(embedding->dims, 16);
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

TEST(WindowEmbedding, RangeSearchFindsEveryPairBelowTheCeilingAndEqualsAScan) {
  const test::TileMatrix m = test::tile_matrix(test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_57.amc"}));
  auto embedding = make_window_embedding(m.features);
  ASSERT_TRUE(embedding);
  const int n = m.features.frames, k = m.features.window;
  for (const double q : {0.005, 0.02, 0.1}) {
    const double ceiling = quantile_of(m, q);
    std::vector<std::pair<int, int>> visited;
    const BoundedPairStatistics stats =
        for_each_bounded_pair(m.features, *embedding, ceiling, [&](int a, std::span<const int> bs) {
          for (int b : bs) visited.emplace_back(a, b);
        });
    EXPECT_EQ(stats.pairs, static_cast<long long>(visited.size()));
    EXPECT_TRUE(std::is_sorted(visited.begin(), visited.end()));
    // The scan: every defined pair whose embedded bound is at most the ceiling.
    std::vector<std::pair<int, int>> scanned;
    long long below = 0, defined = 0;
    for (int a = 0; a < n; ++a) {
      for (int b = k - 1; b < n; ++b) {
        if (!m.features.can_leave[a] || !m.features.can_arrive[b]) continue;
        ++defined;
        if (embedding->bound(a, b - k + 1) <= ceiling) scanned.emplace_back(a, b);
        below += m.at(a, b) <= ceiling ? 1 : 0;
      }
    }
    EXPECT_EQ(visited, scanned) << q;
    // The same on one thread as on three (the batches split differently).
    for (const int threads : {1, 3}) {
      std::vector<std::pair<int, int>> again;
      const BoundedPairStatistics same = for_each_bounded_pair(
          m.features, *embedding, ceiling, [&](int a, std::span<const int> bs) {
            for (int b : bs) again.emplace_back(a, b);
          }, threads);
      EXPECT_EQ(again, visited) << threads;
      EXPECT_EQ(same.scanned, stats.scanned) << threads;
    }
    // Exact: no pair whose D is below the ceiling is left out (D >= the bound).
    const std::set<std::pair<int, int>> found(visited.begin(), visited.end());
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        if (m.at(a, b) <= ceiling * (1.0 - 1e-4)) {
          EXPECT_TRUE(found.count({a, b})) << a << "," << b << " q " << q;
        }
      }
    }
    // And it prunes: far fewer candidates than pairs.
    EXPECT_LT(static_cast<double>(visited.size()), 0.5 * static_cast<double>(defined)) << q;
    EXPECT_GE(static_cast<long long>(visited.size()), below);
    EXPECT_GE(stats.scanned, stats.pairs);
    EXPECT_LE(stats.scanned, defined);
    RecordProperty("candidates_q" + std::to_string(q), std::to_string(double(visited.size()) / double(defined)));
  }
}

TEST(WindowEmbedding, SettingsAndTooFewFramesAreErrors) {
  WindowEmbeddingSettings bad;
  bad.dims = 0;
  EXPECT_FALSE(bad.validate());
  bad = {};
  bad.per_frame_dims = 0;
  EXPECT_FALSE(bad.validate());
  FrameFeatures none;
  EXPECT_FALSE(make_window_embedding(none));
}

}  // namespace
}  // namespace mg
