// The bundled subject-16 graph as a user builds it (`motiongraph build data/cmu/16`), made by
// the library (pipeline/subject16_build.h: the fixture's file, or built in process) once per
// test process, with its synthesis context (synthesis/loaded_graph.h).
#pragma once

#include "motiongraph/synthesis/loaded_graph.h"

namespace mg::test {

// Built on first use and kept for the process; fails the test (throws) when it cannot be.
const LoadedGraph& subject16();

}  // namespace mg::test
