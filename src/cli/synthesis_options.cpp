#include "cli/synthesis_options.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "motiongraph/core/json_text.h"
#include "motiongraph/evaluation/foot_slide_report.h"
#include "motiongraph/io/file.h"

namespace mg::cli {

Status check_output_options(const SynthesisOptions& options) {
  if (auto s = check_motion_output(options.output); !s) return s;
  return options.motion_output.settings().validate();
}

Result<std::unique_ptr<LoadedGraph>> load_for_synthesis(const SynthesisOptions& options,
                                                        const std::vector<std::string>& inputs) {
  if (auto s = check_output_options(options); !s) return s.error();
  std::vector<std::string> read = inputs;
  read.push_back(options.graph);
  if (auto s = check_outputs({options.output, options.report}, read); !s) return s.error();
  // Synthesis reads no candidate minima: the file opens faster without them.
  return LoadedGraph::load(options.graph, options.skeleton, GraphReadOptions{.candidate_minima = false});
}

SynthesisRunSettings run_settings(const SynthesisOptions& options, std::chrono::steady_clock::time_point begin) {
  SynthesisRunSettings settings;
  settings.cleanup = !options.no_cleanup;
  settings.graph_name = options.graph;
  settings.begin = begin;
  return settings;
}

void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& line : warnings) spdlog::warn("{}", line);
}

Status write_synthesis_outputs(const SynthesisOptions& options, const LoadedGraph& loaded, const Motion& motion,
                               const Walk& walk, nlohmann::json report, std::vector<ContactMask> contacts) {
  const SynthesisContext& context = loaded.context();
  if (auto s = write_synthesized_motion(options.output, context, motion, walk, std::move(contacts),
                                       options.motion_output.settings());
      !s) {
    return s;
  }
  if (!options.report.empty()) {
    if (!report.contains("foot_slide")) report["foot_slide"] = foot_slide_report(context, walk, motion);
    if (auto s = write_file_atomic(options.report, json_text(report, 2) + "\n"); !s) return s;
  }
  return Ok{};
}

}  // namespace mg::cli
