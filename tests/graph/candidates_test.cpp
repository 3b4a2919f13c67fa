// Local minima found tile by tile against a brute-force search of the whole matrix, and the
// selection rules (threshold, locality, alignment) checked from their definitions.
#include "motiongraph/graph/candidates.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "motiongraph/graph/transition_selection.h"
#include "motiongraph/metric/reference_distance.h"
#include "test_data.h"

namespace mg {
namespace {

struct Fixture {
  MotionDatabase db;
  FrameFeatures features;
  CandidateSearch search;
};

Fixture run(int tile_frames, int picture_side = CandidateSettings{}.picture_side) {
  Fixture x;
  x.db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_17.amc"});
  DistanceSettings distance;
  distance.tile_frames = tile_frames;
  distance.threads = 2;
  auto layout = make_cloud_layout(x.db.skeletons[0], {});
  x.features = *make_frame_features(x.db, *layout, distance);
  CandidateSettings settings;
  settings.keep_matrix = true;
  settings.picture_side = picture_side;
  auto search = find_candidates(x.features, distance, settings);
  EXPECT_TRUE(search) << search.error().to_string();
  x.search = std::move(*search);
  return x;
}

std::set<std::pair<int, int>> brute_force_minima(const Fixture& x) {
  const int n = x.features.frames;
  const int k = x.features.window;
  auto d = [&](int a, int b) { return x.search.matrix[static_cast<size_t>(a) * n + b]; };
  std::set<std::pair<int, int>> minima;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      if (!std::isfinite(d(a, b))) continue;
      if (x.db.clip_of(a) == x.db.clip_of(b) && std::abs(b - (a + k - 1)) <= k) continue;
      bool minimum = true;
      for (int da = -1; da <= 1; ++da) {
        for (int db = -1; db <= 1; ++db) {
          const int na = a + da, nb = b + db;
          if ((da == 0 && db == 0) || na < 0 || nb < 0 || na >= n || nb >= n || !std::isfinite(d(na, nb))) continue;
          if (d(na, nb) < d(a, b) || (d(na, nb) == d(a, b) && (na * n + nb) < (a * n + b))) minimum = false;
        }
      }
      if (minimum) minima.insert({a, b});
    }
  }
  return minima;
}

TEST(Candidates, TileBordersDoNotChangeTheMinima) {
  const Fixture small_tiles = run(37);
  const Fixture one_tile = run(4096);
  std::set<std::pair<int, int>> found;
  for (const Transition& t : small_tiles.search.minima) found.insert({t.from_frame, t.to_frame});
  const auto expected = brute_force_minima(one_tile);
  EXPECT_GT(expected.size(), 20u);
  EXPECT_EQ(found, expected);
  EXPECT_EQ(small_tiles.search.histogram.total(), one_tile.search.histogram.total());
  // The histogram counts every finite pair once.
  size_t finite = 0;
  for (float v : one_tile.search.matrix) finite += std::isfinite(v) ? 1 : 0;
  EXPECT_EQ(one_tile.search.histogram.total(), finite);
}

TEST(Candidates, PictureHoldsBlockMinima) {
  // One frame a pixel, and blocks of several frames that tile borders cut.
  for (const auto& [tile_frames, picture_side] : {std::pair{100, 1024}, std::pair{37, 16}}) {
    const Fixture x = run(tile_frames, picture_side);
    const int n = x.features.frames;
    const int block = x.search.picture_block;
    if (picture_side == 16) {
      EXPECT_GT(block, 1);
      EXPECT_NE(tile_frames % block, 0);
    }
    for (int row = 0; row < x.search.picture_side; row += picture_side == 16 ? 1 : 5) {
      for (int col = 0; col < x.search.picture_side; col += picture_side == 16 ? 1 : 3) {
        float expected = NAN;
        for (int a = row * block; a < std::min(n, (row + 1) * block); ++a) {
          for (int b = col * block; b < std::min(n, (col + 1) * block); ++b) {
            const float v = x.search.matrix[static_cast<size_t>(a) * n + b];
            if (std::isfinite(v) && !(expected <= v)) expected = v;
          }
        }
        const float pixel = x.search.picture[static_cast<size_t>(row) * x.search.picture_side + col];
        if (std::isnan(expected)) {
          EXPECT_TRUE(std::isnan(pixel)) << row << "," << col;
        } else {
          EXPECT_EQ(pixel, expected) << row << "," << col;
        }
      }
    }
  }
}

// A stop asked for while the tiles run passes over the work items not begun and fails the search
// with ErrorKind::kStopped; one asked for before any runs none.
TEST(Candidates, StopsWhenAsked) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc"});
  DistanceSettings distance;
  distance.tile_frames = 37;
  distance.threads = 1;  // items one after another: the count below is exact
  auto layout = make_cloud_layout(db.skeletons[0], {});
  const FrameFeatures features = *make_frame_features(db, *layout, distance);
  const long long all_tiles = [&] {
    const TileItems grid = tile_items(features, distance);
    return static_cast<long long>(grid.per_side) * grid.per_side;
  }();
  ASSERT_GT(all_tiles, 20);
  std::stop_source stop;
  long long visited = 0;
  auto search = find_candidates(
      features, distance, {},
      [&](long long done, long long) {
        visited = done;
        if (done == 5) stop.request_stop();
      },
      {}, {}, stop.get_token());
  ASSERT_FALSE(search);
  EXPECT_EQ(search.error().kind, ErrorKind::kStopped);
  // The item under way when asked finishes (its mirror tile, at most): none after it begins.
  EXPECT_GE(visited, 5);
  EXPECT_LE(visited, 6);

  std::stop_source before;
  before.request_stop();
  visited = 0;
  auto none = find_candidates(features, distance, {}, [&](long long done, long long) { visited = done; }, {}, {},
                              before.get_token());
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().kind, ErrorKind::kStopped);
  EXPECT_EQ(visited, 0);
  // A token that never asks runs them all.
  auto whole = find_candidates(features, distance, {}, [&](long long done, long long) { visited = done; }, {}, {},
                               std::stop_source().get_token());
  ASSERT_TRUE(whole) << whole.error().to_string();
  EXPECT_EQ(visited, all_tiles);
}

TEST(TransitionSelection, ThresholdLocalityAndAlignment) {
  const Fixture x = run(128);
  TransitionSettings settings;
  settings.threshold_quantile = 0.05;
  auto selection = select_transitions(x.features, x.search, settings);
  ASSERT_TRUE(selection) << selection.error().to_string();
  const auto& kept = selection->transitions;
  ASSERT_GT(kept.size(), 5u);
  const int r = selection->locality_radius;
  EXPECT_EQ(r, x.features.window / 2);
  for (size_t i = 0; i < kept.size(); ++i) {
    EXPECT_LE(kept[i].distance, selection->threshold);
    for (size_t j = i + 1; j < kept.size(); ++j) {
      EXPECT_FALSE(std::abs(kept[i].from_frame - kept[j].from_frame) <= r &&
                   std::abs(kept[i].to_frame - kept[j].to_frame) <= r);
    }
  }
  // Every candidate below the threshold is kept or has a better kept one within the radius.
  for (const Transition& c : x.search.minima) {
    if (c.distance > selection->threshold) continue;
    bool covered = false;
    for (const Transition& t : kept) {
      covered |= std::abs(t.from_frame - c.from_frame) <= r && std::abs(t.to_frame - c.to_frame) <= r &&
                 t.distance <= c.distance;
    }
    EXPECT_TRUE(covered) << c.from_frame << "->" << c.to_frame;
  }
  // The quantile threshold lets about that fraction of the finite distances through.
  EXPECT_NEAR(selection->threshold_quantile, 0.05, 0.01);
  // Alignments are the reference's.
  const int p = x.features.points;
  const std::vector<Vec3> clouds = database_clouds(x.db, *make_cloud_layout(x.db.skeletons[0], {}));
  for (const Transition& t : kept) {
    const auto ref = reference_distance(clouds, p, x.features.point_weights, x.features.taper, t.from_frame, t.to_frame);
    EXPECT_NEAR(t.yaw_rad, ref.alignment.yaw_rad, 1e-4);
    EXPECT_NEAR(t.x_m, ref.alignment.x_m, 1e-4);
    EXPECT_NEAR(t.z_m, ref.alignment.z_m, 1e-4);
    // float32 products: agreement within 1e-4 of the median distance (DESIGN.md 3.3).
    EXPECT_NEAR(t.distance, ref.distance, 1e-4 * x.search.histogram.quantile(0.5));
  }
  // An absolute threshold is used as given.
  settings.threshold = selection->threshold / 2;
  auto stricter = select_transitions(x.features, x.search, settings);
  ASSERT_TRUE(stricter);
  EXPECT_EQ(stricter->threshold, selection->threshold / 2);
  EXPECT_LT(stricter->transitions.size(), kept.size());
}

}  // namespace
}  // namespace mg
