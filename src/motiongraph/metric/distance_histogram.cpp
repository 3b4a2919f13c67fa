#include "motiongraph/metric/distance_histogram.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mg {

int DistanceHistogram::bin_of(double value) {
  if (!(value > 0.0)) return 0;
  const double position = (std::log2(value) - kMinExponent) * kBinsPerOctave;
  if (position < 0.0) return 0;
  return std::min(kBins - 1, 1 + static_cast<int>(position));
}

double DistanceHistogram::bin_upper_edge(int bin) {
  if (bin == 0) return std::exp2(static_cast<double>(kMinExponent));
  return std::exp2(kMinExponent + static_cast<double>(bin) / kBinsPerOctave);
}

void DistanceHistogram::add(float value) {
  if (!std::isfinite(value)) return;
  ++counts_[bin_of(value)];
  ++total_;
}

void DistanceHistogram::merge(const DistanceHistogram& other) {
  for (int b = 0; b < kBins; ++b) counts_[b] += other.counts_[b];
  total_ += other.total_;
}

void DistanceHistogram::set_counts(std::vector<std::uint64_t> counts) {
  counts_ = std::move(counts);
  counts_.resize(kBins, 0);
  total_ = std::accumulate(counts_.begin(), counts_.end(), std::uint64_t{0});
}

double DistanceHistogram::quantile(double q) const {
  if (total_ == 0) return 0.0;
  const double wanted = std::clamp(q, 0.0, 1.0) * static_cast<double>(total_);
  std::uint64_t seen = 0;
  for (int b = 0; b < kBins; ++b) {
    seen += counts_[b];
    if (static_cast<double>(seen) >= wanted && seen > 0) return bin_upper_edge(b);
  }
  return bin_upper_edge(kBins - 1);
}

double DistanceHistogram::fraction_below(double value) const {
  if (total_ == 0) return 0.0;
  const int last = bin_of(value);
  std::uint64_t seen = 0;
  for (int b = 0; b <= last; ++b) seen += counts_[b];
  return static_cast<double>(seen) / static_cast<double>(total_);
}

}  // namespace mg
