#include "synthesis/subject16_graph.h"

#include <memory>
#include <stdexcept>

#include "pipeline/subject16_build.h"

namespace mg::test {

const LoadedGraph& subject16() {
  static const std::unique_ptr<LoadedGraph> loaded = [] {
    auto graph = LoadedGraph::create(subject16_graph_file(), "subject16.mgraph");
    if (!graph) throw std::runtime_error(graph.error().to_string());
    return std::move(*graph);
  }();
  return *loaded;
}

}  // namespace mg::test
