// Least costs to goals, found by Dijkstra over a graph's edges walked backwards: each node's cost
// is the least, over its out-edges, of the edge's cost and the cost of the node it leads to, or
// its own cost as a goal. What the searches' costs-to-go are made of (synthesis/tag_distance.h:
// to a motion tag; synthesis/rest_endings.h: to rest).
#pragma once

#include <functional>
#include <vector>

#include "motiongraph/graph/motion_graph.h"

namespace mg {

// Per node, the least cost to a goal: `at_goal` gives each node's cost where it is a goal (+inf
// elsewhere), edge_cost(e) each edge's (>= 0; negative: the edge is not taken). -1 where no goal is
// reached.
std::vector<double> backward_costs(const MotionGraph& graph, std::vector<double> at_goal,
                                   const std::function<double(int edge)>& edge_cost);

}  // namespace mg
