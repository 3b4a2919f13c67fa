// The pruned distance stage against the exhaustive one run with the same tile side (the
// reference): the same minima up to the ceiling bit for bit, the histogram exact below it and
// a picture that says where it is above, on the bundled clips with randomised choices of clips,
// taper, rate, tile side, ceiling and threads.
#include "motiongraph/graph/pruned_candidates.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "test_data.h"

namespace mg {
namespace {

struct Exhaustive {
  FrameFeatures features;
  CandidateSearch search;  // with the matrix
};

Exhaustive exhaustive_stage(const MotionDatabase& db, const DistanceSettings& distance) {
  Exhaustive e;
  auto layout = make_cloud_layout(db.skeletons[0], {});
  EXPECT_TRUE(layout);
  e.features = *make_frame_features(db, *layout, distance);
  CandidateSettings settings;
  settings.keep_matrix = true;
  auto search = find_candidates(e.features, distance, settings);
  EXPECT_TRUE(search) << search.error().to_string();
  e.search = std::move(*search);
  return e;
}

double quantile(const Exhaustive& e, double q) {
  std::vector<float> finite;
  for (float v : e.search.matrix) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  const auto i = static_cast<std::ptrdiff_t>(q * static_cast<double>(finite.size()));
  std::nth_element(finite.begin(), finite.begin() + i, finite.end());
  return finite[static_cast<size_t>(i)];
}

// Compares the two stages at `ceiling` (the exhaustive stage ran with tiles of
// pruned_settings' side).
void expect_same_below(const Exhaustive& e, double ceiling, const PrunedSearchSettings& pruned_settings,
                       const std::string& what) {
  PrunedSearchStatistics stats;
  auto pruned = find_candidates_pruned(e.features, ceiling, CandidateSettings{}, pruned_settings, &stats);
  ASSERT_TRUE(pruned) << pruned.error().to_string();
  EXPECT_EQ(pruned->ceiling, ceiling);
  // The minima at or below the ceiling: the same pairs with the same D, bit for bit.
  std::vector<Transition> expected;
  for (const Transition& t : e.search.minima) {
    if (t.distance <= ceiling) expected.push_back(t);
  }
  ASSERT_EQ(pruned->minima.size(), expected.size()) << what;
  ASSERT_FALSE(expected.empty()) << what;
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(pruned->minima[i].from_frame, expected[i].from_frame) << what << " minimum " << i;
    EXPECT_EQ(pruned->minima[i].to_frame, expected[i].to_frame) << what << " minimum " << i;
    EXPECT_EQ(pruned->minima[i].distance, expected[i].distance) << what << " minimum " << i;
  }
  // Only some tiles ran, and they held every pair at or below the ceiling.
  const int n = e.features.frames;
  long long below = 0, defined = 0;
  for (float v : e.search.matrix) {
    defined += std::isfinite(v) ? 1 : 0;
    below += v <= ceiling ? 1 : 0;
  }
  EXPECT_EQ(stats.defined_pairs, defined) << what;
  EXPECT_EQ(stats.tile_frames, pruned_settings.tile_for(e.features.window)) << what;
  const long long per_side = (n + stats.tile_frames - 1) / stats.tile_frames;
  EXPECT_EQ(stats.tiles, per_side * per_side) << what;
  EXPECT_LE(stats.tiles_computed, stats.tiles) << what;
  EXPECT_GE(stats.computed_pairs, below) << what;
  // The histogram: all defined pairs; below the ceiling's bin the exhaustive stage's counts.
  ASSERT_EQ(pruned->histogram.total(), e.search.histogram.total()) << what;
  const int last = DistanceHistogram::bin_of(ceiling);
  for (int b = 0; b < last; ++b) {
    EXPECT_EQ(pruned->histogram.counts()[static_cast<size_t>(b)], e.search.histogram.counts()[static_cast<size_t>(b)])
        << what << " bin " << b;
  }
  for (int b = last + 1; b + 1 < DistanceHistogram::kBins; ++b) {
    EXPECT_EQ(pruned->histogram.counts()[static_cast<size_t>(b)], 0u) << what << " bin " << b;
  }
  EXPECT_EQ(pruned->histogram.quantile(0.9999), DistanceHistogram::bin_upper_edge(DistanceHistogram::kBins - 1))
      << what << ": pairs above are not binned";
  // The picture: exact block minima at or below the ceiling, +infinity above, NaN where undefined.
  EXPECT_EQ(pruned->picture_side, e.search.picture_side);
  for (size_t i = 0; i < pruned->picture.size(); ++i) {
    const float x = e.search.picture[i], p = pruned->picture[i];
    if (std::isnan(x)) {
      EXPECT_TRUE(std::isnan(p)) << what << " pixel " << i;
    } else if (x <= ceiling) {
      EXPECT_EQ(p, x) << what << " pixel " << i;
    } else {
      EXPECT_EQ(p, std::numeric_limits<float>::infinity()) << what << " pixel " << i;
    }
  }
}

TEST(PrunedCandidates, SameMinimaHistogramAndPictureAsTheExhaustiveStage) {
  const MotionDatabase db =
      test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_57.amc", "cmu/16/16_01.amc"});
  DistanceSettings distance;
  distance.threads = 2;
  PrunedSearchSettings settings;  // the tile side chosen from the window
  distance.tile_frames = settings.tile_for(distance.window_for(db.fps));
  const Exhaustive e = exhaustive_stage(db, distance);
  PrunedSearchStatistics at_two_percent;
  for (const double q : {0.01, 0.02, 0.06}) {
    expect_same_below(e, quantile(e, q), settings, "quantile " + std::to_string(q));
  }
  ASSERT_TRUE(find_candidates_pruned(e.features, quantile(e, 0.02), {}, settings, &at_two_percent));
  EXPECT_LT(at_two_percent.tiles_computed, at_two_percent.tiles) << "the bound rules no tile out";
  // One thread, and a tile side given.
  settings.threads = 1;
  settings.tile_frames = 96;
  distance.tile_frames = 96;
  const Exhaustive small_tiles = exhaustive_stage(db, distance);
  expect_same_below(small_tiles, quantile(small_tiles, 0.02), settings, "tiles of 96, one thread");
}

TEST(PrunedCandidates, RandomisedClipsTapersRatesTilesCeilingsAndThreads) {
  const std::vector<std::string> clips = {"cmu/16/16_01.amc", "cmu/16/16_11.amc", "cmu/16/16_15.amc",
                                          "cmu/16/16_17.amc", "cmu/16/16_35.amc", "cmu/16/16_37.amc",
                                          "cmu/16/16_43.amc", "cmu/16/16_57.amc"};
  std::mt19937 rng(20261201);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<std::string> chosen = clips;
    std::shuffle(chosen.begin(), chosen.end(), rng);
    chosen.resize(2 + rng() % 2);
    const double fps = trial % 2 == 0 ? 30.0 : 60.0;
    DistanceSettings distance;
    distance.threads = 2;
    distance.taper = rng() % 2 == 0 ? DistanceSettings::Taper::kUniform : DistanceSettings::Taper::kHann;
    distance.tile_frames = 32 + static_cast<int>(rng() % 200);
    const Exhaustive e = exhaustive_stage(test::small_database(chosen, false, 0.0, Vec3::Zero(), fps), distance);
    PrunedSearchSettings settings;
    settings.tile_frames = distance.tile_frames;
    settings.threads = 1 + static_cast<int>(rng() % 3);
    // A ceiling between the 10th and the 60th percentile of the minima's D.
    std::vector<float> minima;
    for (const Transition& t : e.search.minima) minima.push_back(t.distance);
    ASSERT_GT(minima.size(), 10u);
    std::sort(minima.begin(), minima.end());
    const double q = std::uniform_real_distribution<double>(0.1, 0.6)(rng);
    const double ceiling = minima[static_cast<size_t>(q * static_cast<double>(minima.size()))];
    expect_same_below(e, ceiling, settings, "trial " + std::to_string(trial));
  }
}

TEST(PrunedCandidates, TileSideFromTheWindow) {
  PrunedSearchSettings automatic;
  EXPECT_EQ(automatic.tile_for(10), 64);   // 30 fps
  EXPECT_EQ(automatic.tile_for(40), 256);  // 120 fps
  for (int k = 1; k < 400; ++k) {
    const int tile = automatic.tile_for(k);
    EXPECT_GE(tile, 64);
    EXPECT_EQ(tile % 64, 0);
    EXPECT_LE(tile, std::max(64, 7 * k + 64));
    EXPECT_GE(tile, 6 * k - 64);
  }
  PrunedSearchSettings given;
  given.tile_frames = 200;
  EXPECT_EQ(given.tile_for(40), 200);
}

TEST(PrunedCandidates, RefusesTheMatrixBadSettingsAndABadCeiling) {
  DistanceSettings distance;
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  auto layout = make_cloud_layout(db.skeletons[0], {});
  const FrameFeatures f = *make_frame_features(db, *layout, distance);
  CandidateSettings with_matrix;
  with_matrix.keep_matrix = true;
  auto refused = find_candidates_pruned(f, 1.0, with_matrix);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("holds no matrix"), std::string::npos);
  EXPECT_FALSE(find_candidates_pruned(f, -1.0, CandidateSettings{}));
  EXPECT_FALSE(find_candidates_pruned(f, std::nan(""), CandidateSettings{}));
  PrunedSearchSettings bad_tile;
  bad_tile.tile_frames = 8;
  EXPECT_FALSE(find_candidates_pruned(f, 1.0, CandidateSettings{}, bad_tile));
  PrunedSearchSettings bad_threads;
  bad_threads.threads = -1;
  EXPECT_FALSE(find_candidates_pruned(f, 1.0, CandidateSettings{}, bad_threads));
  // A ceiling of zero finds nothing but still counts every pair.
  auto none = find_candidates_pruned(f, 0.0, CandidateSettings{});
  ASSERT_TRUE(none);
  EXPECT_GT(none->histogram.total(), 0u);
}

}  // namespace
}  // namespace mg
