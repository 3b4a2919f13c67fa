// The distance histogram: bins read off a float's bits, and the row-at-a-time add_all that
// the distance stage uses, against add() value by value.
#include "motiongraph/metric/distance_histogram.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace mg {
namespace {

TEST(DistanceHistogram, BinsFollowTheirEdges) {
  EXPECT_EQ(DistanceHistogram::bin_of(0.0), 0);
  EXPECT_EQ(DistanceHistogram::bin_of(-3.0), 0);
  EXPECT_EQ(DistanceHistogram::bin_of(std::exp2(-45.0)), 0);
  EXPECT_EQ(DistanceHistogram::bin_of(std::exp2(45.0)), DistanceHistogram::kBins - 1);
  // Every value just below a bin's upper edge is in that bin, just above it in the next.
  for (int bin = 1; bin < DistanceHistogram::kBins - 1; bin += 7) {
    const double edge = DistanceHistogram::bin_upper_edge(bin);
    EXPECT_EQ(DistanceHistogram::bin_of(edge * (1.0 - 1e-6)), bin) << bin;
    EXPECT_EQ(DistanceHistogram::bin_of(edge * (1.0 + 1e-6)), bin + 1) << bin;
  }
}

TEST(DistanceHistogram, AddAllCountsAsAddDoes) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> values = {0.0f, -0.0f, -1.5f, 1e-30f, 1e-45f, 1e30f, inf, -inf, nan, 1.0f, 1.0f, 3.25f};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> exponent(-50.0f, 50.0f);
  for (int i = 0; i < 5000; ++i) {
    values.push_back(i % 17 == 0 ? nan : std::exp2(exponent(rng)));
  }
  DistanceHistogram one_by_one, all;
  for (float v : values) one_by_one.add(v);
  all.add_all(values);
  all.add_all({});
  EXPECT_EQ(all.total(), one_by_one.total());
  EXPECT_EQ(all.counts(), one_by_one.counts());
  // NaN and infinities are not counted.
  size_t finite = 0;
  for (float v : values) finite += std::isfinite(v) ? 1 : 0;
  EXPECT_EQ(all.total(), finite);
}

TEST(DistanceHistogram, FoldAboveKeepsFractionsBelowAndTheTotal) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(0.0, 100.0);
  DistanceHistogram h;
  for (int i = 0; i < 20000; ++i) h.add(static_cast<float>(value(rng)));
  const DistanceHistogram before = h;
  const double ceiling = 37.5;
  h.fold_above(ceiling);
  EXPECT_EQ(h.total(), before.total());
  for (double v : {0.5, 10.0, 30.0, 37.0, ceiling}) EXPECT_EQ(h.fraction_below(v), before.fraction_below(v)) << v;
  // Above the ceiling's bin everything sits in the overflow bin.
  const int last = DistanceHistogram::bin_of(ceiling);
  EXPECT_EQ(h.fraction_below(99.0), h.fraction_below(ceiling));
  EXPECT_LT(before.fraction_below(ceiling), before.fraction_below(99.0));
  EXPECT_EQ(h.counts().back(), before.total() - static_cast<std::uint64_t>(before.fraction_below(ceiling) *
                                                                          static_cast<double>(before.total()) + 0.5));
  EXPECT_GT(h.counts()[static_cast<size_t>(last)], 0u);
  EXPECT_EQ(h.quantile(0.99), DistanceHistogram::bin_upper_edge(DistanceHistogram::kBins - 1));
}

}  // namespace
}  // namespace mg
