// The tiles the window embedding's bound cannot rule out, against a scan of every pair's
// bound (the brute-force reference) and against the tiles' own D.
#include "motiongraph/metric/bounded_tiles.h"

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "metric/tile_matrix.h"
#include "test_data.h"

namespace mg {
namespace {

using test::quantile_of;

// flags[I][J] = whether a defined pair of tile (I, J) has an embedded bound <= ceiling.
std::vector<char> scanned_tiles(const FrameFeatures& f, const WindowEmbedding& e, int tile, double ceiling) {
  const int n = f.frames, k = f.window, per_side = (n + tile - 1) / tile;
  std::vector<char> flags(static_cast<size_t>(per_side) * per_side, 0);
  for (int a = 0; a < n; ++a) {
    for (int b = k - 1; b < n; ++b) {
      if (!f.can_leave[a] || !f.can_arrive[b]) continue;
      if (e.bound(a, b - k + 1) <= ceiling) flags[static_cast<size_t>(a / tile) * per_side + b / tile] = 1;
    }
  }
  return flags;
}

TEST(BoundedTiles, EqualsAScanOfEveryPairAndHoldsEveryPairBelowTheCeiling) {
  std::mt19937 rng(20261201);
  for (const double fps : {30.0, 60.0}) {
    const test::TileMatrix m =
        test::tile_matrix(test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_57.amc"}, false, 0.0,
                                               Vec3::Zero(), fps));
    auto embedding = make_window_embedding(m.features);
    ASSERT_TRUE(embedding);
    const int n = m.features.frames;
    for (const double q : {0.005, 0.02, 0.1}) {
      const double ceiling = quantile_of(m, q);
      const int tile = 16 + static_cast<int>(rng() % 64);
      const std::string what =
          "fps " + std::to_string(fps) + " q " + std::to_string(q) + " tile " + std::to_string(tile);
      const BoundedTiles found = find_bounded_tiles(m.features, *embedding, tile, ceiling);
      ASSERT_EQ(found.per_side, (n + tile - 1) / tile) << what;
      EXPECT_EQ(found.flags, scanned_tiles(m.features, *embedding, tile, ceiling)) << what;
      // The same on one thread as on three.
      for (const int threads : {1, 3}) {
        EXPECT_EQ(find_bounded_tiles(m.features, *embedding, tile, ceiling, threads).flags, found.flags) << what;
      }
      // A search of some tiles only: theirs flagged as by the whole search, the others never.
      std::vector<char> only(found.flags.size(), 0);
      for (char& c : only) c = static_cast<char>(rng() % 3 == 0);
      const BoundedTiles some = find_bounded_tiles(m.features, *embedding, tile, ceiling, 2, only);
      long long searched_flagged = 0;
      for (size_t t = 0; t < only.size(); ++t) {
        EXPECT_EQ(some.flags[t], only[t] ? found.flags[t] : 0) << what << " tile " << t;
        searched_flagged += only[t] && found.flags[t] ? 1 : 0;
      }
      EXPECT_GT(searched_flagged, 0) << what;
      EXPECT_LT(some.pairs, found.pairs) << what;
      // Exact: every pair whose D is at or below the ceiling lies in a flagged tile (D >= the
      // bound; a hair of float rounding spared).
      long long below = 0;
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
          if (m.at(a, b) <= ceiling * (1.0 - 1e-4)) {
            ++below;
            EXPECT_TRUE(found.flagged(a / tile, b / tile)) << what << ": " << a << "," << b;
          }
        }
      }
      EXPECT_GT(below, 0) << what;
      // And it prunes at the lower ceilings: some tiles are left out.
      if (q < 0.05) {
        EXPECT_LT(found.count(), static_cast<long long>(found.flags.size())) << what;
      }
      EXPECT_GT(found.count(), 0) << what;
      EXPECT_GT(found.pairs, 0) << what;
    }
  }
}

TEST(BoundedTiles, NoCeilingNoTiles) {
  const test::TileMatrix m = test::tile_matrix(test::small_database({"cmu/16/16_15.amc"}));
  auto embedding = make_window_embedding(m.features);
  ASSERT_TRUE(embedding);
  const BoundedTiles none = find_bounded_tiles(m.features, *embedding, 64, -1.0);
  EXPECT_EQ(none.count(), 0);
  EXPECT_EQ(none.per_side, (m.features.frames + 63) / 64);
}

}  // namespace
}  // namespace mg
