// Spacing transitions so that walks play original motion between blends (Kovar et al. 2002
// keep one transition per region of the distance matrix; on a dense library that still leaves
// several transitions per frame, and output that is blend upon blend).
//
// A transition a -> b leaves the clip at frame a and lands at frame b (motion_graph.h). Taken
// best first (lowest D), a transition is kept when
//  - with max_out > 0: fewer than max_out kept transitions leave any out_window consecutive
//    frames around a (a search meets at most max_out branches per out_window frames);
//  - with min_piece > 0: no kept transition lands in (a - min_piece, a] of a's clip, and none
//    leaves from [b, b + min_piece) of b's clip, so between two blends a walk plays at least
//    min_piece frames of captured motion.
// Both are off by default. Measured on subject 16 (docs/performance.md) either one leaves too
// few transitions for paths and steering to be followed (a 90 degree turn not reached at all
// with 4 per window), while the search's cost per transition (path_synthesis.h, controller.h)
// brings blends down to about one a second with no such loss. They are there for libraries
// whose graphs are too dense to search.
// The best transition of a stretch always survives: a later one only goes when a better one
// is there. Cheap: runs on the transitions that survive a first pruning.
#pragma once

#include <span>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/transition.h"

namespace mg {

struct TransitionSpacing {
  int out_window_frames = -1;  // the stretch max_out counts over; -1: the window k
  int max_out = 0;             // transitions leaving any out_window frames; 0: no limit (default)
  int min_piece_frames = 0;    // captured frames between an arrival and the next departure; 0: off

  Status validate() const;
  int out_window_for(int window) const { return out_window_frames < 0 ? window : out_window_frames; }
  // The same spacing with out_window_frames resolved for the window (as recorded).
  TransitionSpacing resolved(int window) const {
    TransitionSpacing out = *this;
    out.out_window_frames = out_window_for(window);
    return out;
  }
};

// Its JSON form, the one the graph file (pipeline/saved_settings.h) and the build report write:
// {"out_window_frames", "min_piece_frames", "max_out"}; a key missing on reading keeps its
// default (graph files written before transitions were spaced record none).
void to_json(nlohmann::json& json, const TransitionSpacing& spacing);
void from_json(const nlohmann::json& json, TransitionSpacing& spacing);

// The kept transitions, sorted by (from_frame, to_frame). clip_of_frame maps every global
// frame to its clip (frames of different clips never constrain each other); window is k.
std::vector<Transition> space_transitions(std::span<const Transition> transitions, std::span<const int> clip_of_frame,
                                          int window, const TransitionSpacing& spacing);

}  // namespace mg
