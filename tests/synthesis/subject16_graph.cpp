#include "synthesis/subject16_graph.h"

#include <cstdlib>
#include <memory>
#include <stdexcept>

namespace mg::test {

const LoadedGraph& subject16() {
  static const std::unique_ptr<LoadedGraph> loaded = [] {
    const char* path = std::getenv("MOTIONGRAPH_TEST_GRAPH");
    if (path == nullptr) {
      throw std::runtime_error(
          "MOTIONGRAPH_TEST_GRAPH is not set: run the tests through ctest, whose fixture "
          "builds the subject-16 graph");
    }
    auto graph = LoadedGraph::load(path);
    if (!graph) throw std::runtime_error(graph.error().to_string());
    return std::move(*graph);
  }();
  return *loaded;
}

}  // namespace mg::test
