#include "pipeline/subject16_build.h"

#include <stdexcept>
#include <vector>

#include "motiongraph/pipeline/build_graph.h"

namespace mg::test {

GraphFile build_subject16_graph(const std::string& folder) {
  const std::vector<std::string> inputs = {folder};
  auto built = build_graph(inputs, BuildSettings{});
  if (!built) throw std::runtime_error(built.error().to_string());
  if (!built->graph_status) throw std::runtime_error(built->graph_status.error().to_string());
  return std::move(built->file);
}

}  // namespace mg::test
