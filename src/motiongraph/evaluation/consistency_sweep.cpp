// Self-consistency of transitions against the threshold.
#include "motiongraph/evaluation/consistency_sweep.h"

#include "motiongraph/evaluation/threshold_sweep.h"

namespace mg {

Result<std::vector<ConsistencyRow>> sweep_consistency(const MotionDatabase& db, const FrameFeatures& features,
                                                      const CandidateSearch& candidates,
                                                      const GraphFromCandidatesSettings& settings,
                                                      std::span<const double> quantiles, OnDemandCandidates* more) {
  if (db.clips.empty()) return Error{"", 0, "the database has no clip"};
  const int target = db.clips.front().skeleton;
  const Vec3 forward_axis = learn_travel_axes(db)[target];
  std::vector<ConsistencyRow> rows;
  auto visit = [&](double quantile, const TransitionsWithBridges& selected, const Result<PrunedGraph>& pruned) -> Status {
    ConsistencyRow row;
    row.quantile = quantile;
    row.threshold = selected.selection.threshold;
    // Nothing remains after pruning: a row with no transitions.
    if (pruned) {
      auto assembler = MotionAssembler::create(db, pruned->graph, target);
      if (!assembler) return assembler.error();
      row.transitions = static_cast<int>(pruned->graph.transitions.size());
      row.transition = transition_consistency(db, pruned->graph, *assembler, forward_axis);
    }
    rows.push_back(row);
    return Ok{};
  };
  if (auto s = for_each_threshold(db, features, candidates, settings, quantiles, visit, more); !s) return s.error();
  return rows;
}

}  // namespace mg
