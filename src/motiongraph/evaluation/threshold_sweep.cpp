// Graph size against the transition threshold.
#include "motiongraph/evaluation/threshold_sweep.h"

#include <cmath>

namespace mg {

std::vector<double> log_spaced(double lowest, double highest, int count) {
  std::vector<double> values;
  for (int i = 0; i < count; ++i) {
    values.push_back(lowest * std::pow(highest / lowest, static_cast<double>(i) / (count - 1)));
  }
  return values;
}

std::vector<double> quantiles_below_ceiling(const CandidateSearch& candidates, std::span<const double> quantiles) {
  std::vector<double> kept;
  for (const double q : quantiles) {
    if (candidates.ceiling < 0.0 || candidates.histogram.quantile(q) <= candidates.ceiling) kept.push_back(q);
  }
  return kept;
}

Status for_each_threshold(
    const MotionDatabase& db, const FrameFeatures& features, const CandidateSearch& candidates,
    const GraphFromCandidatesSettings& settings, std::span<const double> quantiles,
    const std::function<Status(double quantile, const TransitionsWithBridges&, const Result<PrunedGraph>&)>& visit,
    OnDemandCandidates* more) {
  for (const double quantile : quantiles) {
    GraphFromCandidatesSettings at = settings;
    at.transitions.threshold = -1.0;
    at.transitions.threshold_quantile = quantile;
    // The automatic choice's per-type thresholds belong to its point: the sweep varies one
    // threshold, with per-tag thresholds by rank where the candidates allow them.
    at.transitions.tag_thresholds.clear();
    if (candidates.ceiling >= 0.0) at.transitions.per_tag_thresholds = false;
    auto selected = select_transitions_with_bridges(db, features, candidates, at, more);
    if (!selected) return selected.error();
    const Result<PrunedGraph> pruned = build_spaced_graph(db, *selected, features, at);
    // Nothing left after pruning is a measurement (the visitor's row keeps nothing); any other
    // failure is an error.
    if (!pruned && pruned.error().kind != ErrorKind::kEmptyGraph) return pruned.error();
    if (auto s = visit(quantile, *selected, pruned); !s) return s;
  }
  return Ok{};
}

Result<std::vector<ThresholdSweepRow>> sweep_thresholds(const MotionDatabase& db, const FrameFeatures& features,
                                                        const CandidateSearch& candidates,
                                                        const GraphFromCandidatesSettings& settings,
                                                        std::span<const double> quantiles,
                                                        OnDemandCandidates* more) {
  std::vector<ThresholdSweepRow> rows;
  auto visit = [&](double quantile, const TransitionsWithBridges& selected, const Result<PrunedGraph>& pruned) -> Status {
    ThresholdSweepRow row;
    row.quantile = quantile;
    row.threshold = selected.selection.threshold;
    row.transitions = static_cast<int>(selected.selection.transitions.size());
    row.bridges = static_cast<int>(selected.bridges.size());
    // Pruning fails when nothing would remain: the row then keeps nothing.
    GraphStatistics before;
    if (pruned) {
      before = pruned->prune.before;
      row.kept_nodes = pruned->prune.after.nodes;
      row.kept_transitions = pruned->prune.after.transitions;
      row.kept_clip_frames = pruned->prune.after.clip_frames;
    } else {
      auto graph = build_motion_graph(db, selected.all_transitions, features.window);
      if (!graph) return graph.error();
      before = compute_graph_statistics(*graph, db.frame_tags());
    }
    row.nodes = before.nodes;
    row.largest_component_nodes = before.largest_component_nodes;
    rows.push_back(row);
    return Ok{};
  };
  if (auto s = for_each_threshold(db, features, candidates, settings, quantiles, visit, more); !s) return s.error();
  return rows;
}

}  // namespace mg
