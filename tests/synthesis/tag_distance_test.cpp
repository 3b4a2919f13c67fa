#include "motiongraph/synthesis/tag_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <random>
#include <span>
#include <string>

#include <fmt/format.h>

#include "synthesis/search_test_graphs.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// The definition, solved by relaxing every edge until nothing changes (Bellman-Ford): from u by
// e to v, e's cost and per_frame for each of e's frames before its first tagged one, or for all
// of them and v's cost.
std::vector<double> by_relaxation(const MotionGraph& graph, const EdgeTracks& tracks, TagMask tag, double per_frame,
                                  const std::function<double(int)>& edge_cost) {
  const double far = std::numeric_limits<double>::infinity();
  std::vector<double> d(static_cast<size_t>(graph.node_count()), far);
  for (bool changed = true; changed;) {
    changed = false;
    for (int e = 0; e < static_cast<int>(graph.edges.size()); ++e) {
      const auto tags = tracks.tags_of(e);
      const double taken = edge_cost ? edge_cost(e) : 0.0;
      double through = far;
      for (size_t f = 0; f < tags.size(); ++f) {
        if ((tags[f] & tag) != 0) {
          through = taken + per_frame * static_cast<double>(f);
          break;
        }
      }
      const double v = d[static_cast<size_t>(graph.edges[e].to_node)];
      if (through == far && v < far) through = taken + per_frame * static_cast<double>(tags.size()) + v;
      double& u = d[static_cast<size_t>(graph.edges[e].from_node)];
      if (through < u - 1e-12) u = through, changed = true;
    }
  }
  for (double& x : d) x = x == far ? -1.0 : x;
  return d;
}

void expect_near(const std::vector<double>& a, const std::vector<double>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-9) << what << " node " << i;
}

TEST(TagDistance, EqualsTheDefinitionOnRandomGraphs) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 3 + trial % 12, trial % 20, 6);
    EdgeTracks tracks = test::random_tracks(rng, graph);
    // Sparse tags: most frames carry none of bit 2, some none at all.
    for (TagMask& t : tracks.tags) t = (rng() % 9 == 0) ? TagMask{4} : TagMask{0};
    // Each transition costs 0.7, plus 3 for one in five (a bridge, say).
    auto edge_cost = [&](int e) { return graph.edges[e].transition ? 0.7 + (e % 5 == 0 ? 3.0 : 0.0) : 0.0; };
    for (TagMask tag : {TagMask{1}, TagMask{2}, TagMask{4}, TagMask{8}}) {
      const std::string what = fmt::format("trial {} tag {}", trial, tag);
      expect_near(cost_to_tag(graph, tracks, tag, 1.0), by_relaxation(graph, tracks, tag, 1.0, {}), what);
      expect_near(cost_to_tag(graph, tracks, tag, 2.0, edge_cost), by_relaxation(graph, tracks, tag, 2.0, edge_cost),
                  what + " with edge costs");
    }
  }
}

// Any marks of the edges' frames (not the tracks' tags): the same definition, the marks as the
// tags; and what a walk still pays after its horizon, from those marks as from tags.
TEST(TagDistance, MarksOfTheFramesAreCostedAsTags) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 100; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 3 + trial % 12, trial % 20, 6);
    EdgeTracks tracks = test::random_tracks(rng, graph);
    for (TagMask& t : tracks.tags) t = TagMask{rng() % 3 == 0 ? 2u : 1u};  // tags the marks must not read
    std::vector<TagMask> marks(tracks.tags.size());
    for (TagMask& m : marks) m = rng() % 7 == 0 ? TagMask{1} : TagMask{0};
    auto marks_of = [&](int e) {
      return std::span<const TagMask>(marks).subspan(static_cast<size_t>(tracks.edges[e].first),
                                                     static_cast<size_t>(tracks.edges[e].count));
    };
    EdgeTracks marked = tracks;
    marked.tags = marks;
    auto edge_cost = [&](int e) { return graph.edges[e].transition ? 0.5 : 0.0; };
    const std::vector<double> to_mark = cost_to_mark(graph, marks_of, 1, 1.5, edge_cost);
    const std::string what = fmt::format("trial {}", trial);
    expect_near(to_mark, by_relaxation(graph, marked, 1, 1.5, edge_cost), what);
    for (int e = 0; e < static_cast<int>(graph.edges.size()); ++e) {
      for (size_t costed = 0; costed <= static_cast<size_t>(tracks.edges[e].count); ++costed) {
        EXPECT_EQ(cost_to_mark_after(marks_of(e), costed, graph.edges[e].to_node, 1, 1.5, to_mark),
                  cost_to_tag_after(marked, e, costed, graph.edges[e].to_node, 1, 1.5, to_mark))
            << what << " edge " << e;
      }
    }
  }
}

TEST(TagDistance, OnSubject16ZeroWhereTheNodeCarriesTheTag) {
  const SynthesisContext& context = test::subject16().context();
  const MotionGraph& graph = *context.graph;
  for (const char* name : {"walk", "run", "jump"}) {
    const TagMask tag = *context.tag_mask(name);
    const std::vector<double> d = cost_to_tag(graph, context.tracks, tag, 1.0);
    expect_near(d, by_relaxation(graph, context.tracks, tag, 1.0, {}), name);
    // Bridges priced as steering prices them: never cheaper, and the definition still.
    auto bridges = [&](int e) {
      const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      return edge.transition ? 1.0 + (unasked_bridge(context, edge, tag) ? 30.0 : 0.0) : 0.0;
    };
    const std::vector<double> priced = cost_to_tag(graph, context.tracks, tag, 2.0, bridges);
    expect_near(priced, by_relaxation(graph, context.tracks, tag, 2.0, bridges), std::string(name) + " priced");
    for (size_t n = 0; n < d.size(); ++n) EXPECT_GE(priced[n], 2.0 * d[n] - 1e-9) << name << " node " << n;
    // Strongly connected and the tag kept: every node reaches it; 0 exactly where a node's
    // out-edges start on a frame carrying it.
    for (int n = 0; n < graph.node_count(); ++n) {
      ASSERT_GE(d[static_cast<size_t>(n)], 0.0) << name << " node " << n;
      bool starts_tagged = false;
      for (int e = graph.edge_offsets[n]; e < graph.edge_offsets[n + 1]; ++e) {
        starts_tagged = starts_tagged || (context.tracks.tags_of(e).front() & tag) != 0;
      }
      EXPECT_EQ(d[static_cast<size_t>(n)] == 0, starts_tagged) << name << " node " << n;
    }
    EXPECT_GT(*std::max_element(d.begin(), d.end()), 0) << name;
  }
  // A tag no frame carries: no node reaches it.
  const std::vector<double> none = cost_to_tag(graph, context.tracks, TagMask{1} << 63, 1.0);
  EXPECT_TRUE(std::all_of(none.begin(), none.end(), [](double x) { return x == -1.0; }));
}

}  // namespace
}  // namespace mg
