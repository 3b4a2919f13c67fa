// The bundled subject-16 graph as `motiongraph build data/cmu/16` makes it (the default
// settings), made by build_graph() (pipeline/build_graph.h), never by the CLI: what the
// synthesis and studio tests play, and what the CTest fixture "subject16_graph" writes
// (make_subject16_graph) for the tests that run the CLI, Blender or a browser on a graph file.
#pragma once

#include <string>

#include "motiongraph/graph/graph_file.h"
#include "motiongraph/pipeline/build_settings.h"

namespace mg::test {

// The graph of the clips in `folder` (data/cmu/16) with `settings` (by default
// BuildSettings{}), no cache; throws std::runtime_error when it cannot be built.
GraphFile build_subject16_graph(const std::string& folder, const BuildSettings& settings = {});

// The graph the fixture wrote (MOTIONGRAPH_TEST_GRAPH, set by ctest) when there is one, else
// build_subject16_graph() in process. The fixture's file spares each test process the build
// (about 0.3 s, but half a minute under the sanitizers); throws when neither works.
GraphFile subject16_graph_file();

}  // namespace mg::test
