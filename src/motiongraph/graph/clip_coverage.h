// What a pruned graph keeps of each clip: the frames its clip edges play, and for a clip it
// keeps nothing of, the lowest threshold at which candidate transitions could lead into it from
// the frames the graph keeps and out again (how far above the threshold the clip lies). The build warns with it
// when a graph keeps less than half of a library, and `inspect --clips` lists it.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/graph/transition.h"

namespace mg {

struct ClipCoverage {
  int clip = 0;         // index into MotionDatabase::clips
  int frames = 0;       // the clip's frames
  int kept_frames = 0;  // of those, frames the graph's clip edges play
  // Only for a clip the graph keeps nothing of, and only among the candidates given: the lowest
  // threshold at which two of them would play some of it, one leaving a kept frame for the clip
  // and a later one leaving the clip for a kept frame (the larger D of the two, minimised over
  // such pairs); < 0 when no such pair exists. A threshold below it cannot keep the clip; one
  // above may still not (pruning per tag, the spacing of transitions).
  float best_join = -1.0f;
};

// One entry per clip of `db`, in clip order. `graph` is a graph of `db` (pruned or not);
// `candidates` any transitions between its frames (a build's local minima), possibly none.
std::vector<ClipCoverage> clip_coverage(const MotionGraph& graph, const MotionDatabase& db,
                                        std::span<const Transition> candidates);

}  // namespace mg
