// Graph size against the transition threshold (the seed's figure 2.12): for each threshold,
// the transitions are selected again on the stored candidates, bridged, and the graph built
// and pruned (graph_from_candidates.h); each row has the graph's nodes and the nodes of its
// largest strongly connected component before pruning, and what pruning keeps. Thresholds
// are given as quantiles of all finite D (the fraction of pairs below), as build's
// --threshold-quantile. A threshold whose transitions form no cycle gives a row with nothing
// kept rather than an error.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/graph_from_candidates.h"

namespace mg {

struct ThresholdSweepRow {
  double quantile = 0.0;           // as asked
  double threshold = 0.0;          // absolute D
  int transitions = 0;             // selected below the threshold (per-tag thresholds included)
  int bridges = 0;
  int nodes = 0;                   // before pruning
  int largest_component_nodes = 0; // before pruning (0: no cycle)
  int kept_nodes = 0;              // after pruning (0: nothing would remain)
  int kept_transitions = 0;
  long long kept_clip_frames = 0;  // database frames the pruned graph plays
};

// Log-spaced quantiles from `lowest` to `highest` (count >= 2, 0 < lowest < highest <= 1).
std::vector<double> log_spaced(double lowest, double highest, int count);

// For each quantile in turn: the transitions selected at it (with bridges) and the pruned
// graph, or the ErrorKind::kEmptyGraph error pruning gave (nothing would remain). `settings`
// as the graph was built; its threshold is replaced. Stops at the first error selection,
// building or pruning (other than nothing remaining) or `visit` returns. `more`: as
// select_transitions_with_bridges takes it (a graph built by the pruned stage); such a graph's
// candidates know the thresholds up to its ceiling only (quantiles_below_ceiling). Per-type
// thresholds the automatic choice gave are not kept: each quantile is one threshold, with
// per-tag thresholds by rank (transition_selection.h) on the exhaustive stage's candidates and
// without them on the pruned stage's (by rank they count candidates above its ceiling).
Status for_each_threshold(
    const MotionDatabase& db, const FrameFeatures& features, const CandidateSearch& candidates,
    const GraphFromCandidatesSettings& settings, std::span<const double> quantiles,
    const std::function<Status(double quantile, const TransitionsWithBridges&, const Result<PrunedGraph>&)>& visit,
    OnDemandCandidates* more = nullptr);

// The quantiles whose threshold lies at or below the candidates' ceiling (all of them for the
// exhaustive stage's).
std::vector<double> quantiles_below_ceiling(const CandidateSearch& candidates, std::span<const double> quantiles);

// One row per quantile.
Result<std::vector<ThresholdSweepRow>> sweep_thresholds(const MotionDatabase& db, const FrameFeatures& features,
                                                        const CandidateSearch& candidates,
                                                        const GraphFromCandidatesSettings& settings,
                                                        std::span<const double> quantiles,
                                                        OnDemandCandidates* more = nullptr);

}  // namespace mg
