// The motion graph (Kovar et al. 2002, sections 3.2-3.3; DESIGN.md 4): nodes are database
// frames (global indices) where transitions leave or land, plus each clip's first and last
// frame; edges are the clip pieces between consecutive nodes of a clip and one edge per
// transition. Pruning keeps the part a walk can play forever (the largest strongly connected
// component), and with motion tags also keeps each tag's edges strongly connected among
// themselves.
//
// What an edge plays (the convention walks, search and assembly rely on). Every edge plays
// the frames from its source node's frame up to, not including, its target node's frame; the
// target node's frame is the first frame of the next edge. So the frames of a walk are the
// sum of its edges' frame_count, with no frame played twice:
//  - a clip edge from frame f1 to frame f2 (f1 < f2, same clip) plays f1 .. f2-1:
//    frame_count = f2 - f1;
//  - a transition edge for transition t (window k) goes from the node at t.from_frame to the
//    node at t.to_frame. Its blend reads the k frames t.from_frame .. t.from_frame+k-1 of the
//    clip we leave and t.to_frame-k+1 .. t.to_frame of the clip we arrive in; blended frame
//    p = 0..k-1 mixes the two windows' frames p with weight alpha(p) (DESIGN.md 5) on the one
//    we leave. alpha(k-1) = 0, so blended frame k-1 IS frame t.to_frame (aligned), which the
//    next edge plays. The transition edge therefore plays blended frames p = 0..k-2:
//    frame_count = k - 1. Hence k >= 2. A transition may blend over more frames than the
//    window, L >= k (bridges far above the threshold do: graph_from_candidates.h); it then
//    reads L frames on each side and plays L - 1, so L = frame_count + 1 always
//    (blend_frames below).
//
// Bridges: transitions between motion types above the threshold, added so that each type can
// reach the others (graph/bridges.h). Their edges carry `bridge`; searches price them so that a
// walk changes motion type through one only when asked to (horizon_search.h).
//
// Tags: an edge belongs to tag t when every frame it reads carries t (a clip edge: f1..f2-1;
// a transition: all 2k frames of both windows). Frames beyond the frame_tags span carry no
// tag, so an empty span means "no tags".
#pragma once

#include <span>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/transition.h"

namespace mg {

struct GraphNode {
  int frame = 0;  // global frame index
  int clip = 0;   // index into MotionDatabase::clips
};

struct GraphEdge {
  int from_node = 0;
  int to_node = 0;
  bool transition = false;
  int transition_index = -1;  // into MotionGraph::transitions; -1 for clip edges
  int frame_count = 0;        // frames played (see the header comment): f2 - f1, or k - 1
  // A transition that joins two motion types far above the threshold (graph/bridges.h): a
  // visible blend, which searches take only where a change of motion type is asked for.
  bool bridge = false;
  // A bridge blended longer than the window is centred on the window its D was measured on
  // (bridges.h bridge_blend): it leaves this many frames before that window's first frame (and
  // lands blend_frames() - window - blend_lead after its last). 0 for every other edge.
  int blend_lead = 0;
};

struct MotionGraph {
  int window = 0;                       // k, the blend length in frames
  std::vector<GraphNode> nodes;         // sorted by frame (so by clip too), frames distinct
  std::vector<GraphEdge> edges;         // sorted by from_node; per node its clip edge first,
                                        // then its transitions in transition order
  std::vector<int> edge_offsets;        // node_count + 1: node n's edges are
                                        // edges[edge_offsets[n] .. edge_offsets[n+1])
  std::vector<Transition> transitions;  // one per transition edge, in the order given

  int node_count() const { return static_cast<int>(nodes.size()); }
  int edge_count() const { return static_cast<int>(edges.size()); }
  std::span<const GraphEdge> out_edges(int node) const {
    return std::span<const GraphEdge>(edges).subspan(edge_offsets[node], edge_offsets[node + 1] - edge_offsets[node]);
  }
  // The node at a global frame; -1 when there is none.
  int node_at_frame(int frame) const;
};

// The frames a transition edge blends over (L, the window k or more; see the header comment).
inline int blend_frames(const GraphEdge& edge) { return edge.frame_count + 1; }

// The frames a transition edge's D was measured on: the first frame of the window it leaves and
// the last of the one it arrives in. A transition's own; a bridge whose blend is centred on its
// window leaves blend_lead frames before it and lands the rest of its extra frames after it.
struct MeasuredPair {
  int from_frame = 0;
  int to_frame = 0;
};
inline MeasuredPair measured_pair(const MotionGraph& graph, const GraphEdge& edge) {
  const Transition& t = graph.transitions[static_cast<size_t>(edge.transition_index)];
  const int extra = blend_frames(edge) - graph.window;
  return {t.from_frame + edge.blend_lead, t.to_frame - (extra - edge.blend_lead)};
}

// The unpruned graph. Fails when window < 2, when the clips are not one after the other from
// global frame 0 (each at least one frame), or when a transition's windows do not lie inside
// one clip each (from_frame .. from_frame+L-1, to_frame-L+1 .. to_frame). blend_lengths gives
// each transition's L (at least the window); empty: every transition blends over the window.
// bridges flags the transitions that are bridges (GraphEdge::bridge); empty: none is.
Result<MotionGraph> build_motion_graph(const MotionDatabase& db, std::span<const Transition> transitions, int window,
                                       std::span<const int> blend_lengths = {}, std::span<const char> bridges = {});

// The tags of one edge: the AND of frame_tags over every frame the edge reads (see above).
TagMask edge_tags(const MotionGraph& graph, const GraphEdge& edge, std::span<const TagMask> frame_tags);

// Pruning (Kovar 3.3, with tags as in DESIGN.md 4). Repeat passes until a pass removes nothing:
//  1. whole graph: keep the largest strongly connected component (largest_component() in
//     scc.h: most nodes, non-trivial, ties to the component holding the lowest node index);
//     every other node goes, with every edge touching it;
//  2. then for each tag t in connected_tags that some live edge carries, in increasing t:
//     the t-subgraph is the live edges that belong to t (with their end nodes); find its
//     largest strongly connected component the same way and remove every t-edge not inside
//     it (an edge belonging to several tags is removed from the graph for all of them).
// Removing edges for a tag can strand nodes (dead ends, sinks), which the next pass's step 1
// removes. Each pass but the last removes at least one edge, so this ends. At the end:
//  - the graph is strongly connected and non-trivial: no dead ends, no sinks;
//  - for each tag t in connected_tags, the edges belonging to t, with their end nodes, form one
//    strongly connected subgraph (or there are none): a walk may stay inside t forever and
//    get from any t-edge to any other using only t-edges.
// Consequences: a t-edge that only leads out of t's region (e.g. the clip piece from a walk
// loop to the frame where a walk->run transition leaves) is removed, so transitions between
// tags survive only when they leave from and land on nodes of the tags' regions; a region of
// tag t connected to t's largest region only through edges of other tags (walk - run - walk)
// loses its t-edges and then, usually, its nodes. Edges belonging to no tag (mixed frames,
// transitions between tags) are only subject to step 1.
struct PruneSettings {
  TagMask connected_tags = ~TagMask{0};  // tags whose subgraph must be strongly connected; 0 = ignore tags

  Status validate() const;  // nothing can be wrong today; kept for the settings convention
};

struct TagStatistics {
  int tag = 0;                      // bit index into MotionDatabase::tag_names
  int database_frames = 0;          // frames of frame_tags carrying the tag
  int frames = 0;                   // of those, frames played by the graph's clip edges
  int nodes = 0;                    // nodes touching an edge that belongs to the tag
  int edges = 0;                    // edges that belong to the tag
  int largest_component_nodes = 0;  // of the tag's subgraph (0 when it has no cycle)
};

struct GraphStatistics {
  int nodes = 0;
  int edges = 0;                    // clip and transition edges
  int clip_edges = 0;
  int transitions = 0;              // transition edges
  int bridges = 0;                  // of which bridges (GraphEdge::bridge)
  long long clip_frames = 0;        // database frames played by clip edges (distinct)
  int largest_component_nodes = 0;  // 0 when the graph has no cycle
  int components = 0;               // strongly connected components, trivial ones included
  std::vector<TagStatistics> tags;  // every tag some frame carries, in tag order
};

GraphStatistics compute_graph_statistics(const MotionGraph& graph, std::span<const TagMask> frame_tags);

struct PruneReport {
  GraphStatistics before;
  GraphStatistics after;
  int passes = 0;
  // For each node / edge / transition of the pruned graph, its index in the graph before.
  std::vector<int> kept_nodes;
  std::vector<int> kept_edges;
  std::vector<int> kept_transitions;
};

// Prunes in place and compacts (kept nodes, edges and transitions in their previous order, so
// the graph's sort orders hold). Fails, leaving the graph as it was, when frame_tags is
// neither empty nor covering every frame the graph reads, or when nothing would remain (the
// transitions form no cycle: a higher transition threshold gives more).
Result<PruneReport> prune_motion_graph(MotionGraph& graph, std::span<const TagMask> frame_tags,
                                       const PruneSettings& settings = {});

// The statistics as JSON text (an object), tags named by tag_names when given.
std::string to_json(const GraphStatistics& statistics, std::span<const std::string> tag_names = {});

}  // namespace mg
