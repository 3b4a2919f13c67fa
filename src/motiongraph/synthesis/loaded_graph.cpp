// A graph file and its synthesis context, made together.
#include "motiongraph/synthesis/loaded_graph.h"

#include <fmt/format.h>

namespace mg {

Result<std::unique_ptr<LoadedGraph>> LoadedGraph::create(GraphFile file, const std::string& file_name,
                                                         int target_skeleton) {
  const int skeletons = static_cast<int>(file.database.skeletons.size());
  if (target_skeleton >= skeletons) {
    return Error{file_name, 0, fmt::format("skeleton {}: the graph has {} skeleton(s)", target_skeleton, skeletons)};
  }
  std::unique_ptr<LoadedGraph> loaded(new LoadedGraph(std::move(file)));
  auto context = make_synthesis_context(loaded->file_.database, loaded->file_.graph, target_skeleton);
  if (!context) return Error{file_name, 0, context.error().message};
  loaded->context_ = std::move(*context);
  return loaded;
}

Result<std::unique_ptr<LoadedGraph>> LoadedGraph::load(const std::string& path, int target_skeleton,
                                                       const GraphReadOptions& options) {
  auto file = load_graph_file(path, options);
  if (!file) return file.error();
  return create(std::move(*file), path, target_skeleton);
}

}  // namespace mg
