#include "cli/synthesis_options.h"

#include <fmt/format.h>

#include <cmath>

#include "motiongraph/core/json_text.h"
#include "motiongraph/evaluation/source_foot_slide.h"
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

namespace {

nlohmann::json foot_slide_json(const FootSlide& slide) {
  return {{"mean_mps", slide.mean_mps},
          {"p95_mps", slide.p95_mps},
          {"max_joint_step_m", slide.max_joint_step_m},
          {"contact_steps", slide.contact_steps}};
}

nlohmann::json ratio_json(double output, double source) {
  const double ratio = times_the_source(output, source);
  return std::isnan(ratio) ? nlohmann::json(nullptr) : nlohmann::json(ratio);
}

nlohmann::json foot_slide_report(const LoadedGraph& loaded, const Walk& walk, const Motion& motion) {
  const SynthesisContext& context = loaded.context;
  const std::vector<int> clips = walk_source_clips(*context.graph, walk.start_node, walk.edges);
  auto comparison = compare_foot_slide(context.assembler.skeleton(), motion, *context.db, clips);
  if (!comparison) return {{"error", comparison.error().message}};
  const FootSlide& output = comparison->output;
  const FootSlide& source = comparison->source;
  nlohmann::json report = foot_slide_json(output);
  report["source"] = foot_slide_json(source);
  nlohmann::json names = nlohmann::json::array();
  for (int c : clips) names.push_back(context.db->clips[c].name);
  report["source"]["clips"] = names;
  report["ratio"] = {{"mean_mps", ratio_json(output.mean_mps, source.mean_mps)},
                     {"p95_mps", ratio_json(output.p95_mps, source.p95_mps)},
                     {"max_joint_step_m", ratio_json(output.max_joint_step_m, source.max_joint_step_m)}};
  return report;
}

}  // namespace

Status write_synthesis_outputs(const SynthesisOptions& options, const LoadedGraph& loaded, const Motion& motion,
                               const Walk& walk, nlohmann::json report) {
  if (auto s = write_motion(options.output, loaded.context.assembler.skeleton(), motion); !s) return s;
  if (!options.report.empty()) {
    report["foot_slide"] = foot_slide_report(loaded, walk, motion);
    if (auto s = write_file_atomic(options.report, json_text(report, 2) + "\n"); !s) return s;
  }
  return Ok{};
}

}  // namespace mg::cli
