#include "motiongraph/synthesis/tag_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "synthesis/search_test_graphs.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// The definition, solved by relaxing every edge until nothing changes (Bellman-Ford): from u by
// e to v, the frames of e before its first tagged one, or all of e's frames and v's distance.
std::vector<int> by_relaxation(const MotionGraph& graph, const EdgeTracks& tracks, TagMask tag) {
  const int far = 1 << 30;
  std::vector<int> d(static_cast<size_t>(graph.node_count()), far);
  for (bool changed = true; changed;) {
    changed = false;
    for (int e = 0; e < static_cast<int>(graph.edges.size()); ++e) {
      const auto tags = tracks.tags_of(e);
      int through = far;
      for (size_t f = 0; f < tags.size(); ++f) {
        if ((tags[f] & tag) != 0) {
          through = static_cast<int>(f);
          break;
        }
      }
      const int v = d[static_cast<size_t>(graph.edges[e].to_node)];
      if (through == far && v < far) through = static_cast<int>(tags.size()) + v;
      int& u = d[static_cast<size_t>(graph.edges[e].from_node)];
      if (through < u) u = through, changed = true;
    }
  }
  for (int& x : d) x = x == far ? -1 : x;
  return d;
}

TEST(TagDistance, EqualsTheDefinitionOnRandomGraphs) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 3 + trial % 12, trial % 20, 6);
    EdgeTracks tracks = test::random_tracks(rng, graph);
    // Sparse tags: most frames carry none of bit 2, some none at all.
    for (TagMask& t : tracks.tags) t = (rng() % 9 == 0) ? TagMask{4} : TagMask{0};
    for (TagMask tag : {TagMask{1}, TagMask{2}, TagMask{4}, TagMask{8}}) {
      EXPECT_EQ(frames_to_tag(graph, tracks, tag), by_relaxation(graph, tracks, tag)) << trial << " tag " << tag;
    }
  }
}

TEST(TagDistance, OnSubject16ZeroWhereTheNodeCarriesTheTag) {
  const SynthesisContext& context = test::subject16().context();
  const MotionGraph& graph = *context.graph;
  for (const char* name : {"walk", "run", "jump"}) {
    const TagMask tag = *context.tag_mask(name);
    const std::vector<int> d = frames_to_tag(graph, context.tracks, tag);
    EXPECT_EQ(d, by_relaxation(graph, context.tracks, tag)) << name;
    // Strongly connected and the tag kept: every node reaches it; 0 exactly where a node's
    // out-edges start on a frame carrying it.
    for (int n = 0; n < graph.node_count(); ++n) {
      ASSERT_GE(d[static_cast<size_t>(n)], 0) << name << " node " << n;
      bool starts_tagged = false;
      for (int e = graph.edge_offsets[n]; e < graph.edge_offsets[n + 1]; ++e) {
        starts_tagged = starts_tagged || (context.tracks.tags_of(e).front() & tag) != 0;
      }
      EXPECT_EQ(d[static_cast<size_t>(n)] == 0, starts_tagged) << name << " node " << n;
    }
    EXPECT_GT(*std::max_element(d.begin(), d.end()), 0) << name;
  }
  // A tag no frame carries: no node reaches it.
  const std::vector<int> none = frames_to_tag(graph, context.tracks, TagMask{1} << 63);
  EXPECT_TRUE(std::all_of(none.begin(), none.end(), [](int x) { return x == -1; }));
}

}  // namespace
}  // namespace mg
