#include "motiongraph/synthesis/horizon_search.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <random>

#include "synthesis/search_test_graphs.h"

namespace mg {
namespace {

// Distance to a target point, with a tag penalty; the walk is done once its root has covered
// `goal_arc` metres.
class TargetCost final : public FrameCost {
 public:
  TargetCost(Vec2 target, double goal_arc) : target_(target), goal_arc_(goal_arc) {}
  double cost(int, const Vec2& root, const Vec2& facing, double arc_m, TagMask tags, bool* goal) const override {
    if (arc_m >= goal_arc_) *goal = true;
    return (root - target_).squaredNorm() + 0.1 * (1.0 - facing.x()) + ((tags & 1) != 0 ? 0.0 : 0.05);
  }

 private:
  Vec2 target_;
  double goal_arc_;
};

// Every walk from the start, played frame by frame: the least cost over walks that reach the
// horizon or the goal.
double brute_force(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start, const FrameCost& cost,
                   int horizon) {
  double best = std::numeric_limits<double>::infinity();
  std::function<void(int, FloorTransform, double, Vec2, bool, int, double)> go =
      [&](int node, FloorTransform w, double arc, Vec2 last, bool has_last, int played, double sum) {
        for (int e = graph.edge_offsets[node]; e < graph.edge_offsets[node + 1]; ++e) {
          double total = sum;
          double a = arc;
          Vec2 l = last;
          bool h = has_last;
          bool done = false;
          for (int p = 0; p < tracks.edges[e].count; ++p) {
            const Vec3 r3 = w.apply(Vec3(tracks.roots_of(e)[p].x(), 0.0, tracks.roots_of(e)[p].y()));
            const Vec3 f3 = w.rotate(Vec3(tracks.facings_of(e)[p].x(), 0.0, tracks.facings_of(e)[p].y()));
            const Vec2 root(r3.x(), r3.z());
            if (h) a += (root - l).norm();
            l = root;
            h = true;
            if (played + p < horizon && !done) {
              bool goal = false;
              total += cost.cost(played + p, root, Vec2(f3.x(), f3.z()), a, tracks.tags_of(e)[p], &goal);
              done = goal;
            }
          }
          const int after = played + tracks.edges[e].count;
          if (done || after >= horizon) {
            best = std::min(best, total);
          } else {
            go(graph.edges[e].to_node, w * tracks.edges[e].change, a, l, h, after, total);
          }
        }
      };
  go(start.node, start.placement, start.arc_m, start.last_root, start.has_last, 0, 0.0);
  return best;
}

TEST(HorizonSearch, MatchesBruteForceWithAGenerousBudget) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 40; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 8, 10, 4);
    const EdgeTracks tracks = test::random_tracks(rng, graph);
    SearchState start;
    start.node = static_cast<int>(rng() % 8);
    start.placement = {0.1 * trial, 0.2, -0.3};
    const TargetCost cost(Vec2(0.5, -0.2), trial % 2 == 0 ? 0.6 : 1e9);
    HorizonSettings settings;
    settings.horizon_frames = 14;
    settings.max_expansions = 10'000'000;
    const HorizonResult result = horizon_search(graph, tracks, start, cost, settings);
    ASSERT_FALSE(result.budget_exhausted);
    EXPECT_NEAR(result.cost, brute_force(graph, tracks, start, cost, settings.horizon_frames), 1e-9) << trial;
    // The walk it returns costs what it says.
    Walk walk{start.node, result.edges};
    EXPECT_TRUE(check_walk(graph, walk).ok());
  }
}

TEST(HorizonSearch, AHintChangesTheOrderNotTheAnswer) {
  std::mt19937 rng(4);
  const MotionGraph graph = test::random_search_graph(rng, 8, 12, 3);
  const EdgeTracks tracks = test::random_tracks(rng, graph);
  const TargetCost cost(Vec2(-0.4, 0.3), 1e9);
  HorizonSettings settings;
  settings.horizon_frames = 12;
  const HorizonResult plain = horizon_search(graph, tracks, {}, cost, settings);
  const std::vector<int> hint(plain.edges.begin(), plain.edges.end());
  const HorizonResult hinted = horizon_search(graph, tracks, {}, cost, settings, hint);
  EXPECT_NEAR(plain.cost, hinted.cost, 1e-12);
  EXPECT_LE(hinted.expansions, plain.expansions);  // the best walk first: the tightest bound at once
}

TEST(HorizonSearch, ABudgetStillAnswersWithAWalk) {
  std::mt19937 rng(8);
  const MotionGraph graph = test::random_search_graph(rng, 10, 30, 2);
  const EdgeTracks tracks = test::random_tracks(rng, graph);
  const TargetCost cost(Vec2(1.0, 1.0), 1e9);
  HorizonSettings settings;
  settings.horizon_frames = 40;
  settings.max_expansions = 30;
  const HorizonResult result = horizon_search(graph, tracks, {}, cost, settings);
  EXPECT_TRUE(result.budget_exhausted);
  ASSERT_FALSE(result.edges.empty());
  EXPECT_TRUE(check_walk(graph, Walk{0, result.edges}).ok());
  HorizonSettings bad = settings;
  bad.horizon_frames = 0;
  EXPECT_FALSE(bad.validate().ok());
}

}  // namespace
}  // namespace mg
