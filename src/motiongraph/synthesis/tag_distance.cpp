#include "motiongraph/synthesis/tag_distance.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace mg {

std::vector<double> cost_to_tag(const MotionGraph& graph, const EdgeTracks& tracks, TagMask tag, double per_frame,
                                const std::function<double(int edge)>& edge_cost) {
  const int nodes = graph.node_count();
  constexpr double kFar = std::numeric_limits<double>::infinity();
  std::vector<double> cost(static_cast<size_t>(nodes), kFar);
  // The edges whose frames carry no tag, by the node they lead into (offsets into `into`): the
  // ways a cost travels back, with what taking and playing them costs.
  const int edges = static_cast<int>(graph.edges.size());
  struct Back {
    int from_node;
    double cost;
  };
  std::vector<int> offsets(static_cast<size_t>(nodes) + 1, 0);
  std::vector<double> through(static_cast<size_t>(edges), -1.0);  // >= 0: an untagged edge's own cost
  for (int e = 0; e < edges; ++e) {
    const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
    const auto tags = tracks.tags_of(e);
    const double taken = edge_cost ? edge_cost(e) : 0.0;
    const auto first = std::find_if(tags.begin(), tags.end(), [&](TagMask m) { return (m & tag) != 0; });
    if (first != tags.end()) {
      double& from = cost[static_cast<size_t>(edge.from_node)];
      from = std::min(from, taken + per_frame * static_cast<double>(first - tags.begin()));
    } else {
      through[static_cast<size_t>(e)] = taken + per_frame * static_cast<double>(tags.size());
      ++offsets[static_cast<size_t>(edge.to_node) + 1];
    }
  }
  for (int n = 0; n < nodes; ++n) offsets[static_cast<size_t>(n) + 1] += offsets[static_cast<size_t>(n)];
  std::vector<Back> into(static_cast<size_t>(offsets.back()));
  {
    std::vector<int> next(offsets.begin(), offsets.end() - 1);
    for (int e = 0; e < edges; ++e) {
      if (through[static_cast<size_t>(e)] < 0.0) continue;
      const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      into[static_cast<size_t>(next[static_cast<size_t>(edge.to_node)]++)] = {edge.from_node,
                                                                              through[static_cast<size_t>(e)]};
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
  return cost;
}

double cost_to_tag_after(const EdgeTracks& tracks, int edge, size_t costed, int end_node, TagMask tag,
                         double per_frame, const std::vector<double>& to_tag) {
  const auto rest = tracks.tags_of(edge).subspan(costed);
  for (size_t f = 0; f < rest.size(); ++f) {
    if ((rest[f] & tag) != 0) return per_frame * static_cast<double>(f);
  }
  const double beyond = to_tag[static_cast<size_t>(end_node)];
  return beyond < 0.0 ? 0.0 : per_frame * static_cast<double>(rest.size()) + beyond;
}

const std::vector<double>* searched_costs_to_tag(const SynthesisContext& context, const TagCostCache::Key& key) {
  if (!context.tag_costs) return nullptr;
  return &context.tag_costs->get(key, [&] {
    const MotionGraph& graph = *context.graph;
    auto edge_cost = [&](int e) {
      const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      return edge.transition ? transition_price(context, edge, key.tag, key.transition_penalty, key.bridge_penalty)
                             : 0.0;
    };
    return cost_to_tag(graph, context.tracks, key.tag, key.per_frame, edge_cost);
  });
}

}  // namespace mg
