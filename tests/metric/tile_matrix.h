// The whole N x N matrix of D from the exhaustive tiles: the reference the pruned stage's
// pieces are tested against.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "motiongraph/metric/distance_tiles.h"

namespace mg::test {

struct TileMatrix {
  FrameFeatures features;
  std::vector<float> d;  // N x N, NaN undefined
  float at(int a, int b) const { return d[static_cast<size_t>(a) * features.frames + b]; }
};

inline TileMatrix tile_matrix(const MotionDatabase& db, DistanceSettings settings = {}) {
  TileMatrix m;
  auto layout = make_cloud_layout(db.skeletons[0], {});
  EXPECT_TRUE(layout);
  auto features = make_frame_features(db, *layout, settings);
  EXPECT_TRUE(features) << features.error().to_string();
  m.features = std::move(*features);
  const int n = m.features.frames;
  m.d.assign(static_cast<size_t>(n) * n, 0.0f);
  settings.threads = 1;
  for_each_distance_tile(m.features, settings, [&](const DistanceTile& tile) {
    for (int a = tile.leave_begin; a < tile.leave_begin + tile.leave_count; ++a) {
      for (int b = tile.arrive_begin; b < tile.arrive_begin + tile.arrive_count; ++b) {
        m.d[static_cast<size_t>(a) * n + b] = tile.at(a, b);
      }
    }
  });
  return m;
}

// The q-quantile of the defined D.
inline double quantile_of(const TileMatrix& m, double q) {
  std::vector<float> finite;
  for (float v : m.d) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  const size_t i = static_cast<size_t>(q * static_cast<double>(finite.size()));
  std::nth_element(finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(i), finite.end());
  return finite[i];
}

}  // namespace mg::test
