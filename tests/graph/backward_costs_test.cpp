#include "motiongraph/graph/backward_costs.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "synthesis/search_test_graphs.h"

namespace mg {
namespace {

// Random goals and edge costs, some edges not taken (negative costs): the least costs by relaxing
// every edge taken until nothing changes (Bellman-Ford).
TEST(BackwardCosts, AreTheLeastCostsToAGoalOnRandomGraphs) {
  std::mt19937 rng(5);
  const double far = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 50; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 25, 35, 9);
    std::vector<double> goal(static_cast<size_t>(graph.node_count()), far), edge(graph.edges.size());
    for (double& g : goal) g = rng() % 5 == 0 ? static_cast<double>(rng() % 20) : far;
    for (double& c : edge) c = rng() % 4 == 0 ? -1.0 : 0.5 * static_cast<double>(rng() % 30);
    std::vector<double> want = goal;
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t e = 0; e < graph.edges.size(); ++e) {
        if (edge[e] < 0.0) continue;
        const double via = want[static_cast<size_t>(graph.edges[e].to_node)] + edge[e];
        double& u = want[static_cast<size_t>(graph.edges[e].from_node)];
        if (via < u) {
          u = via;
          changed = true;
        }
      }
    }
    const std::vector<double> got =
        backward_costs(graph, goal, [&](int e) { return edge[static_cast<size_t>(e)]; });
    ASSERT_EQ(got.size(), want.size());
    for (size_t n = 0; n < got.size(); ++n) {
      EXPECT_EQ(got[n], want[n] == far ? -1.0 : want[n]) << "trial " << trial << " node " << n;
    }
  }
}

}  // namespace
}  // namespace mg
