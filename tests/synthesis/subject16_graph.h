// The bundled subject-16 graph as a user builds it (`motiongraph build data/cmu/16`), made
// once by the CTest fixture "subject16_graph" and found through MOTIONGRAPH_TEST_GRAPH.
#pragma once

#include "motiongraph/graph/graph_file.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg::test {

struct Subject16 {
  GraphFile file;
  SynthesisContext context;
};

// Loaded on first use and kept for the process; fails the test (throws) when missing.
const Subject16& subject16();

}  // namespace mg::test
