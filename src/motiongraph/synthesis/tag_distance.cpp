#include "motiongraph/synthesis/tag_distance.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace mg {

std::vector<int> frames_to_tag(const MotionGraph& graph, const EdgeTracks& tracks, TagMask tag) {
  const int nodes = graph.node_count();
  constexpr int kFar = std::numeric_limits<int>::max();
  std::vector<int> distance(static_cast<size_t>(nodes), kFar);
  // The edges whose frames carry no tag, by the node they lead into (offsets into `into`): the
  // ways a distance travels back.
  const int edges = static_cast<int>(graph.edges.size());
  std::vector<int> offsets(static_cast<size_t>(nodes) + 1, 0);
  std::vector<char> untagged(static_cast<size_t>(edges), 0);
  for (int e = 0; e < edges; ++e) {
    const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
    const auto tags = tracks.tags_of(e);
    const auto first = std::find_if(tags.begin(), tags.end(), [&](TagMask m) { return (m & tag) != 0; });
    if (first != tags.end()) {
      int& from = distance[static_cast<size_t>(edge.from_node)];
      from = std::min(from, static_cast<int>(first - tags.begin()));
    } else {
      untagged[static_cast<size_t>(e)] = 1;
      ++offsets[static_cast<size_t>(edge.to_node) + 1];
    }
  }
  for (int n = 0; n < nodes; ++n) offsets[static_cast<size_t>(n) + 1] += offsets[static_cast<size_t>(n)];
  struct Back {
    int from_node;
    int frames;
  };
  std::vector<Back> into(static_cast<size_t>(offsets.back()));
  {
    std::vector<int> next(offsets.begin(), offsets.end() - 1);
    for (int e = 0; e < edges; ++e) {
      if (untagged[static_cast<size_t>(e)] == 0) continue;
      const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      into[static_cast<size_t>(next[static_cast<size_t>(edge.to_node)]++)] = {edge.from_node,
                                                                              tracks.edges[static_cast<size_t>(e)].count};
    }
  }
  using Entry = std::pair<int, int>;  // distance, node
  std::vector<Entry> heap;
  heap.reserve(static_cast<size_t>(nodes));
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue(std::greater<>(), std::move(heap));
  for (int n = 0; n < nodes; ++n) {
    if (distance[static_cast<size_t>(n)] < kFar) queue.emplace(distance[static_cast<size_t>(n)], n);
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[static_cast<size_t>(v)]) continue;
    for (int i = offsets[static_cast<size_t>(v)]; i < offsets[static_cast<size_t>(v) + 1]; ++i) {
      const Back& back = into[static_cast<size_t>(i)];
      const int through = d + back.frames;
      int& u = distance[static_cast<size_t>(back.from_node)];
      if (through < u) {
        u = through;
        queue.emplace(through, back.from_node);
      }
    }
  }
  for (int& d : distance) {
    if (d == kFar) d = -1;
  }
  return distance;
}

}  // namespace mg
