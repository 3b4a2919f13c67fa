// Foot slide against the threshold.
#include "motiongraph/evaluation/foot_slide_sweep.h"

#include "motiongraph/evaluation/same_frames_slide.h"
#include "motiongraph/evaluation/source_foot_slide.h"
#include "motiongraph/evaluation/threshold_sweep.h"
#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

namespace {

// One shape followed on one graph, measured played and cleaned.
Result<FootSlideSweepRow> measure(const SynthesisContext& context, const std::string& shape,
                                  const PathSynthesisSettings& settings) {
  auto path = make_shape(shape);
  if (!path) return path.error();
  auto result = synthesize_path(context, *path, settings);
  if (!result) return result.error();
  FootSlideSweepRow row;
  row.shape = shape;
  row.graph = true;
  row.frames = result->motion.frame_count;
  row.mean_deviation_m = result->mean_deviation_m;
  for (int e : result->walk.edges) row.transitions += context.graph->edges[e].transition ? 1 : 0;
  const std::vector<int> clips = walk_source_clips(*context.graph, result->walk.start_node, result->walk.edges);
  const Skeleton& skeleton = context.assembler.skeleton();
  const FootSlideSettings measure = database_foot_slide_settings(*context.db);
  auto played = compare_foot_slide(skeleton, result->motion, *context.db, clips, measure);
  if (!played) return played.error();
  auto cleanup = context.foot_cleanup(FootCleanupSettings{});
  if (!cleanup) return cleanup.error();
  Motion cleaned = result->motion;
  if (auto s = context.clean_up_walk(result->walk, *cleanup, cleaned); !s) return s.error();
  auto after = compare_foot_slide(skeleton, cleaned, *context.db, clips, measure);
  if (!after) return after.error();
  row.played_mps = played->output.mean_mps;
  row.cleaned_mps = after->output.mean_mps;
  row.source_mps = played->source.mean_mps;
  row.played_ratio = times_the_source(row.played_mps, row.source_mps);
  row.cleaned_ratio = times_the_source(row.cleaned_mps, row.source_mps);
  row.step_over_source_p999 = times_the_source(after->output.max_joint_step_m, after->source.p999_joint_step_m);
  const std::vector<FrameSource> sources = context.walk_sources(result->walk);
  auto played_same = same_frames_foot_slide(*context.db, context.assembler, result->motion, sources, measure);
  if (!played_same) return played_same.error();
  auto cleaned_same = same_frames_foot_slide(*context.db, context.assembler, cleaned, sources, measure);
  if (!cleaned_same) return cleaned_same.error();
  row.same_frames_steps = played_same->steps;
  row.same_frames_source_mps = played_same->source_mean_mps;
  row.played_same_ratio = times_the_source(played_same->mean_mps, row.same_frames_source_mps);
  // Over its own steps: the clean-up's lifted ones are not counted (the report's ratio).
  row.cleaned_same_ratio = times_the_source(cleaned_same->mean_mps, cleaned_same->source_mean_mps);
  return row;
}

}  // namespace

Result<std::vector<FootSlideSweepRow>> sweep_foot_slide(const MotionDatabase& db, const FrameFeatures& features,
                                                        const CandidateSearch& candidates,
                                                        const GraphFromCandidatesSettings& settings,
                                                        std::span<const double> quantiles,
                                                        std::span<const std::string> shapes,
                                                        const PathSynthesisSettings& path_settings,
                                                        OnDemandCandidates* more) {
  for (const std::string& shape : shapes) {
    if (auto path = make_shape(shape); !path) return path.error();
  }
  std::vector<FootSlideSweepRow> rows;
  auto visit = [&](double quantile, const TransitionsWithBridges& selected, const Result<PrunedGraph>& pruned) -> Status {
    const double threshold = selected.selection.threshold;
    if (!pruned) {
      for (const std::string& shape : shapes) {
        FootSlideSweepRow row;
        row.quantile = quantile;
        row.threshold = threshold;
        row.shape = shape;
        rows.push_back(row);
      }
      return Ok{};
    }
    auto context = make_synthesis_context(db, pruned->graph);
    if (!context) return context.error();
    for (const std::string& shape : shapes) {
      auto row = measure(*context, shape, path_settings);
      if (!row) return row.error();
      row->quantile = quantile;
      row->threshold = threshold;
      rows.push_back(std::move(*row));
    }
    return Ok{};
  };
  if (auto s = for_each_threshold(db, features, candidates, settings, quantiles, visit, more); !s) return s.error();
  return rows;
}

}  // namespace mg
