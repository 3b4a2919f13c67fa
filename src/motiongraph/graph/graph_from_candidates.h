// From cached candidates to the pruned motion graph (Kovar et al. 2002, sections 3.2-3.3;
// DESIGN.md 4): select the transitions below the threshold (transition_selection.h), add
// bridges between motion types that no selected transition joins (bridges.h, aligned like any
// transition), build the graph and prune it per tag. This is what `build` does after the
// distance stage, and what the threshold evaluation repeats at many thresholds on the
// candidates stored in a graph file. Cheap: no distance matrix is involved.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/bridges.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/graph/on_demand_candidates.h"
#include "motiongraph/graph/transition_selection.h"
#include "motiongraph/graph/transition_spacing.h"
#include "motiongraph/metric/frame_features.h"

namespace mg {

// Tags that describe how a motion goes rather than what it is (turn, stop, start, backward,
// veer): they need neither a connected region of their own nor bridges.
bool is_modifier_tag(const std::string& name);

// The motion types of a database: every tag that is not a modifier.
TagMask motion_type_tags(const MotionDatabase& db);

// The clips none of whose frames carries a motion type kept connected (window_membership.h's
// untagged_class_frames), as one more class of motion for the automatic threshold
// (threshold_choice.h) and the thresholds it gives (transition_selection.h): clips the CMU index
// does not list, or the untagged clips of a user's library. Frames of no type in a typed clip
// belong to no class.
inline constexpr int kUntaggedClass = -1;

// A tag's name, or "untagged" for kUntaggedClass.
std::string motion_class_name(const MotionDatabase& db, int tag);

// The mask of the named tags, or an error naming the first tag no clip carries.
Result<TagMask> tag_mask_of(const MotionDatabase& db, std::span<const std::string> names);

struct GraphFromCandidatesSettings {
  TransitionSettings transitions;
  TransitionSpacing spacing;      // applied to the transitions that survive a first pruning
  BridgeSettings bridges;         // tags and locality_radius are set from the selection
  TagMask connected_tags = 0;     // motion types kept connected, with bridges; 0: ignore tags
  // false: transitions and bridges without their floor alignments (0), for graphs built only
  // for their shape (the automatic threshold's search); not recorded in graph files.
  bool aligned = true;

  Status validate() const;
};

struct TransitionsWithBridges {
  TransitionSelection selection;
  std::vector<Transition> bridges;          // aligned, sorted by (from_frame, to_frame)
  // Each bridge's blend length in frames as its D asks (bridge_blend_frames); the graph places
  // it (place_bridge_blends), within what its clips and the pruned graph leave room for.
  std::vector<int> bridge_blends;
  std::vector<UnjoinedPair> unjoined;       // pairs of motion types neither joins
  std::vector<Transition> all_transitions;  // selected and bridges, by (from_frame, to_frame)

  // Which of `transitions` are bridges (1) and which selected (0).
  std::vector<char> bridge_flags(std::span<const Transition> transitions) const;
};

// Whether the settings make bridges (motion types kept connected, bridges per pair > 0). The
// untagged class (window_membership.h) is bridged as one more type (bridges.h
// untagged_bridge_tag); its pairs are not listed in `unjoined`.
bool connected_bridges(const GraphFromCandidatesSettings& settings);

// The first two steps: selection and bridges. The pruned stage's candidates (ceiling >= 0)
// need `more`, made for them, when the settings make bridges (the bridges are then those of
// all the minima: on_demand_candidates.h); `more` is not used with the exhaustive stage's.
Result<TransitionsWithBridges> select_transitions_with_bridges(const MotionDatabase& db, const FrameFeatures& features,
                                                               const CandidateSearch& candidates,
                                                               const GraphFromCandidatesSettings& settings,
                                                               OnDemandCandidates* more = nullptr);

struct PrunedGraph {
  MotionGraph graph;  // pruned
  PruneReport prune;
  int survived_first_pruning = 0;  // transitions (bridges too) before spacing; build_spaced_graph
  // false: pruning the graph with its bridges' blends placed would have lost a transition, and
  // they blend over the window (place_bridge_blends).
  bool bridge_blends_placed = true;
};

// The last two: the graph of `transitions` (window k; blend_lengths and bridges as
// build_motion_graph takes them), pruned keeping connected_tags connected. Fails as build_motion_graph and
// prune_motion_graph do (in particular when the transitions form no cycle).
Result<PrunedGraph> build_pruned_graph(const MotionDatabase& db, std::span<const Transition> transitions, int window,
                                       TagMask connected_tags, std::span<const int> blend_lengths = {},
                                       std::span<const char> bridges = {});

// `pruned` (the graph of `transitions`, flagged bridges by `bridges`, blending over the window,
// pruned) with its bridges blended as long as their D asks (bridge_blend_frames), each blend
// centred on the window its D was measured on (bridge_blend, bridges.h): it leaves before the
// bridge's from_frame and lands after its to_frame, on frames of the clip pieces the pruned
// graph plays whose frames carry one set of tags (the moved ends split pieces the graph keeps
// into pieces of the same tags, so pruning keeps the same transitions), and its edge carries how
// far it leaves before (GraphEdge::blend_lead). The graph of the placed transitions is pruned
// again (the report's before and after are its). Should that lose a transition, `pruned` comes
// back as given, bridge_blends_placed false.
Result<PrunedGraph> place_bridge_blends(const MotionDatabase& db, std::span<const Transition> transitions,
                                        std::span<const char> bridges, double threshold,
                                        const GraphFromCandidatesSettings& settings, PrunedGraph pruned);

struct GraphFromCandidates {
  TransitionsWithBridges transitions;
  PrunedGraph pruned;
};

// The graph of the selection and bridges, spaced: pruned once, the surviving transitions but
// the bridges spaced (transition_spacing.h: the useful ones compete, not those pruning would
// drop anyway; bridges join motion types and are few), then built and pruned again, and its
// bridges' blends placed (place_bridge_blends). Every transition blends over the window while
// the graph is pruned.
Result<PrunedGraph> build_spaced_graph(const MotionDatabase& db, const TransitionsWithBridges& transitions,
                                       const FrameFeatures& features, const GraphFromCandidatesSettings& settings);

// All four steps.
Result<GraphFromCandidates> graph_from_candidates(const MotionDatabase& db, const FrameFeatures& features,
                                                  const CandidateSearch& candidates,
                                                  const GraphFromCandidatesSettings& settings,
                                                  OnDemandCandidates* more = nullptr);

}  // namespace mg
