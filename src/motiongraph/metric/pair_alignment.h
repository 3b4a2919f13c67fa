// The floor alignment of one pair of windows from the per-frame features (DESIGN.md 3.2):
// theta = atan2(B, A), translation from the weighted sums. O(k P); used for the transitions
// that are kept, so the full clouds never need to be held in double.
#pragma once

#include "motiongraph/metric/frame_features.h"
#include "motiongraph/metric/reference_distance.h"

namespace mg {

// Alignment mapping the arrival window (ending at b) onto the departure window (from a).
FloorAlignment align_pair(const FrameFeatures& features, int a, int b);

}  // namespace mg
