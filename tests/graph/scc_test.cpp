#include "motiongraph/graph/scc.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <random>
#include <utility>
#include <vector>

namespace mg {
namespace {

using EdgeList = std::vector<std::pair<int, int>>;

// Reference: reachability by breadth-first search from every node over the live edges
// (alive, both ends alive); two live nodes share a component iff each reaches the other.
std::vector<std::vector<char>> reachability(int n, const EdgeList& edges, const std::vector<char>& node_alive,
                                            const std::vector<char>& edge_alive) {
  std::vector<std::vector<int>> adjacency(n);
  for (size_t i = 0; i < edges.size(); ++i) {
    const auto [u, v] = edges[i];
    if (edge_alive[i] && node_alive[u] && node_alive[v]) adjacency[u].push_back(v);
  }
  std::vector<std::vector<char>> reach(n, std::vector<char>(n, 0));
  for (int s = 0; s < n; ++s) {
    if (!node_alive[s]) continue;
    std::deque<int> queue{s};
    reach[s][s] = 1;
    while (!queue.empty()) {
      const int u = queue.front();
      queue.pop_front();
      for (int v : adjacency[u]) {
        if (!reach[s][v]) {
          reach[s][v] = 1;
          queue.push_back(v);
        }
      }
    }
  }
  return reach;
}

struct RandomGraph {
  int n = 0;
  EdgeList edges;
  std::vector<char> node_alive;  // by node
  std::vector<char> edge_alive;  // by input edge index
  bool filtered = false;
};

RandomGraph random_graph(std::mt19937& rng) {
  RandomGraph g;
  g.n = std::uniform_int_distribution<int>(0, 40)(rng);
  const int max_edges = g.n * std::uniform_int_distribution<int>(0, 4)(rng);
  const int m = std::uniform_int_distribution<int>(0, std::max(0, max_edges))(rng);
  std::uniform_int_distribution<int> node(0, std::max(0, g.n - 1));
  for (int i = 0; i < m && g.n > 0; ++i) g.edges.push_back({node(rng), node(rng)});  // self-loops, duplicates too
  g.filtered = std::bernoulli_distribution(0.5)(rng);
  std::bernoulli_distribution dead(g.filtered ? 0.2 : 0.0);
  g.node_alive.resize(g.n);
  for (auto& a : g.node_alive) a = !dead(rng);
  g.edge_alive.resize(g.edges.size());
  for (auto& a : g.edge_alive) a = !dead(rng);
  return g;
}

// Checks `c` against the brute-force reference on one graph.
void expect_matches_reference(const RandomGraph& g, const Components& c) {
  const auto reach = reachability(g.n, g.edges, g.node_alive, g.edge_alive);
  ASSERT_EQ(static_cast<int>(c.component_of_node.size()), g.n);
  for (int u = 0; u < g.n; ++u) {
    if (!g.node_alive[u]) {
      EXPECT_EQ(c.component_of_node[u], -1) << "dead node " << u;
      continue;
    }
    ASSERT_GE(c.component_of_node[u], 0);
    ASSERT_LT(c.component_of_node[u], c.count());
    for (int v = 0; v < g.n; ++v) {
      if (!g.node_alive[v]) continue;
      const bool mutual = reach[u][v] && reach[v][u];
      EXPECT_EQ(c.component_of_node[u] == c.component_of_node[v], mutual) << u << " " << v;
    }
  }
  // Sizes, lowest nodes and inner edges per component.
  std::vector<int> sizes(c.count(), 0), firsts(c.count(), g.n), inner(c.count(), 0);
  for (int u = 0; u < g.n; ++u) {
    const int cu = c.component_of_node[u];
    if (cu < 0) continue;
    ++sizes[cu];
    firsts[cu] = std::min(firsts[cu], u);
  }
  for (size_t i = 0; i < g.edges.size(); ++i) {
    const auto [u, v] = g.edges[i];
    if (!g.edge_alive[i] || !g.node_alive[u] || !g.node_alive[v]) continue;
    EXPECT_LE(c.component_of_node[v], c.component_of_node[u]) << "ids are not reverse topological";
    if (c.component_of_node[u] == c.component_of_node[v]) ++inner[c.component_of_node[u]];
  }
  EXPECT_EQ(c.node_counts, sizes);
  EXPECT_EQ(c.first_node, firsts);
  EXPECT_EQ(c.edge_counts, inner);
  for (int id = 0; id < c.count(); ++id) EXPECT_GT(sizes[id], 0);

  // Largest: the reference picks among mutual-reachability classes, named by their lowest node.
  int best_first = -1, best_size = 0;
  for (int u = 0; u < g.n; ++u) {
    if (!g.node_alive[u]) continue;
    bool is_lowest = true;
    int size = 0;
    for (int v = 0; v < g.n; ++v) {
      if (!g.node_alive[v] || !(reach[u][v] && reach[v][u])) continue;
      ++size;
      if (v < u) is_lowest = false;
    }
    if (!is_lowest) continue;
    bool has_edge = false;
    for (size_t i = 0; i < g.edges.size(); ++i) {
      const auto [a, b] = g.edges[i];
      if (g.edge_alive[i] && g.node_alive[a] && g.node_alive[b] && reach[u][a] && reach[a][u] && reach[u][b] &&
          reach[b][u]) {
        has_edge = true;
      }
    }
    if (has_edge && size > best_size) {  // classes visited by increasing lowest node: ties keep the first
      best_size = size;
      best_first = u;
    }
  }
  const int largest = largest_component(c);
  if (best_first < 0) {
    EXPECT_EQ(largest, -1);
  } else {
    ASSERT_GE(largest, 0);
    EXPECT_EQ(c.first_node[largest], best_first);
    EXPECT_EQ(c.node_counts[largest], best_size);
  }
}

TEST(Scc, CompressEdgesGroupsBySourceStably) {
  const EdgeList edges = {{2, 0}, {0, 1}, {2, 2}, {0, 2}, {1, 0}};
  const CompressedDigraph g = compress_edges(4, edges);
  EXPECT_EQ(g.offsets, (std::vector<int>{0, 2, 3, 5, 5}));
  EXPECT_EQ(g.targets, (std::vector<int>{1, 2, 0, 0, 2}));
  EXPECT_EQ(g.edge_ids, (std::vector<int>{1, 3, 4, 0, 2}));
  EXPECT_EQ(g.view().node_count(), 4);
  EXPECT_EQ(g.view().edge_count(), 5);
}

TEST(Scc, TextbookExample) {
  // Two 3-cycles joined one way, a 2-cycle, and a lone node with a self-loop, plus a lone node.
  const EdgeList edges = {{0, 1}, {1, 2}, {2, 0}, {2, 3}, {3, 4}, {4, 5}, {5, 3}, {5, 6}, {6, 7}, {7, 6}, {8, 8}};
  const CompressedDigraph g = compress_edges(10, edges);
  const Components c = strongly_connected_components(g.view());
  EXPECT_EQ(c.count(), 5);
  const auto& id = c.component_of_node;
  EXPECT_EQ(id[0], id[1]);
  EXPECT_EQ(id[1], id[2]);
  EXPECT_EQ(id[3], id[4]);
  EXPECT_EQ(id[4], id[5]);
  EXPECT_EQ(id[6], id[7]);
  EXPECT_NE(id[0], id[3]);
  EXPECT_LT(id[6], id[3]);  // reverse topological: 6-7 is downstream of 3-4-5, which is of 0-1-2
  EXPECT_LT(id[3], id[0]);
  EXPECT_FALSE(c.trivial(id[8]));  // self-loop
  EXPECT_TRUE(c.trivial(id[9]));
  // Two 3-cycles tie: the one holding node 0 wins.
  EXPECT_EQ(largest_component(c), id[0]);
}

TEST(Scc, FiltersHideNodesAndEdges) {
  const EdgeList edges = {{0, 1}, {1, 2}, {2, 0}, {1, 0}};
  const CompressedDigraph g = compress_edges(3, edges);
  // Positions: node 0: (0,1); node 1: (1,2), (1,0); node 2: (2,0).
  std::vector<char> edge_alive = {1, 0, 1, 1};  // hide 1 -> 2
  Components c = strongly_connected_components(g.view(), {{}, edge_alive});
  EXPECT_EQ(c.component_of_node[0], c.component_of_node[1]);
  EXPECT_NE(c.component_of_node[0], c.component_of_node[2]);
  std::vector<char> node_alive = {1, 0, 1};
  c = strongly_connected_components(g.view(), {node_alive, {}});
  EXPECT_EQ(c.component_of_node[1], -1);
  EXPECT_EQ(c.count(), 2);
  EXPECT_EQ(largest_component(c), -1);  // 0 and 2 alone, no cycle left
}

TEST(Scc, EmptyGraph) {
  const CompressedDigraph g = compress_edges(0, {});
  const Components c = strongly_connected_components(g.view());
  EXPECT_EQ(c.count(), 0);
  EXPECT_EQ(largest_component(c), -1);
}

TEST(Scc, MatchesBruteForceOnRandomGraphs) {
  for (unsigned seed = 0; seed < 400; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937 rng(seed);
    const RandomGraph g = random_graph(rng);
    const CompressedDigraph compressed = compress_edges(g.n, g.edges);
    std::vector<char> edge_alive_by_position(g.edges.size());
    for (size_t e = 0; e < g.edges.size(); ++e) edge_alive_by_position[e] = g.edge_alive[compressed.edge_ids[e]];
    SccFilter filter;
    if (g.filtered) filter = {g.node_alive, edge_alive_by_position};
    const Components c = strongly_connected_components(compressed.view(), filter);
    expect_matches_reference(g, c);
    if (HasFatalFailure()) return;
  }
}

// A million nodes deep: a recursive Tarjan would need a million nested calls.
constexpr int kMillion = 1'000'000;

TEST(Scc, MillionNodeCycleIsOneComponent) {
  EdgeList edges;
  edges.reserve(kMillion);
  for (int i = 0; i < kMillion; ++i) edges.push_back({i, (i + 1) % kMillion});
  const CompressedDigraph g = compress_edges(kMillion, edges);
  const Components c = strongly_connected_components(g.view());
  ASSERT_EQ(c.count(), 1);
  EXPECT_EQ(c.node_counts[0], kMillion);
  EXPECT_EQ(c.edge_counts[0], kMillion);
  EXPECT_EQ(largest_component(c), 0);
}

TEST(Scc, MillionNodeChainIsAMillionTrivialComponents) {
  EdgeList edges;
  edges.reserve(kMillion - 1);
  for (int i = 0; i + 1 < kMillion; ++i) edges.push_back({i, i + 1});
  const CompressedDigraph g = compress_edges(kMillion, edges);
  const Components c = strongly_connected_components(g.view());
  ASSERT_EQ(c.count(), kMillion);
  // The deepest node completes first.
  EXPECT_EQ(c.component_of_node[kMillion - 1], 0);
  EXPECT_EQ(c.component_of_node[0], kMillion - 1);
  EXPECT_EQ(largest_component(c), -1);
}

TEST(Scc, MillionNodeChainWithBackEdgeInTheMiddle) {
  // 0 -> 1 -> ... -> n-1, plus (3n/4) -> (n/4): the nodes n/4 .. 3n/4 form one component,
  // found only after unwinding a path of 3n/4 nodes.
  EdgeList edges;
  for (int i = 0; i + 1 < kMillion; ++i) edges.push_back({i, i + 1});
  const int lo = kMillion / 4, hi = 3 * kMillion / 4;
  edges.push_back({hi, lo});
  const CompressedDigraph g = compress_edges(kMillion, edges);
  const Components c = strongly_connected_components(g.view());
  const int largest = largest_component(c);
  ASSERT_GE(largest, 0);
  EXPECT_EQ(c.node_counts[largest], hi - lo + 1);
  EXPECT_EQ(c.first_node[largest], lo);
  EXPECT_EQ(c.component_of_node[lo - 1] == largest, false);
  EXPECT_EQ(c.component_of_node[hi + 1] == largest, false);
  EXPECT_EQ(c.count(), kMillion - (hi - lo));
}

}  // namespace
}  // namespace mg
