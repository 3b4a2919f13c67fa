// Foot slide against the transition threshold (DESIGN.md section 5b; issue "feet that stay
// planted"): for each threshold, the graph is selected and pruned again on the stored
// candidates (threshold_sweep.h), each built-in shape is followed (path_synthesis.h), and the
// motion is measured as played and after the foot clean-up against the clips it was cut from
// (source_foot_slide.h): the mean toe speed in contact and the largest per-frame joint step,
// each as "x times the capture", and the toe speed on the frames played beside the same frames'
// in the capture (same_frames_slide.h). A threshold whose transitions form no graph gives rows with
// `graph` false; a rig whose feet are not found is an error (nothing to measure).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/synthesis/path_synthesis.h"

namespace mg {

struct FootSlideSweepRow {
  double quantile = 0.0;
  double threshold = 0.0;
  std::string shape;
  bool graph = false;                 // false: pruning left nothing; the rest is zero
  int frames = 0;
  int transitions = 0;                // taken by the walk
  double mean_deviation_m = 0.0;
  double played_mps = 0.0;            // mean toe speed in contact, as played
  double cleaned_mps = 0.0;           // the same after the clean-up
  double source_mps = 0.0;            // the same over the source clips
  double played_ratio = 0.0;          // played / source (NaN when the source's is 0)
  double cleaned_ratio = 0.0;
  double step_over_source_p999 = 0.0; // cleaned largest joint step / the source's 99.9th percentile
  // On the frames played (same_frames_slide.h): the capture's toe speed on those steps, and the
  // result's as played and cleaned over it (NaN when it is 0).
  long long same_frames_steps = 0;
  double same_frames_source_mps = 0.0;
  double played_same_ratio = 0.0;
  double cleaned_same_ratio = 0.0;
};

Result<std::vector<FootSlideSweepRow>> sweep_foot_slide(const MotionDatabase& db, const FrameFeatures& features,
                                                        const CandidateSearch& candidates,
                                                        const GraphFromCandidatesSettings& settings,
                                                        std::span<const double> quantiles,
                                                        std::span<const std::string> shapes,
                                                        const PathSynthesisSettings& path_settings = {},
                                                        OnDemandCandidates* more = nullptr);

}  // namespace mg
