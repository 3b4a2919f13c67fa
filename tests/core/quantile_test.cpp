#include "motiongraph/core/quantile.h"

#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace mg {
namespace {

// The definition, by sorting: the value at fractional rank q (n - 1), linearly interpolated.
double sorted_reference(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const double rank = q * static_cast<double>(values.size() - 1);
  const size_t i = static_cast<size_t>(rank);
  if (i + 1 >= values.size()) return values.back();
  return values[i] + (values[i + 1] - values[i]) * (rank - static_cast<double>(i));
}

TEST(Quantile, SmallCasesByHand) {
  const std::vector<double> values = {4.0, 1.0, 3.0, 2.0};
  EXPECT_DOUBLE_EQ(quantile(values, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(values, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(quantile(values, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile(values, 1.0 / 3.0), 2.0);
  EXPECT_DOUBLE_EQ(quantile(std::vector<double>{7.0}, 0.3), 7.0);
  EXPECT_DOUBLE_EQ(quantile(std::vector<double>{}, 0.3), 0.0);
}

TEST(Quantile, AgreesWithSortingOnRandomSamplesWithTies) {
  std::mt19937 random(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + static_cast<int>(random() % 40);
    std::vector<double> values(static_cast<size_t>(n));
    for (double& v : values) v = static_cast<double>(random() % 9) - 4.0;  // many ties
    for (double q : {0.0, 0.02, 0.25, 0.5, 0.95, 0.999, 1.0}) {
      EXPECT_DOUBLE_EQ(quantile(values, q), sorted_reference(values, q)) << n << " " << q;
    }
  }
}

}  // namespace
}  // namespace mg
