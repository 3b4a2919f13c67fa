// A histogram of distance values, 64 bins per octave from 2^-40 to 2^40 (linear within each
// octave, read off the float's bits), filled while the tiles stream by, so a threshold can be
// given as a quantile of all finite D values without holding them. Quantiles are exact to the
// bin: within 1.6 %.
#pragma once

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
  // add() for each value (a row of a distance tile), without a branch per value.
  void add_all(std::span<const float> values);
  void merge(const DistanceHistogram& other);
  std::uint64_t total() const { return total_; }
  // The value below which a fraction q (0..1) of the values lie (upper edge of its bin).
  double quantile(double q) const;
  // Fraction of values <= value (bin resolution).
  double fraction_below(double value) const;
  const std::vector<std::uint64_t>& counts() const { return counts_; }
  static double bin_upper_edge(int bin);
  static int bin_of(double value);

  void set_counts(std::vector<std::uint64_t> counts);

 private:
  // The bin of a float given by its bits: 0 for non-positive values (and NaN), else by the
  // exponent and the top 6 mantissa bits.
  static int bin_of_bits(std::uint32_t bits);

  std::vector<std::uint64_t> counts_;
  std::uint64_t total_ = 0;
};

}  // namespace mg
