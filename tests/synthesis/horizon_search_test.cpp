#include "motiongraph/synthesis/horizon_search.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <random>

#include "motiongraph/synthesis/tag_distance.h"
#include "synthesis/search_test_graphs.h"
#include "synthesis/subject16_graph.h"

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

// A partial walk played frame by frame, as the search defines it.
struct Played {
  int node = 0;
  FloorTransform w;
  double arc = 0.0;
  Vec2 last = Vec2::Zero();
  bool has_last = false;
  int frames = 0;
  double cost = 0.0;
  bool done = false;  // reached the goal or the horizon
};

Played play(const MotionGraph& graph, const EdgeTracks& tracks, const FrameCost& cost, int horizon, Played s, int e) {
  for (int p = 0; p < tracks.edges[e].count; ++p) {
    const Vec3 r3 = s.w.apply(Vec3(tracks.roots_of(e)[p].x(), 0.0, tracks.roots_of(e)[p].y()));
    const Vec3 f3 = s.w.rotate(Vec3(tracks.facings_of(e)[p].x(), 0.0, tracks.facings_of(e)[p].y()));
    const Vec2 root(r3.x(), r3.z());
    if (s.has_last) s.arc += (root - s.last).norm();
    s.last = root;
    s.has_last = true;
    if (s.frames + p < horizon && !s.done) {
      bool goal = false;
      s.cost += cost.cost(s.frames + p, root, Vec2(f3.x(), f3.z()), s.arc, tracks.tags_of(e)[p], &goal);
      s.done = goal;
    }
  }
  s.frames += tracks.edges[e].count;
  s.done = s.done || s.frames >= horizon;
  s.w = s.w * tracks.edges[e].change;
  s.node = graph.edges[e].to_node;
  return s;
}

Played played_from(const SearchState& start) {
  Played s;
  s.node = start.node;
  s.w = start.placement;
  s.arc = start.arc_m;
  s.last = start.last_root;
  s.has_last = start.has_last;
  return s;
}

// Every walk from the start: the least cost over walks that reach the horizon or the goal.
double brute_force(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start, const FrameCost& cost,
                   int horizon) {
  double best = std::numeric_limits<double>::infinity();
  std::function<void(const Played&)> go = [&](const Played& s) {
    for (int e = graph.edge_offsets[s.node]; e < graph.edge_offsets[s.node + 1]; ++e) {
      const Played next = play(graph, tracks, cost, horizon, s, e);
      if (next.done) {
        best = std::min(best, next.cost);
      } else {
        go(next);
      }
    }
  };
  go(played_from(start));
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
    const double best = brute_force(graph, tracks, start, cost, settings.horizon_frames);
    // A beam first only gives the branch and bound its first bound: the answer stays exact.
    for (int beam : {0, 1, 3}) {
      settings.beam_width = beam;
      const HorizonResult result = horizon_search(graph, tracks, start, cost, settings);
      ASSERT_FALSE(result.budget_exhausted);
      EXPECT_NEAR(result.cost, best, 1e-9) << trial << " beam " << beam;
      // The walk it returns is a walk of the graph and costs what it says.
      EXPECT_TRUE(check_walk(graph, Walk{start.node, result.edges}).ok());
      Played s = played_from(start);
      for (int e : result.edges) s = play(graph, tracks, cost, settings.horizon_frames, s, e);
      EXPECT_TRUE(s.done);
      EXPECT_NEAR(s.cost, result.cost, 1e-9) << trial << " beam " << beam;
    }
  }
}

// A tag asked for with its cost-to-go, as steering prices it: each frame without bit 1 costs 1,
// a walk that reaches the horizon costs 1 for each frame any walk must still play before bit 1
// (the rest of its last edge's, then the distance from where it ends), and a partial walk is
// bounded below by its node's distance.
class TagToGoCost final : public FrameCost {
 public:
  TagToGoCost(const EdgeTracks& tracks, const std::vector<double>& to_tag) : tracks_(tracks), to_tag_(to_tag) {}
  double cost(int, const Vec2&, const Vec2& facing, double, TagMask tags, bool*) const override {
    return 0.2 * (1.0 - facing.x()) + ((tags & 2) != 0 ? 0.0 : 1.0);
  }
  double terminal_cost(int edge, size_t costed, double, const SearchState& end) const override {
    const auto rest = tracks_.tags_of(edge).subspan(costed);
    for (size_t f = 0; f < rest.size(); ++f) {
      if ((rest[f] & 2) != 0) return static_cast<double>(f);
    }
    const double d = to_tag_[static_cast<size_t>(end.node)];
    return d < 0.0 ? 0.0 : static_cast<double>(rest.size()) + d;
  }
  double node_bound(const SearchState& state, int) const override {
    return std::max(0.0, to_tag_[static_cast<size_t>(state.node)]);
  }

 private:
  const EdgeTracks& tracks_;
  const std::vector<double>& to_tag_;
};

TEST(HorizonSearch, ACostToGoAndItsBoundKeepTheSearchExact) {
  std::mt19937 rng(33);
  int took_terminal = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 9, 12, 5);
    EdgeTracks tracks = test::random_tracks(rng, graph);
    for (TagMask& t : tracks.tags) t = (rng() % 6 == 0) ? TagMask{2} : TagMask{0};
    const std::vector<double> to_tag = cost_to_tag(graph, tracks, 2, 1.0);
    SearchState start;
    start.node = static_cast<int>(rng() % 9);
    const TagToGoCost cost(tracks, to_tag);
    HorizonSettings settings;
    settings.horizon_frames = 8;
    settings.max_expansions = 10'000'000;
    // Every walk played out, its terminal cost added where it reaches the horizon.
    double best = std::numeric_limits<double>::infinity();
    std::function<void(const Played&)> go = [&](const Played& s) {
      for (int e = graph.edge_offsets[s.node]; e < graph.edge_offsets[s.node + 1]; ++e) {
        const Played next = play(graph, tracks, cost, settings.horizon_frames, s, e);
        if (!next.done) {
          go(next);
          continue;
        }
        const size_t costed = static_cast<size_t>(settings.horizon_frames - s.frames);
        SearchState end;
        end.node = next.node;
        best = std::min(best, next.cost + cost.terminal_cost(e, costed, 0.0, end));
      }
    };
    go(played_from(start));
    double without = std::numeric_limits<double>::infinity();
    for (int beam : {0, 2}) {
      settings.beam_width = beam;
      const HorizonResult result = horizon_search(graph, tracks, start, cost, settings);
      ASSERT_FALSE(result.budget_exhausted);
      EXPECT_NEAR(result.cost, best, 1e-9) << trial << " beam " << beam;
    }
    without = brute_force(graph, tracks, start, cost, settings.horizon_frames);
    if (best > without + 1e-9) ++took_terminal;
  }
  EXPECT_GT(took_terminal, 10);  // the cost-to-go mattered in many trials
}

// A cost that judges headings (FrameCost::uses_heading) is given each frame's heading where the
// facing would be: the search equals the brute force over tracks whose facings are the headings,
// and differs from the one over the facings.
TEST(HorizonSearch, ACostJudgingHeadingsIsGivenThem) {
  class HeadingCost final : public FrameCost {
   public:
    bool uses_heading() const override { return true; }
    double cost(int, const Vec2&, const Vec2& facing, double, TagMask, bool*) const override {
      return 1.0 - facing.x();  // east
    }
  } cost;
  std::mt19937 rng(8);
  int differ = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 8, 10, 4);
    EdgeTracks tracks = test::random_tracks(rng, graph);
    std::uniform_real_distribution<double> angle(-0.7, 0.7);
    for (const Vec2& f : tracks.facings) tracks.headings.push_back(turn(FloorTransform{angle(rng), 0.0, 0.0}, f));
    EdgeTracks as_headings = tracks;
    as_headings.facings = tracks.headings;
    SearchState start;
    start.node = static_cast<int>(rng() % 8);
    start.placement = {0.3 * trial, 0.1, 0.4};
    HorizonSettings settings;
    settings.horizon_frames = 12;
    settings.max_expansions = 10'000'000;
    const double judged = brute_force(graph, as_headings, start, cost, settings.horizon_frames);
    for (int beam : {0, 2}) {
      settings.beam_width = beam;
      const HorizonResult result = horizon_search(graph, tracks, start, cost, settings);
      ASSERT_FALSE(result.budget_exhausted);
      EXPECT_NEAR(result.cost, judged, 1e-9) << trial << " beam " << beam;
    }
    if (std::abs(brute_force(graph, tracks, start, cost, settings.horizon_frames) - judged) > 1e-6) ++differ;
  }
  EXPECT_GT(differ, 20);
}

// With no budget left for the depth-first search, the answer is the beam's: a complete walk
// (the budgeted depth-first search alone may have none) that costs what it says.
TEST(HorizonSearch, TheBeamAloneAnswersWithACompleteWalk) {
  std::mt19937 rng(33);
  for (int trial = 0; trial < 20; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 12, 40, 4);
    const EdgeTracks tracks = test::random_tracks(rng, graph);
    const TargetCost cost(Vec2(0.8, -0.5), 1e9);
    HorizonSettings settings;
    settings.horizon_frames = 30;
    settings.max_expansions = 1;
    settings.beam_width = 8;
    const HorizonResult beam = horizon_search(graph, tracks, {}, cost, settings);
    ASSERT_TRUE(check_walk(graph, Walk{0, beam.edges}).ok());
    Played s = played_from({});
    for (int e : beam.edges) s = play(graph, tracks, cost, settings.horizon_frames, s, e);
    EXPECT_TRUE(s.done) << trial;
    EXPECT_NEAR(s.cost, beam.cost, 1e-9) << trial;
  }
  HorizonSettings bad;
  bad.beam_width = -1;
  EXPECT_FALSE(bad.validate().ok());
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

// walk_facings against the motion the assembler plays for the same edges (subject 16's graph,
// random walks through its transitions, started anywhere on the floor): the facing of every frame.
TEST(HorizonSearch, WalkFacingsAreThoseOfTheMotionPlayed) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const MotionGraph& graph = *context.graph;
  std::mt19937 rng(3);
  int transitions = 0;
  for (int trial = 0; trial < 20; ++trial) {
    SearchState state;
    state.node = std::uniform_int_distribution<int>(0, graph.node_count() - 1)(rng);
    state.placement = {std::uniform_real_distribution<double>(-3.0, 3.0)(rng), 1.5 * trial, -0.7 * trial};
    std::vector<int> edges;
    for (int node = state.node; edges.size() < 8;) {
      const int e = std::uniform_int_distribution<int>(graph.edge_offsets[node], graph.edge_offsets[node + 1] - 1)(rng);
      edges.push_back(e);
      transitions += graph.edges[e].transition ? 1 : 0;
      node = graph.edges[e].to_node;
    }
    Motion motion = context.assembler.empty_motion();
    FloorTransform placement = state.placement;
    for (int e : edges) context.assembler.append_edge(e, placement, motion);
    const std::vector<Vec2> all = walk_facings(graph, context.tracks, state, edges, static_cast<size_t>(1) << 30);
    ASSERT_EQ(static_cast<int>(all.size()), motion.frame_count);
    for (int f = 0; f < motion.frame_count; ++f) {
      // The graph file keeps rotations in single precision, unit to float precision (the fixture's,
      // under ctest), which the roots-only play and the whole poses round differently.
      EXPECT_LT((all[f] - facing_on_floor(motion.rotations(f)[0], context.tracks.forward_axis)).norm(), 1e-6) << f;
    }
    const std::vector<Vec2> some = walk_facings(graph, context.tracks, state, edges, 7);
    ASSERT_EQ(some.size(), 7u);
    for (size_t f = 0; f < some.size(); ++f) EXPECT_EQ(some[f], all[f]);
  }
  EXPECT_GT(transitions, 20);  // placed by their alignments
}

}  // namespace
}  // namespace mg
