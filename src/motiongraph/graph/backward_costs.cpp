#include "motiongraph/graph/backward_costs.h"

#include <limits>
#include <queue>
#include <utility>

namespace mg {

std::vector<double> backward_costs(const MotionGraph& graph, std::vector<double> at_goal,
                                   const std::function<double(int edge)>& edge_cost) {
  const int nodes = graph.node_count();
  constexpr double kFar = std::numeric_limits<double>::infinity();
  std::vector<double>& cost = at_goal;  // settled in place
  // The edges taken, by the node they lead into (offsets into `into`), with their costs.
  struct Back {
    int from_node;
    double cost;
  };
  std::vector<double> edge_costs(graph.edges.size());
  std::vector<int> offsets(static_cast<size_t>(nodes) + 1, 0);
  for (int e = 0; e < graph.edge_count(); ++e) {
    edge_costs[static_cast<size_t>(e)] = edge_cost(e);
    if (edge_costs[static_cast<size_t>(e)] >= 0.0) ++offsets[static_cast<size_t>(graph.edges[e].to_node) + 1];
  }
  for (int n = 0; n < nodes; ++n) offsets[static_cast<size_t>(n) + 1] += offsets[static_cast<size_t>(n)];
  std::vector<Back> into(static_cast<size_t>(offsets.back()));
  {
    std::vector<int> next(offsets.begin(), offsets.end() - 1);
    for (int e = 0; e < graph.edge_count(); ++e) {
      if (edge_costs[static_cast<size_t>(e)] < 0.0) continue;
      const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      into[static_cast<size_t>(next[static_cast<size_t>(edge.to_node)]++)] = {edge.from_node,
                                                                              edge_costs[static_cast<size_t>(e)]};
    }
  }
  using Entry = std::pair<double, int>;  // cost, node
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (int n = 0; n < nodes; ++n) {
    if (cost[static_cast<size_t>(n)] < kFar) queue.emplace(cost[static_cast<size_t>(n)], n);
  }
  while (!queue.empty()) {
    const auto [c, v] = queue.top();
    queue.pop();
    if (c > cost[static_cast<size_t>(v)]) continue;
    for (int i = offsets[static_cast<size_t>(v)]; i < offsets[static_cast<size_t>(v) + 1]; ++i) {
      const Back& back = into[static_cast<size_t>(i)];
      const double via = c + back.cost;
      double& u = cost[static_cast<size_t>(back.from_node)];
      if (via < u) {
        u = via;
        queue.emplace(via, back.from_node);
      }
    }
  }
  for (double& c : cost) {
    if (c == kFar) c = -1.0;
  }
  return at_goal;
}

}  // namespace mg
