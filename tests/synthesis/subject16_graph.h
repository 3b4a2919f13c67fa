// The bundled subject-16 graph as a user builds it (`motiongraph build data/cmu/16`), made
// once by the CTest fixture "subject16_graph" and found through MOTIONGRAPH_TEST_GRAPH, loaded
// with its synthesis context (synthesis/loaded_graph.h).
#pragma once

#include "motiongraph/synthesis/loaded_graph.h"

namespace mg::test {

// Loaded on first use and kept for the process; fails the test (throws) when missing.
const LoadedGraph& subject16();

}  // namespace mg::test
