#include "motiongraph/core/quantile.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace mg {

double quantile(std::span<const double> values, double q) {
  assert(q >= 0.0 && q <= 1.0);
  if (values.empty()) return 0.0;
  std::vector<double> sorted(values.begin(), values.end());
  const double position = q * static_cast<double>(sorted.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(position));
  const size_t above = std::min(below + 1, sorted.size() - 1);
  // Two selections instead of a sort: the rest of the order does not matter.
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(below), sorted.end());
  const double low = sorted[below];
  if (above == below) return low;
  const double high = *std::min_element(sorted.begin() + static_cast<std::ptrdiff_t>(above), sorted.end());
  return low + (high - low) * (position - static_cast<double>(below));
}

}  // namespace mg
