// D along diagonal runs against the exhaustive tiles' matrix.
#include "motiongraph/metric/diagonal_runs.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "metric/tile_matrix.h"
#include "test_data.h"

namespace mg {
namespace {

// Random runs, some across clip boundaries and the matrix's edges, each pair as the tiles have
// it: NaN exactly where they have NaN, else within float rounding of theirs (the products'
// cancellation makes small D's error absolute): 1e-4 of the larger of D and the median D,
// what the tiles are held to against the pair-by-pair reference.
void expect_runs_match(const test::TileMatrix& m, int runs) {
  const int n = m.features.frames;
  const double median = test::quantile_of(m, 0.5);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> start(0, n - 1), size(1, 80);
  const DiagonalRuns diagonal(m.features);
  int compared = 0;
  for (int r = 0; r < runs; ++r) {
    const int a = start(rng), b = start(rng);
    const int length = std::min({size(rng), n - a, n - b});
    std::vector<float> out(static_cast<size_t>(length));
    diagonal.distances(a, b, out);
    for (int i = 0; i < length; ++i) {
      const float tiles = m.at(a + i, b + i);
      if (std::isnan(tiles)) {
        EXPECT_TRUE(std::isnan(out[i])) << a + i << "," << b + i;
      } else {
        ASSERT_FALSE(std::isnan(out[i])) << a + i << "," << b + i;
        EXPECT_NEAR(out[i], tiles, 1e-4 * std::max<double>(median, tiles)) << a + i << "," << b + i;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, runs * 5);
}

TEST(DiagonalRuns, EqualTheTilesUniformTaper) {
  expect_runs_match(test::tile_matrix(test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_01.amc"})),
                    400);
}

TEST(DiagonalRuns, EqualTheTilesHannTaperAndATurnedMovedCopy) {
  DistanceSettings settings;
  settings.taper = DistanceSettings::Taper::kHann;
  expect_runs_match(test::tile_matrix(test::small_database({"cmu/16/16_15.amc", "cmu/16/16_57.amc"}, true, 2.0,
                                                           Vec3(30.0, 0.0, -26.0)),
                                      settings),
                    400);
}

TEST(DiagonalRuns, AWholeDiagonalFromTheMatrixCorner) {
  const test::TileMatrix m = test::tile_matrix(test::small_database({"cmu/16/16_35.amc"}));
  const int n = m.features.frames;
  const double median = test::quantile_of(m, 0.5);
  std::vector<float> out(static_cast<size_t>(n));
  DiagonalRuns(m.features).distances(0, 0, out);  // D(a, a): the windows a.. and a-k+1..
  for (int i = 0; i < n; ++i) {
    if (std::isnan(m.at(i, i))) {
      EXPECT_TRUE(std::isnan(out[i])) << i;
    } else {
      EXPECT_NEAR(out[i], m.at(i, i), 1e-4 * std::max<double>(median, m.at(i, i))) << i;
    }
  }
}

}  // namespace
}  // namespace mg
