// The bundled subject-16 graph as `motiongraph build data/cmu/16` makes it (the default
// settings), built in process by build_graph() (pipeline/build_graph.h): what the synthesis and
// studio tests play, and what the CTest fixture "subject16_graph" writes for the tests that run
// the CLI, Blender or a browser on a graph file.
#pragma once

#include <string>

#include "motiongraph/graph/graph_file.h"

namespace mg::test {

// The graph of the clips in `folder` (data/cmu/16) with BuildSettings{}, no cache; throws
// std::runtime_error when it cannot be built.
GraphFile build_subject16_graph(const std::string& folder);

}  // namespace mg::test
