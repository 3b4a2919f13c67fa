#include "motiongraph/metric/distance_histogram.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <numeric>

#include "motiongraph/core/vector_clones.h"

namespace mg {

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

namespace {

// bins[m] = the bin of values[m], or DistanceHistogram::kBins for NaN and infinities.
MG_VECTOR_CLONES void bins_of_row(int count, const float* __restrict values, std::uint16_t* __restrict bins) {
  for (int m = 0; m < count; ++m) {
    const auto bits = std::bit_cast<std::uint32_t>(values[m]);
    const bool finite = (bits & 0x7f800000u) != 0x7f800000u;
    bins[m] = static_cast<std::uint16_t>(finite ? DistanceHistogram::bin_of_bits(bits) : DistanceHistogram::kBins);
  }
}

}  // namespace

void DistanceHistogram::add_block(const float* first, int rows, int cols, std::ptrdiff_t stride) {
  if (rows <= 0 || cols <= 0) return;
  // Four partial histograms (plus a slot for the non-finite), value m going to partial m % 4,
  // so that a run of equal bins is four independent chains of increments, not one.
  constexpr int kPartials = 4;
  constexpr int kSlots = kBins + 1;
  std::vector<std::uint64_t> partial(static_cast<size_t>(kPartials) * kSlots, 0);
  std::vector<std::uint16_t> bins(static_cast<size_t>(cols));
  for (int r = 0; r < rows; ++r) {
    bins_of_row(cols, first + r * stride, bins.data());
    int m = 0;
    for (; m + kPartials <= cols; m += kPartials) {
      for (int p = 0; p < kPartials; ++p) ++partial[static_cast<size_t>(p) * kSlots + bins[m + p]];
    }
    for (; m < cols; ++m) ++partial[bins[m]];
  }
  for (int b = 0; b < kBins; ++b) {
    std::uint64_t sum = 0;
    for (int p = 0; p < kPartials; ++p) sum += partial[static_cast<size_t>(p) * kSlots + b];
    counts_[b] += sum;
    total_ += sum;
  }
}

void DistanceHistogram::merge(const DistanceHistogram& other) {
  for (int b = 0; b < kBins; ++b) counts_[b] += other.counts_[b];
  total_ += other.total_;
}

void DistanceHistogram::fold_above(double value) {
  for (int b = bin_of(value) + 1; b < kBins - 1; ++b) {
    counts_.back() += counts_[b];
    counts_[b] = 0;
  }
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
