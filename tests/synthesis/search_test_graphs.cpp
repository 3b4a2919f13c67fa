#include "synthesis/search_test_graphs.h"

#include <algorithm>

namespace mg::test {

MotionGraph random_search_graph(std::mt19937& rng, int nodes, int extra_edges, int max_frames) {
  MotionGraph graph;
  graph.window = 2;
  for (int n = 0; n < nodes; ++n) graph.nodes.push_back({n * 100, 0});
  std::uniform_int_distribution<int> node(0, nodes - 1), frames(1, max_frames);
  std::uniform_real_distribution<double> distance(0.0, 5.0);
  for (int n = 0; n < nodes; ++n) graph.edges.push_back({n, (n + 1) % nodes, false, -1, frames(rng)});
  for (int i = 0; i < extra_edges; ++i) {
    GraphEdge e{node(rng), node(rng), false, -1, frames(rng)};
    if (rng() % 4 == 0) {
      e.transition = true;
      e.transition_index = static_cast<int>(graph.transitions.size());
      Transition t;
      t.distance = static_cast<float>(distance(rng));
      graph.transitions.push_back(t);
    }
    graph.edges.push_back(e);
  }
  std::stable_sort(graph.edges.begin(), graph.edges.end(),
                   [](const GraphEdge& a, const GraphEdge& b) { return a.from_node < b.from_node; });
  graph.edge_offsets.assign(static_cast<size_t>(nodes) + 1, 0);
  for (const GraphEdge& e : graph.edges) ++graph.edge_offsets[e.from_node + 1];
  for (int n = 0; n < nodes; ++n) graph.edge_offsets[n + 1] += graph.edge_offsets[n];
  return graph;
}

EdgeTracks random_tracks(std::mt19937& rng, const MotionGraph& graph) {
  std::uniform_real_distribution<double> step(-0.1, 0.1), angle(-1.0, 1.0);
  EdgeTracks tracks;
  for (const GraphEdge& edge : graph.edges) {
    EdgeTrack track;
    track.first = static_cast<int>(tracks.roots.size());
    track.count = edge.frame_count;
    Vec2 root(step(rng), step(rng));
    for (int p = 0; p < edge.frame_count; ++p) {
      root += Vec2(step(rng), step(rng));
      tracks.roots.push_back(root);
      const double a = angle(rng);
      tracks.facings.emplace_back(std::cos(a), std::sin(a));
      tracks.tags.push_back(rng() % 3);
    }
    if (edge.transition) track.change = {angle(rng), step(rng), step(rng)};
    tracks.edges.push_back(track);
  }
  return tracks;
}

}  // namespace mg::test
