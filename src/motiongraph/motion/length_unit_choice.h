// A length unit chosen for a file that names none (BVH), and what it gave: see length_unit.h.
#pragma once

#include <string_view>

namespace mg {

struct LengthUnit {
  std::string_view name;   // "m", "cm", "mm", "inch", "CMU unit (1/0.45 inch)"
  double metres_per_unit = 1.0;
};

struct LengthUnitChoice {
  LengthUnit unit;
  double figure_size_units = 0.0;  // the figure's measured size, in the file's units
  double figure_size_m = 0.0;      // the same in metres with the chosen unit
  bool plausible = false;          // some candidate gives a human size
};

}  // namespace mg
