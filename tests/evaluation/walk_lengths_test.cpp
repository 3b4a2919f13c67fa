// Walk lengths per cost on a graph of bundled clips: every walk valid and between its nodes,
// the same node pairs for every cost, constant cost giving the fewest edges, and the same
// samples from the same seed.
#include "motiongraph/evaluation/walk_lengths.h"

#include <gtest/gtest.h>

#include "motiongraph/graph/graph_from_candidates.h"
#include "test_data.h"

namespace mg {
namespace {

const MotionGraph& walking_graph() {
  static const MotionGraph graph = [] {
    const MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_17.amc"});
    DistanceSettings distance;
    distance.threads = 2;
    auto layout = make_cloud_layout(db.skeletons[0], {});
    const FrameFeatures features = *make_frame_features(db, *layout, distance);
    const CandidateSearch candidates = *find_candidates(features, distance, {});
    GraphFromCandidatesSettings settings;
    settings.transitions.threshold_quantile = 0.05;
    return std::move(graph_from_candidates(db, features, candidates, settings)->pruned.graph);
  }();
  return graph;
}

TEST(WalkLengths, ValidWalksBetweenTheSameNodePairsForEveryCost) {
  const MotionGraph& graph = walking_graph();
  ASSERT_GE(graph.node_count(), 2);
  const std::vector<WalkCost> costs = {WalkCost::kConstant, WalkCost::kQuality, WalkCost::kRandom, WalkCost::kHybrid};
  WalkLengthSettings settings;
  settings.walks = 20;
  settings.seed = 7;
  auto samples = sample_walk_lengths(graph, costs, settings);
  ASSERT_TRUE(samples) << samples.error().to_string();
  ASSERT_EQ(samples->size(), costs.size() * 20);
  for (size_t i = 0; i < samples->size(); ++i) {
    const WalkLengthSample& s = (*samples)[i];
    EXPECT_EQ(s.cost, costs[i / 20]);
    EXPECT_EQ(s.index, static_cast<int>(i % 20));
    const WalkLengthSample& first = (*samples)[i % 20];
    EXPECT_EQ(s.from, first.from);
    EXPECT_EQ(s.to, first.to);
    EXPECT_NE(s.from, s.to);
    // The pruned graph is strongly connected and the budget ample: every walk is found.
    ASSERT_TRUE(s.found) << s.failure;
    EXPECT_TRUE(check_walk(graph, s.walk));
    EXPECT_EQ(s.walk.start_node, s.from);
    EXPECT_EQ(s.walk.end_node(graph), s.to);
    EXPECT_EQ(s.frames, s.walk.frame_count(graph));
    EXPECT_GT(s.frames, 0);
    EXPECT_GE(s.cost_value, 0.0);
    // Constant cost counts edges: no other cost finds a walk with fewer.
    EXPECT_GE(s.walk.edges.size(), first.walk.edges.size());
    if (s.cost == WalkCost::kConstant) {
      EXPECT_DOUBLE_EQ(s.cost_value, static_cast<double>(s.walk.edges.size()));
    }
  }
  auto again = sample_walk_lengths(graph, costs, settings);
  ASSERT_TRUE(again);
  for (size_t i = 0; i < samples->size(); ++i) EXPECT_EQ((*again)[i].walk.edges, (*samples)[i].walk.edges);
}

TEST(WalkLengths, SettingsAndGraphChecked) {
  const std::vector<WalkCost> costs = {WalkCost::kConstant};
  WalkLengthSettings none;
  none.walks = 0;
  EXPECT_FALSE(sample_walk_lengths(walking_graph(), costs, none));
  EXPECT_FALSE(sample_walk_lengths(MotionGraph{}, costs, {}));
}

}  // namespace
}  // namespace mg
