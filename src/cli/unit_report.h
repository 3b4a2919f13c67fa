// The log lines about BVH length units chosen from the figure's size (motion/length_unit.h):
// one info line per file (info, convert), or one per unit for a database (build), and a
// warning for each file whose figure no unit makes human-sized.
#pragma once

#include <string>

#include "motiongraph/database/database_loader.h"
#include "motiongraph/motion/length_unit_choice.h"

namespace mg::cli {

// "cm (0.01 m), figure 1.74 m": what `info` prints as the unit used.
std::string unit_description(const LengthUnitChoice& choice);

void report_unit(const std::string& file, const LengthUnitChoice& choice);
// quiet: the warnings only.
void report_units(const DatabaseLoadNotes& notes, bool quiet);

}  // namespace mg::cli
