// What the commands that write motion share: the output format by extension (.bvh in metres,
// .json world positions), checked before any work. (Graph files load with load_graph_file,
// graph/graph_file.h.)
#pragma once

#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/export/positions_json.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/motion/motion.h"

namespace mg::cli {

// Fails unless the path ends in .bvh or .json.
Status check_motion_output(const std::string& path);
// Writes the motion atomically as BVH (metres * units_per_metre) or JSON positions.
// JSON gets the feet's contacts too when `contacts` is given (export/positions_json.h).
Status write_motion(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                    double units_per_metre = 1.0, const PositionsJsonContacts* contacts = nullptr);

}  // namespace mg::cli
