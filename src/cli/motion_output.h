// What the commands that write motion or read graphs share: the output format by extension
// (.bvh in metres, .json world positions), checked before any work, and loading a graph file.
#pragma once

#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/motion/motion.h"

namespace mg::cli {

// Fails unless the path ends in .bvh or .json.
Status check_motion_output(const std::string& path);
// Writes the motion atomically as BVH (metres * units_per_metre) or JSON positions.
Status write_motion(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                    double units_per_metre = 1.0);
Result<GraphFile> load_graph_file(const std::string& path);

}  // namespace mg::cli
