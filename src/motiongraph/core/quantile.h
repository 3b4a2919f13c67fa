// Quantiles of a sample, interpolated linearly between order statistics (numpy's default,
// Hyndman & Fan type 7): q = 0 gives the least value, q = 1 the greatest, q = 0.5 the median.
// Used for robust levels (a floor as the 2nd percentile of a joint's heights) and for
// reported percentiles (a 95th percentile of speeds).
#pragma once

#include <span>

namespace mg {

// The q-quantile (0 <= q <= 1) of `values`; 0 for an empty sample. Takes a copy: O(n).
double quantile(std::span<const double> values, double q);

}  // namespace mg
