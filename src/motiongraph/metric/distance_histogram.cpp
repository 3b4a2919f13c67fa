#include "motiongraph/metric/distance_histogram.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <numeric>

namespace mg {

int DistanceHistogram::bin_of_bits(std::uint32_t bits) {
  // The exponent picks the octave, the top 6 mantissa bits the bin in it (64 linear steps
  // per octave: monotonic, at most 1.6 % wide). No log2 per value. Exponent and mantissa bits
  // together, (bits >> 17) & 0x3fff, count bins from exponent 0 on; below kMinExponent
  // (zero, subnormals) is bin 0, from kMaxExponent on the overflow bin. Written as selects.
  const int biased_bin = static_cast<int>((bits >> 17) & 0x3fff) - (127 + kMinExponent) * kBinsPerOctave + 1;
  const int bin = std::clamp(biased_bin, 0, kBins - 1);
  return (bits >> 31) != 0 ? 0 : bin;  // negative
}

int DistanceHistogram::bin_of(double value) {
  if (!(value > 0.0)) return 0;
  return bin_of_bits(std::bit_cast<std::uint32_t>(static_cast<float>(value)));
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

void DistanceHistogram::add_all(std::span<const float> values) {
  // Non-finite values go to bin 0 like the others and are taken back out at the end.
  std::uint64_t rejected = 0;
  for (float value : values) {
    const auto bits = std::bit_cast<std::uint32_t>(value);
    const bool finite = (bits & 0x7f800000u) != 0x7f800000u;
    ++counts_[finite ? bin_of_bits(bits) : 0];
    rejected += finite ? 0 : 1;
  }
  counts_[0] -= rejected;
  total_ += values.size() - rejected;
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
