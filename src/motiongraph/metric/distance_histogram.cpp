#include "motiongraph/metric/distance_histogram.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <numeric>

namespace mg {

int DistanceHistogram::bin_of(double value) {
  if (!(value > 0.0)) return 0;
  // From the float's bits: the exponent picks the octave, the top 6 mantissa bits the bin in
  // it (64 linear steps per octave: monotonic, at most 1.6 % wide). No log2 per value.
  const auto bits = std::bit_cast<std::uint32_t>(static_cast<float>(value));
  const int exponent = static_cast<int>((bits >> 23) & 0xff) - 127;
  if (exponent < kMinExponent) return 0;
  if (exponent >= kMaxExponent) return kBins - 1;
  return 1 + (exponent - kMinExponent) * kBinsPerOctave + static_cast<int>((bits >> 17) & 63);
}

double DistanceHistogram::bin_upper_edge(int bin) {
  if (bin == 0) return std::exp2(static_cast<double>(kMinExponent));
  if (bin >= kBins - 1) return std::exp2(static_cast<double>(kMaxExponent));
  const int octave = (bin - 1) / kBinsPerOctave;
  const int step = (bin - 1) % kBinsPerOctave;
  return std::exp2(static_cast<double>(kMinExponent + octave)) * (1.0 + (step + 1.0) / kBinsPerOctave);
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
