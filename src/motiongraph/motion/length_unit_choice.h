// A length unit chosen for a file that names none (BVH), and what it gave: see length_unit.h.
#pragma once

#include <optional>
#include <string_view>

namespace mg {

struct LengthUnit {
  std::string_view name;   // "m", "cm", "mm", "inch", "CMU unit (1/0.45 inch)"
  double metres_per_unit = 1.0;
};

// The units a file's lengths may be given in, by --scale (metres per unit) or --output-scale
// (units per metre): from the micrometre to 1000 km. Beyond, a person's figure is a speck or
// beyond a float's range, and the files written from it hold infinities.
inline constexpr double kMinLengthUnitScale = 1e-6;
inline constexpr double kMaxLengthUnitScale = 1e6;

// Whether `scale` lies in that range (false for NaN).
constexpr bool is_length_unit_scale(double scale) {
  return scale >= kMinLengthUnitScale && scale <= kMaxLengthUnitScale;
}

struct LengthUnitChoice {
  LengthUnit unit;
  double figure_size_units = 0.0;  // the figure's measured size, in the file's units
  double figure_size_m = 0.0;      // the same in metres with the chosen unit
  bool plausible = false;          // some candidate gives a human size
  // Another unit that gives a human size too, the next closest to a typical one (a child of
  // 0.95 m in cm is a giant of 2.4 m in inches, which is chosen): the choice was a guess.
  std::optional<LengthUnit> also;
  double also_figure_size_m = 0.0;
};

}  // namespace mg
