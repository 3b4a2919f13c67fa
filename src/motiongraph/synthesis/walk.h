// A walk through a motion graph: a start node and the edges taken from it, each leaving the
// node the previous one entered (motion_graph.h says what every edge plays).
#pragma once

#include <span>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/motion_graph.h"

namespace mg {

// How many of `edges` (indices into graph.edges) are transitions.
inline int count_transitions(const MotionGraph& graph, std::span<const int> edges) {
  int n = 0;
  for (int e : edges) n += graph.edges[e].transition ? 1 : 0;
  return n;
}

// How many of `edges` are bridges (GraphEdge::bridge: blends between motion types above the
// threshold).
inline int count_bridges(const MotionGraph& graph, std::span<const int> edges) {
  int n = 0;
  for (int e : edges) n += graph.edges[e].bridge ? 1 : 0;
  return n;
}

struct Walk {
  int start_node = 0;
  std::vector<int> edges;  // indices into MotionGraph::edges
  // A walk that comes to rest (rest_endings.h): the database frames played after its edges, as
  // captured under the last edge's placement: its end node's clip on from the node's frame to the
  // clip's end, then that last frame held. Empty for every other walk.
  std::vector<int> rest_frames = {};

  // The node the walk ends at (start_node when it has no edges).
  int end_node(const MotionGraph& graph) const {
    return edges.empty() ? start_node : graph.edges[edges.back()].to_node;
  }
  // Frames played: the sum of the edges' frame_count.
  long long frame_count(const MotionGraph& graph) const {
    long long n = 0;
    for (int e : edges) n += graph.edges[e].frame_count;
    return n;
  }
  // Transition edges taken (each one a blend): how often the motion leaves its clip.
  int transition_count(const MotionGraph& graph) const { return count_transitions(graph, edges); }
};

// Fails unless start_node is a node and every edge exists and leaves the node the walk is at,
// and its rest frames, if any, start at the frame of the node it ends at.
Status check_walk(const MotionGraph& graph, const Walk& walk);

}  // namespace mg
