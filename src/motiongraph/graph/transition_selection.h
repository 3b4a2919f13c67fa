// From candidates to transitions (Kovar et al. 2002, section 3.2): keep the local minima
// below a threshold, given in absolute units of D or as a quantile of all finite D; within a
// locality radius keep only the best (lowest D) candidate; compute each kept transition's
// floor alignment. Cheap: runs on the cached candidates, not on the distance matrix.
#pragma once

#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/metric/frame_features.h"

namespace mg {

struct TransitionSettings {
  double threshold = -1.0;         // absolute D; < 0: use the quantile
  double threshold_quantile = 0.02;  // fraction of all finite D below the threshold
  int locality_radius = -1;        // frames (both a and b); -1 = half the window

  Status validate() const;
};

struct TransitionSelection {
  double threshold = 0.0;          // the absolute threshold used
  double threshold_quantile = 0.0; // the fraction of finite D below it
  int locality_radius = 0;
  int candidates_below_threshold = 0;
  std::vector<Transition> transitions;  // with alignment, sorted by (from_frame, to_frame)
};

Result<TransitionSelection> select_transitions(const FrameFeatures& features, const CandidateSearch& candidates,
                                               const TransitionSettings& settings);

}  // namespace mg
