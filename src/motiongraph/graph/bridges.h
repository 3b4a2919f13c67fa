// Bridges between motion types. Transitions below the threshold connect frames of one kind
// of motion with each other; between kinds (walking and running of one subject, say) every
// candidate may lie above it, and the pruned graph then keeps one kind only. A bridge is the
// best candidate (lowest D, a local minimum like any other) from frames that all carry tag s
// to frames that all carry tag t, added for each ordered pair of tags (s, t) that no selected
// transition joins. Bridges are reported apart, with their D, so the user sees what quality
// the connection costs; pruning treats them like any transition.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/graph/transition.h"

namespace mg {

struct BridgeSettings {
  int per_tag_pair = 3;          // bridges per ordered pair of tags (0: none)
  TagMask tags = ~TagMask{0};    // the tags to bridge between
  int locality_radius = 5;       // bridges of one pair lie at least this far apart (frames)

  Status validate() const;
};

// The frames of a tag's core: the clip frames of the largest strongly connected region that
// the tag's own transitions (both windows carrying the tag) make (prune_motion_graph on them).
// Empty when the tag has no cycle (pruning leaves nothing); fails on any other error of
// building or pruning that graph (transitions outside the database, tags that do not cover it).
Result<std::vector<char>> tag_core_frames(const MotionDatabase& db, std::span<const Transition> selected,
                                          std::span<const TagMask> frame_tags, int window, int tag);

// The bridges to add to `selected` (sorted by (from_frame, to_frame)); window k. A bridge
// from s to u leaves from a frame of s's core and lands on a frame of u's core (cores[t] from
// tag_core_frames; a tag without a core gets no bridges).
std::vector<Transition> select_bridges(std::span<const Transition> candidates, std::span<const Transition> selected,
                                       std::span<const TagMask> frame_tags, std::span<const std::vector<char>> cores,
                                       int window, const BridgeSettings& settings);

}  // namespace mg
