#include "motiongraph/synthesis/path_cost.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "synthesis/search_test_graphs.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// Every walk from `start` played out as horizon_search plays it, priced through the FrameCost
// interface: a transition's cost when it starts within the horizon, each frame's cost within it,
// and the terminal cost of a walk that reaches the horizon without reaching the goal. The least.
double every_walk(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start, const FrameCost& cost,
                  int horizon) {
  double best = std::numeric_limits<double>::infinity();
  std::function<void(const SearchState&, double)> go = [&](const SearchState& from, double paid) {
    for (int e = graph.edge_offsets[from.node]; e < graph.edge_offsets[from.node + 1]; ++e) {
      double total = paid;
      if (graph.edges[e].transition) total += cost.transition_cost(graph.edges[e], from);
      SearchState s = from;
      bool goal = false;
      size_t costed = 0;
      double horizon_arc = 0.0;
      const auto roots = tracks.roots_of(e);
      for (size_t p = 0; p < roots.size(); ++p) {
        const Vec3 r = s.placement.apply(Vec3(roots[p].x(), 0.0, roots[p].y()));
        const Vec2 root(r.x(), r.z());
        if (s.has_last) s.arc_m += (root - s.last_root).norm();
        s.last_root = root;
        s.has_last = true;
        if (s.frames + static_cast<long long>(p) < horizon && !goal) {
          total += cost.cost(static_cast<int>(s.frames + static_cast<long long>(p)), root, Vec2::UnitX(), s.arc_m,
                             tracks.tags_of(e)[p], &goal);
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
        go(s, total);
      }
    }
  };
  go(start, 0.0);
  return best;
}

// The same cost without its node bound: the search is as exact, and only its pruning differs.
class WithoutNodeBound final : public FrameCost {
 public:
  explicit WithoutNodeBound(const FrameCost& cost) : cost_(cost) {}
  double cost(int frame, const Vec2& root, const Vec2& facing, double arc_m, TagMask tags, bool* goal) const override {
    return cost_.cost(frame, root, facing, arc_m, tags, goal);
  }
  bool add_costs(const PlayedFrames& frames, double bound, double* total, bool* goal) const override {
    return cost_.add_costs(frames, bound, total, goal);
  }
  bool uses_facing() const override { return cost_.uses_facing(); }
  double remaining_bound(int frames_left, const Vec2& root, double arc_m) const override {
    return cost_.remaining_bound(frames_left, root, arc_m);
  }
  double transition_cost(const GraphEdge& edge, const SearchState& from) const override {
    return cost_.transition_cost(edge, from);
  }
  double terminal_cost(int edge, size_t costed, double horizon_arc_m, const SearchState& end) const override {
    return cost_.terminal_cost(edge, costed, horizon_arc_m, end);
  }

 private:
  const FrameCost& cost_;
};

// Subject 16's graph, a path of short segments asking for walk, run and jump (and stretches
// asking for nothing), searches started anywhere along it, near a segment's end as often as not:
// the branch and bound with the path's bounds and its cost-to-go finds the least cost of every
// walk (the bounds stay below every walk's cost, wherever the segment asked for changes within
// the horizon); without the node bound it finds the same and expands more; and the cost-to-go
// changes the walk chosen.
TEST(PathCost, TheSearchWithTheTagsCostToGoIsExact) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const MotionGraph& graph = *context.graph;
  const double step = context.tracks.max_root_step_m;
  ASSERT_GT(step, 0.0);
  std::mt19937 rng(16);
  const char* tags[] = {"walk", "run", "jump", ""};
  long long with_bound = 0, without_bound = 0;
  int bound_cut = 0, took_terminal = 0, trials = 0;
  for (int trial = 0; trial < 24; ++trial) {
    // An s-curve of 6 m cut into pieces of 0.4-1.2 m, each asking for one of the tags or none.
    auto shape = make_shape("s-curve:6");
    ASSERT_TRUE(shape.ok());
    std::vector<PathSegment> segments;
    for (double from = 0.0; from < shape->length_m();) {
      const double to = from + std::uniform_real_distribution<double>(0.4, 1.2)(rng);
      const char* tag = tags[rng() % 4];
      if (*tag != '\0') segments.push_back({from, to, tag});
      from = to;
    }
    auto path = FloorPath::create(shape->points(), segments);
    ASSERT_TRUE(path.ok());
    std::vector<TagMask> masks;
    for (const PathSegment& segment : path->segments()) masks.push_back(*context.tag_mask(segment.tag));
    PathSynthesisSettings settings;
    settings.tag_lookahead = trial % 3 == 0 ? 1.0 : 0.5;
    settings.tag_penalty_m2 = trial % 2 == 0 ? 1.0 : 0.1;
    PathCost cost(context, *path, masks, settings);
    PathSynthesisSettings blind = settings;
    blind.tag_lookahead = 0.0;
    PathCost horizon_only(context, *path, masks, blind);
    const WithoutNodeBound unbounded(cost);

    SearchState start;
    start.node = std::uniform_int_distribution<int>(0, graph.node_count() - 1)(rng);
    start.arc_m = trial % 2 == 0 && !segments.empty()
                      ? std::max(0.0, segments[rng() % segments.size()].to_m -
                                          std::uniform_real_distribution<double>(0.0, 14.0 * step)(rng))
                      : std::uniform_real_distribution<double>(0.0, path->length_m() - 0.5)(rng);
    // The root where the path is at that arc, heading along it, give or take a few centimetres.
    const Vec2 at = path->point_at(start.arc_m) + Vec2(0.05 * (trial % 3) - 0.05, 0.03);
    start.placement = context.placement_heading(start.node, at, path->direction_at(start.arc_m));
    HorizonSettings search;
    search.horizon_frames = 14;
    search.max_expansions = 100'000'000;
    cost.start_search(start.arc_m);
    horizon_only.start_search(start.arc_m);
    const double best = every_walk(graph, context.tracks, start, cost, search.horizon_frames);
    ASSERT_TRUE(std::isfinite(best));
    for (int beam : {0, 4}) {
      search.beam_width = beam;
      const HorizonResult found = horizon_search(graph, context.tracks, start, cost, search);
      ASSERT_FALSE(found.budget_exhausted);
      EXPECT_NEAR(found.cost, best, 1e-9 * std::max(1.0, best)) << "trial " << trial << " beam " << beam;
      const HorizonResult plain = horizon_search(graph, context.tracks, start, unbounded, search);
      EXPECT_NEAR(plain.cost, best, 1e-9 * std::max(1.0, best)) << "trial " << trial << " beam " << beam;
      if (beam == 0) {
        with_bound += found.expansions;
        without_bound += plain.expansions;
        bound_cut += found.expansions < plain.expansions ? 1 : 0;
        EXPECT_LE(found.expansions, plain.expansions) << "trial " << trial;
      }
    }
    const double blind_best = every_walk(graph, context.tracks, start, horizon_only, search.horizon_frames);
    search.beam_width = 0;
    EXPECT_NEAR(horizon_search(graph, context.tracks, start, horizon_only, search).cost, blind_best,
                1e-9 * std::max(1.0, blind_best));
    if (best > blind_best + 1e-9) ++took_terminal;
    ++trials;
  }
  EXPECT_EQ(trials, 24);
  EXPECT_GT(bound_cut, 6);           // the node bound cut branches in many searches
  EXPECT_LT(with_bound, without_bound);
  EXPECT_GT(took_terminal, 6);       // the cost-to-go mattered
}

// Where every frame moves the root by the graph's fastest step, the frames a walk surely plays in
// a segment are exactly those it plays there, and a bound counting one too many is caught: random
// graphs whose walks all go east at 5 cm a frame along a straight path cut into segments of
// 0.2-0.7 m asking for tag 1, tag 2 or nothing, searches started a few centimetres beside it.
TEST(PathCost, TheBoundsHoldAtTheFastestStep) {
  constexpr double kStep = 0.05;
  std::mt19937 rng(5);
  MotionDatabase db;  // the frame rate only
  long long with_bound = 0, without_bound = 0;
  int took_terminal = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const MotionGraph graph = test::random_search_graph(rng, 9, 14, 5);
    EdgeTracks tracks;
    for (const GraphEdge& edge : graph.edges) {
      EdgeTrack track;
      track.first = static_cast<int>(tracks.roots.size());
      track.count = edge.frame_count;
      for (int p = 0; p < edge.frame_count; ++p) {
        tracks.roots.emplace_back(kStep * p, 0.0);
        tracks.facings.emplace_back(1.0, 0.0);
        tracks.tags.push_back(static_cast<TagMask>(rng() % 4 == 0 ? 0 : 1u << (rng() % 2)));
      }
      track.change = {0.0, kStep * edge.frame_count, 0.0};
      tracks.edges.push_back(track);
    }
    tracks.max_root_step_m = kStep;
    SynthesisContext context;
    context.db = &db;
    context.graph = &graph;
    context.tracks = std::move(tracks);
    std::vector<PathSegment> segments;
    std::vector<TagMask> masks;
    for (double from = 0.0; from < 6.0;) {
      const double to = from + std::uniform_real_distribution<double>(0.2, 0.7)(rng);
      const int tag = static_cast<int>(rng() % 3);
      if (tag > 0) {
        segments.push_back({from, to, tag == 1 ? "one" : "two"});
        masks.push_back(static_cast<TagMask>(tag));
      }
      from = to;
    }
    auto path = FloorPath::create({{0.0, 0.0}, {6.0, 0.0}}, segments);
    ASSERT_TRUE(path.ok());
    PathSynthesisSettings settings;
    settings.tag_lookahead = trial % 2 == 0 ? 1.0 : 0.5;
    settings.transition_penalty_m2 = trial % 3 == 0 ? 0.0 : 0.3;
    PathCost cost(context, *path, masks, settings);
    settings.tag_lookahead = 0.0;
    PathCost horizon_only(context, *path, masks, settings);
    const WithoutNodeBound unbounded(cost);
    SearchState start;
    start.node = static_cast<int>(rng() % 9);
    start.arc_m = std::uniform_real_distribution<double>(0.0, 5.0)(rng);
    start.placement = {0.0, start.arc_m, 0.02 * (trial % 4)};
    cost.start_search(start.arc_m);
    horizon_only.start_search(start.arc_m);
    HorizonSettings search;
    search.horizon_frames = 16;
    search.max_expansions = 100'000'000;
    const double best = every_walk(graph, context.tracks, start, cost, search.horizon_frames);
    for (int beam : {0, 3}) {
      search.beam_width = beam;
      const HorizonResult found = horizon_search(graph, context.tracks, start, cost, search);
      ASSERT_FALSE(found.budget_exhausted);
      EXPECT_NEAR(found.cost, best, 1e-9 * std::max(1.0, best)) << "trial " << trial << " beam " << beam;
      if (beam == 0) {
        with_bound += found.expansions;
        without_bound += horizon_search(graph, context.tracks, start, unbounded, search).expansions;
      }
    }
    if (best > every_walk(graph, context.tracks, start, horizon_only, search.horizon_frames) + 1e-9) ++took_terminal;
  }
  EXPECT_LT(with_bound, without_bound) << with_bound << " " << without_bound;
  EXPECT_GT(took_terminal, 5) << took_terminal;
}

TEST(PathCost, TheLookaheadIsFromZeroToOne) {
  PathSynthesisSettings settings;
  EXPECT_TRUE(settings.validate().ok());
  for (double bad : {-0.1, 1.5, std::nan("")}) {
    settings.tag_lookahead = bad;
    EXPECT_FALSE(settings.validate().ok()) << bad;
  }
  settings.tag_lookahead = 0.0;
  EXPECT_TRUE(settings.validate().ok());
}

}  // namespace
}  // namespace mg
