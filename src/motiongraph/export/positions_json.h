// World positions as JSON for other tools and the studio:
//   {"fps": F, "joints": [{"name": ..., "parent": index}, ...],
//    "positions": [frame][joint][x, y, z]}   (metres, rounded to the micrometre)
#pragma once

#include <string>

#include "motiongraph/motion/motion.h"

namespace mg {

std::string write_positions_json(const Skeleton& skeleton, const Motion& motion);

}  // namespace mg
