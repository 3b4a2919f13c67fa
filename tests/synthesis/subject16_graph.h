// The bundled subject-16 graph as a user builds it (`motiongraph build data/cmu/16`), built in
// process once per test process (pipeline/subject16_build.h) and loaded with its synthesis
// context (synthesis/loaded_graph.h).
#pragma once

#include "motiongraph/synthesis/loaded_graph.h"

namespace mg::test {

// Built on first use and kept for the process; fails the test (throws) when it cannot be.
const LoadedGraph& subject16();

}  // namespace mg::test
