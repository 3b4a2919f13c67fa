#include "cli/synthesis_options.h"

#include <fmt/format.h>

#include "motiongraph/core/json_text.h"
#include "motiongraph/io/file.h"

namespace mg::cli {

Result<std::unique_ptr<LoadedGraph>> load_for_synthesis(const SynthesisOptions& options) {
  if (auto s = check_motion_output(options.output); !s) return s.error();
  auto file = load_graph_file(options.graph);
  if (!file) return file.error();
  auto loaded = std::make_unique<LoadedGraph>();
  loaded->file = std::move(*file);
  if (options.skeleton >= static_cast<int>(loaded->file.database.skeletons.size())) {
    return Error{options.graph, 0, fmt::format("--skeleton {}: the graph has {} skeleton(s)", options.skeleton,
                                               loaded->file.database.skeletons.size())};
  }
  auto context = make_synthesis_context(loaded->file.database, loaded->file.graph, options.skeleton);
  if (!context) return Error{options.graph, 0, context.error().message};
  loaded->context = std::move(*context);
  return loaded;
}

Status write_synthesis_outputs(const SynthesisOptions& options, const LoadedGraph& loaded, const Motion& motion,
                               const nlohmann::json& report) {
  if (auto s = write_motion(options.output, loaded.context.assembler.skeleton(), motion); !s) return s;
  if (!options.report.empty()) {
    if (auto s = write_file_atomic(options.report, json_text(report, 2) + "\n"); !s) return s;
  }
  return Ok{};
}

}  // namespace mg::cli
