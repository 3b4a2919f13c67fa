#include "pipeline/subject16_build.h"

#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "motiongraph/pipeline/build_graph.h"

namespace mg::test {

GraphFile build_subject16_graph(const std::string& folder, const BuildSettings& settings) {
  const std::vector<std::string> inputs = {folder};
  auto built = build_graph(inputs, settings);
  if (!built) throw std::runtime_error(built.error().to_string());
  if (!built->graph_status) throw std::runtime_error(built->graph_status.error().to_string());
  return std::move(built->file);
}

GraphFile subject16_graph_file() {
  if (const char* path = std::getenv("MOTIONGRAPH_TEST_GRAPH"); path != nullptr && *path != '\0') {
    auto file = load_graph_file(path);
    if (!file) throw std::runtime_error(file.error().to_string());
    return std::move(*file);
  }
  return build_subject16_graph(std::string(MOTIONGRAPH_DATA_DIR) + "/cmu/16");
}

}  // namespace mg::test
