#include "synthesis/subject16_graph.h"

#include <memory>
#include <stdexcept>

#include "pipeline/subject16_build.h"
#include "test_data.h"

namespace mg::test {

const LoadedGraph& subject16() {
  static const std::unique_ptr<LoadedGraph> loaded = [] {
    auto graph = LoadedGraph::create(build_subject16_graph(data_path("cmu/16")), "subject16.mgraph");
    if (!graph) throw std::runtime_error(graph.error().to_string());
    return std::move(*graph);
  }();
  return *loaded;
}

}  // namespace mg::test
