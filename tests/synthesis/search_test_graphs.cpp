#include "synthesis/search_test_graphs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

namespace {

// The least cost any walk from `from` still adds (its transitions, its frames within the
// horizon, its terminal cost), every walk played out as horizon_search plays it. With `tally`,
// also expects each partial walk's bound, as horizon_search adds it (remaining_bound plus
// node_bound), to be at most that least cost of its own.
double least_completion(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& from,
                        const FrameCost& cost, int horizon, BoundTally* tally, const std::string& what) {
  const bool headings = cost.uses_heading() && !tracks.headings.empty();
  double best = std::numeric_limits<double>::infinity();
  for (int e = graph.edge_offsets[from.node]; e < graph.edge_offsets[from.node + 1]; ++e) {
    double total = graph.edges[e].transition ? cost.transition_cost(graph.edges[e], from) : 0.0;
    SearchState s = from;
    bool goal = false;
    size_t costed = 0;
    double horizon_arc = 0.0;
    const auto roots = tracks.roots_of(e);
    const auto facings = headings ? tracks.headings_of(e) : tracks.facings_of(e);
    for (size_t p = 0; p < roots.size(); ++p) {
      const Vec3 r = s.placement.apply(Vec3(roots[p].x(), 0.0, roots[p].y()));
      const Vec3 f = s.placement.rotate(Vec3(facings[p].x(), 0.0, facings[p].y()));
      const Vec2 root(r.x(), r.z());
      if (s.has_last) s.arc_m += (root - s.last_root).norm();
      s.last_root = root;
      s.has_last = true;
      const long long frame = s.frames + static_cast<long long>(p);
      if (frame < horizon && !goal) {
        total += cost.cost(static_cast<int>(frame), root, Vec2(f.x(), f.z()), s.arc_m, tracks.tags_of(e)[p], &goal);
        costed = p + 1;
        horizon_arc = s.arc_m;
      }
    }
    s.frames += static_cast<long long>(roots.size());
    s.placement = s.placement * tracks.edges[e].change;
    s.node = graph.edges[e].to_node;
    if (goal) {
      best = std::min(best, total);
    } else if (s.frames >= horizon) {
      best = std::min(best, total + cost.terminal_cost(e, costed, horizon_arc, s));
    } else {
      const double rest = least_completion(graph, tracks, s, cost, horizon, tally, what);
      if (tally != nullptr) {
        const int frames_left = static_cast<int>(horizon - s.frames);
        const double node = cost.node_bound(s, frames_left);
        const double bound = cost.remaining_bound(frames_left, s.last_root, s.arc_m) + node;
        EXPECT_LE(bound, rest + 1e-9 * std::max(1.0, rest))
            << what << ": a partial walk's bound above its least completion";
        ++tally->partial_walks;
        tally->node_bounded += node > 0.0 ? 1 : 0;
      }
      best = std::min(best, total + rest);
    }
  }
  return best;
}

}  // namespace

double every_walk(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start, const FrameCost& cost,
                  int horizon) {
  return least_completion(graph, tracks, start, cost, horizon, nullptr, "");
}

double expect_search_exact(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start,
                           const FrameCost& cost, int horizon, BoundTally& tally, const std::string& what) {
  EXPECT_EQ(start.frames, 0) << what;  // frames are counted from the search's start
  const double best = least_completion(graph, tracks, start, cost, horizon, &tally, what);
  EXPECT_TRUE(std::isfinite(best)) << what;
  const double tolerance = 1e-9 * std::max(1.0, best);
  const WithoutNodeBound unbounded(cost);
  HorizonSettings search;
  search.horizon_frames = horizon;
  search.max_expansions = 100'000'000;
  for (int beam : {0, 4}) {
    search.beam_width = beam;
    const HorizonResult found = horizon_search(graph, tracks, start, cost, search);
    EXPECT_FALSE(found.budget_exhausted) << what;
    EXPECT_NEAR(found.cost, best, tolerance) << what << ", beam " << beam;
    const HorizonResult plain = horizon_search(graph, tracks, start, unbounded, search);
    EXPECT_NEAR(plain.cost, best, tolerance) << what << ", beam " << beam << ", no node bound";
    if (beam > 0) continue;
    tally.with_bound += found.expansions;
    tally.without_bound += plain.expansions;
    tally.cut += found.expansions < plain.expansions ? 1 : 0;
  }
  return best;
}

}  // namespace mg::test
