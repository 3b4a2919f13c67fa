#include "motiongraph/synthesis/walk_search.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "synthesis/search_test_graphs.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// The cheapest cost to reach (to, >= min_frames) by relaxing every state until nothing
// changes: an independent brute force over the same state space.
double brute_force_cost(const MotionGraph& graph, const std::vector<double>& costs, int from, int to, int min_frames) {
  const double inf = std::numeric_limits<double>::infinity();
  const int levels = min_frames + 1;
  std::vector<double> best(static_cast<size_t>(graph.node_count()) * levels, inf);
  best[static_cast<size_t>(from) * levels] = 0.0;
  for (bool changed = true; changed;) {
    changed = false;
    for (int n = 0; n < graph.node_count(); ++n) {
      for (int f = 0; f < levels; ++f) {
        const double here = best[static_cast<size_t>(n) * levels + f];
        if (here == inf) continue;
        for (int e = graph.edge_offsets[n]; e < graph.edge_offsets[n + 1]; ++e) {
          const int g = std::min(min_frames, f + graph.edges[e].frame_count);
          double& there = best[static_cast<size_t>(graph.edges[e].to_node) * levels + g];
          if (here + costs[e] < there - 1e-12) {
            there = here + costs[e];
            changed = true;
          }
        }
      }
    }
  }
  return best[static_cast<size_t>(to) * levels + min_frames];
}

TEST(WalkSearch, FindsTheCheapestWalkOfEveryCostOnRandomGraphs) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 60; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 12, 25, 6);
    WalkSearchSettings settings;
    settings.cost = static_cast<WalkCost>(trial % 4);
    settings.seed = trial;
    settings.min_frames = static_cast<int>(rng() % 40);
    const int from = static_cast<int>(rng() % 12), to = static_cast<int>(rng() % 12);
    auto found = find_walk(graph, from, to, settings);
    ASSERT_TRUE(found.ok()) << found.error().to_string();
    ASSERT_TRUE(check_walk(graph, found->walk).ok());
    EXPECT_EQ(found->walk.start_node, from);
    EXPECT_EQ(found->walk.end_node(graph), to);
    EXPECT_GE(found->walk.frame_count(graph), settings.min_frames);
    const std::vector<double> costs = walk_edge_costs(graph, settings);
    double sum = 0.0;
    for (int e : found->walk.edges) sum += costs[e];
    EXPECT_NEAR(found->cost, sum, 1e-9);
    EXPECT_NEAR(found->cost, brute_force_cost(graph, costs, from, to, settings.min_frames), 1e-9)
        << walk_cost_name(settings.cost) << " trial " << trial;
  }
}

TEST(WalkSearch, CostsFollowTheirDefinitions) {
  std::mt19937 rng(5);
  const MotionGraph graph = test::random_search_graph(rng, 10, 30, 4);
  WalkSearchSettings settings;
  settings.seed = 9;
  settings.cost = WalkCost::kRandom;
  const auto random = walk_edge_costs(graph, settings);
  settings.cost = WalkCost::kHybrid;
  const auto hybrid = walk_edge_costs(graph, settings);
  settings.cost = WalkCost::kQuality;
  const auto quality = walk_edge_costs(graph, settings);
  for (int e = 0; e < graph.edge_count(); ++e) {
    EXPECT_GT(random[e], 0.0);
    EXPECT_LE(random[e], 1.0);
    const GraphEdge& edge = graph.edges[e];
    EXPECT_DOUBLE_EQ(quality[e], edge.transition ? graph.transitions[edge.transition_index].distance : 0.0);
    EXPECT_NEAR(hybrid[e], random[e] * quality[e], 1e-12);  // same seed, same draws
  }
  settings.seed = 10;
  settings.cost = WalkCost::kRandom;
  EXPECT_NE(walk_edge_costs(graph, settings), random);
}

TEST(WalkSearch, BudgetAndBadNodesAreClearErrors) {
  const auto& graph = test::subject16().file().graph;
  WalkSearchSettings settings;
  settings.min_frames = 3000;
  settings.max_expansions = 50;
  auto found = find_walk(graph, 0, 5, settings);
  ASSERT_FALSE(found.ok());
  EXPECT_NE(found.error().message.find("budget of 50 expansions"), std::string::npos);
  EXPECT_FALSE(find_walk(graph, -1, 5, {}).ok());
  EXPECT_FALSE(find_walk(graph, 0, graph.node_count(), {}).ok());
  EXPECT_FALSE(parse_walk_cost("cheap").ok());
}

TEST(WalkSearch, StopsWhenAsked) {
  const auto& graph = test::subject16().file().graph;
  WalkSearchSettings settings;
  settings.min_frames = 600;
  std::stop_source stop;
  settings.stop = stop.get_token();
  ASSERT_TRUE(find_walk(graph, 3, graph.node_count() - 4, settings).ok());  // not asked: found
  stop.request_stop();
  auto found = find_walk(graph, 3, graph.node_count() - 4, settings);
  ASSERT_FALSE(found.ok());
  EXPECT_EQ(found.error().kind, ErrorKind::kStopped);
}

TEST(WalkSearch, LongWalksOnTheBundledGraph) {
  const auto& graph = test::subject16().file().graph;
  WalkSearchSettings settings;
  settings.min_frames = 600;
  for (WalkCost cost : {WalkCost::kConstant, WalkCost::kQuality, WalkCost::kRandom, WalkCost::kHybrid}) {
    settings.cost = cost;
    auto found = find_walk(graph, 3, graph.node_count() - 4, settings);
    ASSERT_TRUE(found.ok()) << found.error().to_string();
    EXPECT_GE(found->walk.frame_count(graph), 600);
    EXPECT_TRUE(check_walk(graph, found->walk).ok());
  }
}

}  // namespace
}  // namespace mg
