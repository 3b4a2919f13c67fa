// The log lines about BVH length units chosen from the figure's size (motion/length_unit.h):
// one info line per file (info, convert), or one per unit for a database (build), and a
// warning for each file whose figure no unit makes human-sized. Likewise for the files read z
// up (motion/up_axis.h).
#pragma once

#include <string>

#include "motiongraph/database/database_loader.h"
#include "motiongraph/motion/length_unit_choice.h"
#include "motiongraph/motion/up_axis_choice.h"

namespace mg::cli {

// "cm (0.01 m), figure 1.74 m": what `info` prints as the unit used.
std::string unit_description(const LengthUnitChoice& choice);

void report_unit(const std::string& file, const LengthUnitChoice& choice);
// "z (the figure stands along z: 3.1 times its depth; turned y up)": what `info` prints.
std::string up_axis_description(const UpAxisChoice& choice);
// An info line for a file read z up (nothing for y, BVH's own convention).
void report_up_axis(const std::string& file, const UpAxisChoice& choice);
// Also one info line for the files read z up. quiet: the warnings only.
void report_units(const DatabaseLoadNotes& notes, bool quiet);

}  // namespace mg::cli
