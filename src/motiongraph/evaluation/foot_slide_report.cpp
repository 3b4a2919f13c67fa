#include "motiongraph/evaluation/foot_slide_report.h"

#include <cmath>

#include "motiongraph/evaluation/same_frames_slide.h"
#include "motiongraph/evaluation/source_foot_slide.h"

namespace mg {

namespace {

nlohmann::json foot_slide_json(const FootSlide& slide) {
  return {{"mean_mps", slide.mean_mps},
          {"p95_mps", slide.p95_mps},
          {"max_joint_step_m", slide.max_joint_step_m},
          {"p999_joint_step_m", slide.p999_joint_step_m},
          {"contact_steps", slide.contact_steps}};
}

nlohmann::json ratio_json(double output, double source) {
  const double ratio = times_the_source(output, source);
  return std::isnan(ratio) ? nlohmann::json(nullptr) : nlohmann::json(ratio);
}

}  // namespace

nlohmann::json foot_slide_report(const SynthesisContext& context, const Walk& walk, const Motion& motion) {
  return foot_slide_report(context, walk, motion, context.walk_sources(walk));
}

nlohmann::json foot_slide_report(const SynthesisContext& context, const Walk& walk, const Motion& motion,
                                 std::span<const FrameSource> sources) {
  const std::vector<int> clips = walk_source_clips(*context.graph, walk.start_node, walk.edges);
  const FootSlideSettings settings = database_foot_slide_settings(*context.db);
  auto comparison = compare_foot_slide(context.assembler.skeleton(), motion, *context.db, clips, settings);
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
                     {"max_joint_step_m", ratio_json(output.max_joint_step_m, source.max_joint_step_m)},
                     {"max_joint_step_over_source_p999", ratio_json(output.max_joint_step_m, source.p999_joint_step_m)}};
  auto same = same_frames_foot_slide(*context.db, context.assembler, motion, sources, settings);
  if (!same) {
    report["same_frames"] = {{"error", same.error().message}};
  } else {
    report["same_frames"] = {{"steps", same->steps},
                             {"lifted_steps", same->lifted_steps},
                             {"mean_mps", same->mean_mps},
                             {"source_mean_mps", same->source_mean_mps},
                             {"ratio", ratio_json(same->mean_mps, same->source_mean_mps)}};
  }
  return report;
}

}  // namespace mg
