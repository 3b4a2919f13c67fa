#include "motiongraph/synthesis/rest_endings.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "motiongraph/database/travel_tags.h"
#include "motiongraph/graph/backward_costs.h"

namespace mg {

std::vector<int> RestEnding::frames(const MotionGraph& graph) const {
  std::vector<int> out;
  for (int f = graph.nodes[static_cast<size_t>(node)].frame; f <= last_frame; ++f) out.push_back(f);
  return out;
}

RestEndings find_rest_endings(const MotionDatabase& db, const MotionGraph& graph, const MotionAssembler& assembler) {
  RestEndings out;
  out.of_node.assign(static_cast<size_t>(graph.node_count()), -1);
  const TravelTagSettings travel;  // the defaults walk and run are tagged with
  int node = 0;                    // nodes are sorted by frame, so by clip
  for (int c = 0; c < static_cast<int>(db.clips.size()); ++c) {
    const DatabaseClip& clip = db.clips[static_cast<size_t>(c)];
    const int first = node;
    while (node < graph.node_count() && graph.nodes[static_cast<size_t>(node)].clip == c) ++node;
    if (first == node || clip.frame_count < 2) continue;  // no node in it, or nothing to play
    std::vector<Vec3> roots(static_cast<size_t>(clip.frame_count));
    for (int f = 0; f < clip.frame_count; ++f) {
      roots[static_cast<size_t>(f)] = assembler.root_position(clip.first_frame + f, {});
    }
    const std::vector<FrameSpan> spans = travelling_spans(roots, db.fps, travel);
    const int rests_from = spans.empty() ? 0 : spans.back().first + spans.back().count;
    if (rests_from >= clip.frame_count) continue;  // it travels to its end
    for (int n = first; n < node; ++n) {
      out.of_node[static_cast<size_t>(n)] = static_cast<int>(out.endings.size());
      out.endings.push_back({n, clip.first_frame + rests_from, clip.first_frame + clip.frame_count - 1});
    }
  }
  return out;
}

std::vector<double> cost_to_rest(const MotionGraph& graph, const RestEndings& endings, double transition_cost,
                                 double bridge_cost) {
  std::vector<double> at_rest(static_cast<size_t>(graph.node_count()), std::numeric_limits<double>::infinity());
  for (const RestEnding& ending : endings.endings) {
    double& c = at_rest[static_cast<size_t>(ending.node)];
    c = std::min(c, static_cast<double>(ending.frames_to_rest(graph)));
  }
  return backward_costs(graph, std::move(at_rest), [&](int e) {
    return rest_edge_cost(graph.edges[static_cast<size_t>(e)], transition_cost, bridge_cost);
  });
}

RestRoute rest_route(const MotionGraph& graph, const RestEndings& endings, const std::vector<double>& costs, int node,
                     double transition_cost, double bridge_cost, int max_frames) {
  RestRoute route;
  for (int frames = 0; costs[static_cast<size_t>(node)] >= 0.0;) {
    const double target = costs[static_cast<size_t>(node)];
    const RestEnding* here = endings.at(node);
    if (here != nullptr && here->frames_to_rest(graph) <= target + 1e-9) {
      route.ending = here;
      break;
    }
    if (frames >= max_frames) break;
    int best = -1;
    for (int e = graph.edge_offsets[node]; e < graph.edge_offsets[node + 1] && best < 0; ++e) {
      const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      const double to = costs[static_cast<size_t>(edge.to_node)];
      if (to >= 0.0 && rest_edge_cost(edge, transition_cost, bridge_cost) + to <= target + 1e-9) best = e;
    }
    if (best < 0) break;  // (cannot happen: the node's cost came from one of its edges)
    route.edges.push_back(best);
    frames += graph.edges[static_cast<size_t>(best)].frame_count;
    node = graph.edges[static_cast<size_t>(best)].to_node;
  }
  return route;
}

}  // namespace mg
