// The pruned distance stage against the exhaustive one (the reference): the same minima up to
// the ceiling, an exact histogram below it and a picture that says where it is above, on the
// bundled clips with randomised choices of clips, taper, rate, ceiling and band size.
#include "motiongraph/graph/pruned_candidates.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "test_data.h"

namespace mg {
namespace {

struct Stages {
  FrameFeatures features;
  CandidateSearch exhaustive;  // with the matrix
  double scale = 0.0;          // the median D: rounding is relative to max(D, scale)
};

Stages exhaustive_stage(const MotionDatabase& db, const DistanceSettings& distance) {
  Stages s;
  auto layout = make_cloud_layout(db.skeletons[0], {});
  EXPECT_TRUE(layout);
  s.features = *make_frame_features(db, *layout, distance);
  CandidateSettings settings;
  settings.keep_matrix = true;
  auto search = find_candidates(s.features, distance, settings);
  EXPECT_TRUE(search) << search.error().to_string();
  s.exhaustive = std::move(*search);
  s.scale = s.exhaustive.histogram.quantile(0.5);
  return s;
}

float at(const Stages& s, int a, int b) {
  const int n = s.features.frames;
  if (a < 0 || b < 0 || a >= n || b >= n) return std::numeric_limits<float>::quiet_NaN();
  return s.exhaustive.matrix[static_cast<size_t>(a) * n + b];
}

// The two stages' D agree to float rounding: 2e-4 of max(D, the median D) (a D near zero is a
// difference of large sums).
double rounding(const Stages& s, double d) { return 2e-4 * std::max(d, s.scale); }

// Whether the exhaustive D of (a, b) lies within float rounding of one of its
// neighbours' or of the ceiling: the only pairs whose decision may differ between two ways of
// summing the same products.
bool is_tie(const Stages& s, int a, int b, double ceiling) {
  const double d = at(s, a, b);
  const double tolerance = rounding(s, d);
  if (std::abs(d - ceiling) <= tolerance) return true;
  for (int da = -1; da <= 1; ++da) {
    for (int db = -1; db <= 1; ++db) {
      const float v = at(s, a + da, b + db);
      if ((da != 0 || db != 0) && std::isfinite(v) && std::abs(v - d) <= tolerance) return true;
    }
  }
  return false;
}

double quantile(const Stages& s, double q) {
  std::vector<float> finite;
  for (float v : s.exhaustive.matrix) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  const auto i = static_cast<std::ptrdiff_t>(q * static_cast<double>(finite.size()));
  std::nth_element(finite.begin(), finite.begin() + i, finite.end());
  return finite[static_cast<size_t>(i)];
}

// Compares the two stages at `ceiling`; returns how many minima differed (all ties).
int expect_same_below(const Stages& s, double ceiling, const PrunedSearchSettings& pruned_settings,
                      const std::string& what) {
  PrunedSearchStatistics stats;
  auto pruned = find_candidates_pruned(s.features, ceiling, CandidateSettings{}, pruned_settings, &stats);
  EXPECT_TRUE(pruned) << pruned.error().to_string();
  if (!pruned) return 0;
  EXPECT_EQ(pruned->ceiling, ceiling);
  std::map<std::pair<int, int>, float> expected, got;
  for (const Transition& t : s.exhaustive.minima) {
    if (t.distance <= ceiling) expected[{t.from_frame, t.to_frame}] = t.distance;
  }
  for (const Transition& t : pruned->minima) {
    EXPECT_LE(t.distance, ceiling) << what;
    got[{t.from_frame, t.to_frame}] = t.distance;
  }
  EXPECT_TRUE(std::is_sorted(pruned->minima.begin(), pruned->minima.end(), [](const Transition& x, const Transition& y) {
    return std::make_pair(x.from_frame, x.to_frame) < std::make_pair(y.from_frame, y.to_frame);
  }));
  int differences = 0;
  for (const auto& [pair, d] : expected) {
    auto it = got.find(pair);
    if (it == got.end()) {
      ++differences;
      EXPECT_TRUE(is_tie(s, pair.first, pair.second, ceiling))
          << what << ": exhaustive minimum " << pair.first << "," << pair.second << " (D " << d << ") missing";
    } else {
      EXPECT_NEAR(it->second, d, rounding(s, d)) << what;
    }
  }
  for (const auto& [pair, d] : got) {
    if (expected.count(pair) == 0) {
      ++differences;
      EXPECT_TRUE(is_tie(s, pair.first, pair.second, ceiling))
          << what << ": extra minimum " << pair.first << "," << pair.second << " (D " << d << ")";
    }
  }
  EXPECT_LE(differences, std::max<size_t>(2, expected.size() / 200)) << what;
  EXPECT_GT(expected.size(), 0u) << what;
  // Only part of the pairs was computed, and every pair at or below the ceiling was.
  long long below = 0, defined = 0;
  for (float v : s.exhaustive.matrix) {
    defined += std::isfinite(v) ? 1 : 0;
    below += v <= ceiling ? 1 : 0;
  }
  EXPECT_EQ(stats.defined_pairs, defined) << what;
  EXPECT_GE(stats.candidate_pairs, below) << what;
  EXPECT_LT(stats.candidate_pairs, defined) << what;
  // The histogram: all defined pairs, exact below the ceiling (to the bin of values that sit
  // on a bin edge within rounding).
  EXPECT_EQ(pruned->histogram.total(), s.exhaustive.histogram.total()) << what;
  for (double t : {0.25 * ceiling, 0.5 * ceiling, 0.9 * ceiling}) {
    // Within the rounding of D and a bin (1.6 %) of t.
    const double r = rounding(s, t) + 0.02 * t;
    EXPECT_GE(pruned->histogram.fraction_below(t), s.exhaustive.histogram.fraction_below(t - r)) << what;
    EXPECT_LE(pruned->histogram.fraction_below(t), s.exhaustive.histogram.fraction_below(t + r)) << what;
  }
  EXPECT_GT(pruned->histogram.quantile(0.999), 1e6 * ceiling) << what << ": pairs above are not binned";
  // The picture: exact block minima at or below the ceiling, +infinity above, NaN where undefined.
  EXPECT_EQ(pruned->picture_side, s.exhaustive.picture_side);
  for (size_t i = 0; i < pruned->picture.size(); ++i) {
    const float e = s.exhaustive.picture[i], p = pruned->picture[i];
    if (std::isnan(e)) {
      EXPECT_TRUE(std::isnan(p)) << what << " pixel " << i;
    } else if (e <= ceiling - rounding(s, e)) {
      EXPECT_NEAR(p, e, rounding(s, e)) << what << " pixel " << i;
    } else if (e > ceiling + rounding(s, e)) {
      EXPECT_EQ(p, std::numeric_limits<float>::infinity()) << what << " pixel " << i;
    }
  }
  return differences;
}

TEST(PrunedCandidates, SameMinimaHistogramAndPictureAsTheExhaustiveStage) {
  DistanceSettings distance;
  distance.threads = 2;
  const Stages s = exhaustive_stage(
      test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_57.amc", "cmu/16/16_01.amc"}), distance);
  int differences = 0;
  for (const double q : {0.01, 0.02, 0.06}) {
    PrunedSearchSettings settings;
    differences += expect_same_below(s, quantile(s, q), settings, "quantile " + std::to_string(q));
  }
  // Bands of a few hundred pairs: runs cut at every band, neighbours read across them.
  PrunedSearchSettings small_bands;
  small_bands.band_pairs = 300;
  small_bands.threads = 1;
  differences += expect_same_below(s, quantile(s, 0.02), small_bands, "small bands");
  RecordProperty("tie_differences", differences);
}

TEST(PrunedCandidates, RandomisedClipsTapersRatesCeilingsAndBands) {
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
    distance.tile_frames = 128 << (rng() % 3);
    const Stages s = exhaustive_stage(test::small_database(chosen, false, 0.0, Vec3::Zero(), fps), distance);
    PrunedSearchSettings settings;
    settings.band_pairs = 1 << (8 + rng() % 10);
    settings.threads = 1 + static_cast<int>(rng() % 2);
    // A ceiling between the 10th and the 60th percentile of the minima's D.
    std::vector<float> minima;
    for (const Transition& t : s.exhaustive.minima) minima.push_back(t.distance);
    ASSERT_GT(minima.size(), 10u);
    std::sort(minima.begin(), minima.end());
    const double q = std::uniform_real_distribution<double>(0.1, 0.6)(rng);
    const double ceiling = minima[static_cast<size_t>(q * static_cast<double>(minima.size()))];
    expect_same_below(s, ceiling, settings, "trial " + std::to_string(trial));
  }
}

TEST(PrunedCandidates, RefusesTheMatrixAndABadCeiling) {
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
  PrunedSearchSettings no_band;
  no_band.band_pairs = 0;
  EXPECT_FALSE(find_candidates_pruned(f, 1.0, CandidateSettings{}, no_band));
  // A ceiling of zero finds nothing but still counts every pair.
  auto none = find_candidates_pruned(f, 0.0, CandidateSettings{});
  ASSERT_TRUE(none);
  EXPECT_GT(none->histogram.total(), 0u);
}

}  // namespace
}  // namespace mg
