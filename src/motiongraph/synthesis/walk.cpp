#include "motiongraph/synthesis/walk.h"

#include <fmt/format.h>

namespace mg {

Status check_walk(const MotionGraph& graph, const Walk& walk) {
  if (walk.start_node < 0 || walk.start_node >= graph.node_count()) {
    return Error{"", 0, fmt::format("walk starts at node {}, but the graph has nodes 0..{}", walk.start_node,
                                    graph.node_count() - 1)};
  }
  int at = walk.start_node;
  for (size_t i = 0; i < walk.edges.size(); ++i) {
    const int e = walk.edges[i];
    if (e < 0 || e >= graph.edge_count()) {
      return Error{"", 0, fmt::format("walk step {}: edge {} does not exist (the graph has {} edges)", i, e,
                                      graph.edge_count())};
    }
    if (graph.edges[e].from_node != at) {
      return Error{"", 0, fmt::format("walk step {}: edge {} leaves node {}, but the walk is at node {}", i, e,
                                      graph.edges[e].from_node, at)};
    }
    at = graph.edges[e].to_node;
  }
  if (!walk.rest_frames.empty() && walk.rest_frames.front() != graph.nodes[at].frame) {
    return Error{"", 0, fmt::format("the walk comes to rest from frame {}, but it ends at node {} (frame {})",
                                    walk.rest_frames.front(), at, graph.nodes[at].frame)};
  }
  return Ok{};
}

}  // namespace mg
