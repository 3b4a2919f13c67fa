#include "motiongraph/synthesis/tag_distance.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <utility>

#include "motiongraph/graph/backward_costs.h"

namespace mg {

std::vector<double> cost_to_tag(const MotionGraph& graph, const EdgeTracks& tracks, TagMask tag, double per_frame,
                                const std::function<double(int edge)>& edge_cost) {
  return cost_to_mark(graph, [&tracks](int e) { return tracks.tags_of(e); }, tag, per_frame, edge_cost);
}

std::vector<double> cost_to_mark(const MotionGraph& graph,
                                 const std::function<std::span<const TagMask>(int edge)>& marks_of, TagMask tag,
                                 double per_frame, const std::function<double(int edge)>& edge_cost) {
  constexpr double kFar = std::numeric_limits<double>::infinity();
  std::vector<double> at_tag(static_cast<size_t>(graph.node_count()), kFar);
  // An edge whose frames carry the tag makes its node a goal; the others are the ways a cost
  // travels back, with what taking and playing them costs (-1: none).
  const int edges = static_cast<int>(graph.edges.size());
  std::vector<double> through(static_cast<size_t>(edges), -1.0);
  for (int e = 0; e < edges; ++e) {
    const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
    const auto tags = marks_of(e);
    const double taken = edge_cost ? edge_cost(e) : 0.0;
    const auto first = std::find_if(tags.begin(), tags.end(), [&](TagMask m) { return (m & tag) != 0; });
    if (first != tags.end()) {
      double& from = at_tag[static_cast<size_t>(edge.from_node)];
      from = std::min(from, taken + per_frame * static_cast<double>(first - tags.begin()));
    } else {
      through[static_cast<size_t>(e)] = taken + per_frame * static_cast<double>(tags.size());
    }
  }
  return backward_costs(graph, std::move(at_tag), [&](int e) { return through[static_cast<size_t>(e)]; });
}

double cost_to_tag_after(const EdgeTracks& tracks, int edge, size_t costed, int end_node, TagMask tag,
                         double per_frame, const std::vector<double>& to_tag) {
  return cost_to_mark_after(tracks.tags_of(edge), costed, end_node, tag, per_frame, to_tag);
}

double cost_to_mark_after(std::span<const TagMask> marks, size_t costed, int end_node, TagMask tag, double per_frame,
                          const std::vector<double>& to_tag) {
  const auto rest = marks.subspan(std::min(costed, marks.size()));
  for (size_t f = 0; f < rest.size(); ++f) {
    if ((rest[f] & tag) != 0) return per_frame * static_cast<double>(f);
  }
  const double beyond = to_tag[static_cast<size_t>(end_node)];
  return beyond < 0.0 ? 0.0 : per_frame * static_cast<double>(rest.size()) + beyond;
}

TagCostCache::Costs searched_costs_to_tag(const SynthesisContext& context, const TagCostCache::Key& key) {
  if (!context.tag_costs) return nullptr;
  return context.tag_costs->get(key, [&] {
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
