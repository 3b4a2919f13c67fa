// A histogram of distance values, 64 bins per octave from 2^-40 to 2^40 (linear within each
// octave, read off the float's bits), filled while the tiles stream by, so a threshold can be
// given as a quantile of all finite D values without holding them. Quantiles are exact to the
// bin: within 1.6 %.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mg {

class DistanceHistogram {
 public:
  static constexpr int kBinsPerOctave = 64;
  static constexpr int kMinExponent = -40;
  static constexpr int kMaxExponent = 40;
  static constexpr int kBins = (kMaxExponent - kMinExponent) * kBinsPerOctave + 2;  // + zero, + overflow

  DistanceHistogram() : counts_(kBins, 0) {}

  void add(float value);
  // add() for each value, without a branch per value.
  void add_all(std::span<const float> values) { add_block(values.data(), 1, static_cast<int>(values.size()), 0); }
  // add() for each value of a block of `rows` rows of `cols` values, row r starting at
  // first + r * stride (a tile of the distance matrix): bins in a vector loop, counted in
  // interleaved partial histograms (neighbouring distances often share a bin).
  void add_block(const float* first, int rows, int cols, std::ptrdiff_t stride);
  void merge(const DistanceHistogram& other);
  // `count` values known only to lie above every binned one (the pruned distance stage's pairs
  // above its ceiling): counted in the overflow bin, so fractions below any binned value stay
  // exact.
  void add_above(std::uint64_t count) {
    counts_.back() += count;
    total_ += count;
  }
  // Moves the counts of every bin above `value`'s into the overflow bin: what the pruned
  // distance stage does with the pairs it computed above its ceiling, since the pairs it left
  // out would fall there too.
  void fold_above(double value);
  std::uint64_t total() const { return total_; }
  // The value below which a fraction q (0..1) of the values lie (upper edge of its bin).
  double quantile(double q) const;
  // Fraction of values <= value (bin resolution).
  double fraction_below(double value) const;
  const std::vector<std::uint64_t>& counts() const { return counts_; }
  static double bin_upper_edge(int bin);
  static int bin_of(double value);
  // The bin of a positive finite float given by its bits (0 for negative values): the
  // exponent picks the octave, the top 6 mantissa bits the bin in it (64 linear steps per
  // octave: monotonic, at most 1.6 % wide), no log2. Exponent and mantissa bits together,
  // (bits >> 17) & 0x3fff, count bins from exponent 0 on; below kMinExponent (zero,
  // subnormals) is bin 0, from kMaxExponent on the overflow bin. Selects only (vectorises).
  static int bin_of_bits(std::uint32_t bits) {
    const int biased_bin = static_cast<int>((bits >> 17) & 0x3fff) - (127 + kMinExponent) * kBinsPerOctave + 1;
    const int bin = biased_bin < 0 ? 0 : biased_bin > kBins - 1 ? kBins - 1 : biased_bin;
    return (bits >> 31) != 0 ? 0 : bin;
  }

  void set_counts(std::vector<std::uint64_t> counts);

 private:

  std::vector<std::uint64_t> counts_;
  std::uint64_t total_ = 0;
};

}  // namespace mg
