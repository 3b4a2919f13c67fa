// Self-consistency of transitions against the threshold (the seed's figure 3.2): for each
// threshold (a quantile of all finite D), the pruned graph is built again from the stored
// candidates (graph_from_candidates.h) and the measure of self_consistency.h taken around its
// transitions, played on the skeleton of the database's first clip.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/evaluation/self_consistency.h"
#include "motiongraph/graph/graph_from_candidates.h"

namespace mg {

struct ConsistencyRow {
  double quantile = 0.0;
  double threshold = 0.0;     // absolute D
  int transitions = 0;        // transition edges of the pruned graph (0: nothing remained)
  ConsistencySum transition;  // around them
};

Result<std::vector<ConsistencyRow>> sweep_consistency(const MotionDatabase& db, const FrameFeatures& features,
                                                      const CandidateSearch& candidates,
                                                      const GraphFromCandidatesSettings& settings,
                                                      std::span<const double> quantiles,
                                                      OnDemandCandidates* more = nullptr);

}  // namespace mg
