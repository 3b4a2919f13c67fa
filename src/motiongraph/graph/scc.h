// Strongly connected components of a directed graph (Tarjan 1972), used to prune the motion
// graph to the part a walk can play forever (Kovar et al. 2002, section 3.3; DESIGN.md 4).
//
// The graph is in compressed form: the edges leaving node v are the positions
// offsets[v] .. offsets[v+1]-1 of `targets`, and edge position e goes to node targets[e].
// Filters (alive masks) hide nodes and edges without copying the graph: an edge counts only
// when it is alive and both its ends are alive. Tarjan's depth-first search is written
// iteratively with explicit stacks, so chains of millions of nodes do not touch the call
// stack. Time O(V + E), memory O(V). Inputs are checked with assert only (programmer errors).
#pragma once

#include <span>
#include <utility>
#include <vector>

namespace mg {

// A view of a graph in compressed (CSR) form; the caller owns the arrays.
struct DigraphView {
  std::span<const int> offsets;  // node_count + 1 entries, non-decreasing, from 0 to targets.size()
  std::span<const int> targets;  // one per edge position, each in [0, node_count)

  int node_count() const { return offsets.empty() ? 0 : static_cast<int>(offsets.size()) - 1; }
  int edge_count() const { return static_cast<int>(targets.size()); }
};

// What the search may see. An empty span means "all alive"; otherwise one entry per node
// (per edge position), non-zero = alive.
struct SccFilter {
  std::span<const char> node_alive;
  std::span<const char> edge_alive;
};

// A graph built from (from, to) pairs, owning its arrays. Edges are grouped by source node,
// in input order within a node (a stable counting sort); edge_ids[e] is the input index of
// the edge at position e, so per-edge data can be carried over.
struct CompressedDigraph {
  std::vector<int> offsets;
  std::vector<int> targets;
  std::vector<int> edge_ids;

  DigraphView view() const { return {offsets, targets}; }
};

CompressedDigraph compress_edges(int node_count, std::span<const std::pair<int, int>> edges);

struct Components {
  // Component of every node; -1 for nodes the filter hides. Ids are given in the order
  // Tarjan completes the components, which is a reverse topological order of the condensed
  // graph: for a live edge u -> v, component_of_node[v] <= component_of_node[u].
  std::vector<int> component_of_node;
  std::vector<int> node_counts;  // per component
  std::vector<int> edge_counts;  // per component: live edges with both ends in it (self-loops too)
  std::vector<int> first_node;   // per component: its lowest node index

  int count() const { return static_cast<int>(node_counts.size()); }
  // A component with no edge inside (one node without a self-loop) is trivial: no walk can
  // stay in it.
  bool trivial(int component) const { return edge_counts[component] == 0; }
};

Components strongly_connected_components(const DigraphView& graph, const SccFilter& filter = {});

// The non-trivial component with the most nodes; ties go to the one whose lowest node index is
// smallest (independent of the search order). -1 when every component is trivial (no cycle).
int largest_component(const Components& components);

}  // namespace mg
