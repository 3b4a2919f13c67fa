// The log lines about BVH length units chosen from the figure's size (motion/length_unit.h):
// one info line per file (info, convert), or one per unit for a database (build), and a
// warning for each file whose figure no unit makes human-sized. Likewise for the files read z
// up (motion/up_axis.h), and for the clips whose travel was recovered from their feet
// (motion/in_place.h).
#pragma once

#include <string>
#include <vector>

#include "motiongraph/database/database_loader.h"
#include "motiongraph/motion/capture_glitches.h"
#include "motiongraph/motion/in_place_choice.h"
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
// "in place as read (planted feet slide 0.84 m/s, the root moves 0.00 m/s); 3.67 m of travel
// recovered from the planted feet": what `info` prints for a clip whose travel was recovered.
std::string travel_description(const InPlaceChoice& choice);
// An info line for a clip whose travel was recovered (nothing otherwise).
void report_travel(const std::string& file, const InPlaceChoice& choice);
// "the first 2 frames and the last frame dropped, cut off by a capture glitch: a joint jumping
// 0.2 m or more at 20 m/s or faster between two calm frames, or out and back within a frame"
// (motion/glitched_ends.h); empty when neither.
std::string glitched_ends_description(int leading, int trailing);
// Also one info line for the files read z up, for the files whose leading rest frames were
// dropped, for those whose ends a glitch cut off, one for the clips whose travel was recovered, one
// for the clips that loop, and one for the clips whose description's walk or run was left off
// the frames where they stand (database/travel_tags.h).
// quiet: the warnings only.
// A clip cut at capture glitches within it (motion/capture_glitches.h): "05_05 (05_05.amc): 11
// glitches at 2.68-7.28 s (the largest rtoes_end 0.39 m at 3.17 s) cut into 05_05, 05_05_part2,
// 05_05_part3, 67 frames dropped".
std::string glitch_split_description(const DatabaseLoadNotes::GlitchSplit& split);

// A file's capture glitches within it (`found`: glitch_free_parts of the clip as read) as a
// library would cut the file there: "11 glitches at 2.68-7.28 s (the largest ...)
// within it (...): a library cuts it there into 3 parts ..."; empty when it has none.
std::string clip_glitches_description(const Clip& clip, const GlitchFreeParts& found);

void report_units(const DatabaseLoadNotes& notes, bool quiet);

}  // namespace mg::cli
