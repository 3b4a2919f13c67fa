// How far a motion tag lies from each node of a graph, priced as a search prices it: the least
// cost any walk from the node pays before it plays a frame carrying the tag, `per_frame` for each
// frame it plays without it and edge_cost(e) for each edge e it takes on the way (a transition's
// penalty, a bridge's into another motion type; charged as the edge starts). A search that sees
// only its horizon finds every walk within it as far from a tag it cannot reach in time: asked
// to run, a character walking far from any way into running would walk on. This is what any
// continuation beyond the horizon must still pay, a cost-to-go (steer_cost.h, path_cost.h).
//
// Each edge's frames are its track's (EdgeTracks::tags_of: a transition's blended frames carry
// the tags of the side that weighs more); from node u by edge e to node v the cost is
// edge_cost(e) plus per_frame times e's frames before its first tagged one, or its frames all
// and v's cost. Dijkstra over the reversed edges. In a strongly connected graph (a pruned one)
// a tag is reached from every node or from none.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "motiongraph/synthesis/edge_tracks.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

// Per node of `graph`, the cost to the first frame carrying any tag of `tag`; -1 where no walk
// reaches one. edge_cost(e) >= 0 (empty: 0 for every edge).
std::vector<double> cost_to_tag(const MotionGraph& graph, const EdgeTracks& tracks, TagMask tag, double per_frame,
                                const std::function<double(int edge)>& edge_cost = {});

// The same for any marks of the edges' frames (marks_of(e): one per frame of edge e, as
// EdgeTracks::tags_of gives the tags): the cost to the first frame whose mark has a bit of `mark`.
std::vector<double> cost_to_mark(const MotionGraph& graph,
                                 const std::function<std::span<const TagMask>(int edge)>& marks_of, TagMask mark,
                                 double per_frame, const std::function<double(int edge)>& edge_cost = {});

// What any walk still pays before `tag` after a walk that reached its horizon in edge `edge`, its
// first `costed` frames costed, and ends at node `end_node`: per_frame for each later frame of
// the edge before one carrying the tag, or for all of them and then the node's cost in `to_tag`
// (cost_to_tag's; 0 where no walk reaches the tag from there). The path and steering searches'
// cost-to-go, before their weight.
double cost_to_tag_after(const EdgeTracks& tracks, int edge, size_t costed, int end_node, TagMask tag,
                         double per_frame, const std::vector<double>& to_tag);
// The same for an edge's marks (`marks`, one per frame of the edge) and cost_to_mark's costs.
double cost_to_mark_after(std::span<const TagMask> marks, size_t costed, int end_node, TagMask mark, double per_frame,
                          const std::vector<double>& to_mark);

// The costs to `key.tag` of `context`'s graph as path and steering searches price them: per_frame
// for each frame without it, the transition penalty for each transition and the bridge penalty
// more for each bridge that does not lead into it (unasked_bridge). Kept in the context's cache
// (made the first time any search asks); null when the context has none.
TagCostCache::Costs searched_costs_to_tag(const SynthesisContext& context, const TagCostCache::Key& key);

}  // namespace mg
