#include "motiongraph/synthesis/path_cost.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "synthesis/search_test_graphs.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// Subject 16's graph, a path of short segments asking for walk, run and jump (and stretches
// asking for nothing), searches started anywhere along it (near a segment's end as often as not,
// up to 45 cm off it): every partial walk's bound stays below the least cost of the walks that
// complete it, wherever the segment asked for changes within the horizon, so the branch and
// bound with the path's bounds and its cost-to-go finds the least cost of every walk; without the
// node bound it finds the same and expands more; and the cost-to-go changes the walk chosen.
TEST(PathCost, TheSearchWithTheTagsCostToGoIsExact) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const MotionGraph& graph = *context.graph;
  const double step = context.tracks.max_root_step_m;
  ASSERT_GT(step, 0.0);
  std::mt19937 rng(16);
  const char* tags[] = {"walk", "run", "jump", ""};
  test::BoundTally tally, blind;
  int took_terminal = 0;
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
    PathSynthesisSettings horizon_only_settings = settings;
    horizon_only_settings.tag_lookahead = 0.0;
    PathCost horizon_only(context, *path, masks, horizon_only_settings);
    SearchState start;
    start.node = std::uniform_int_distribution<int>(0, graph.node_count() - 1)(rng);
    start.arc_m = trial % 2 == 0 && !segments.empty()
                      ? std::max(0.0, segments[rng() % segments.size()].to_m -
                                          std::uniform_real_distribution<double>(0.0, 14.0 * step)(rng))
                      : std::uniform_real_distribution<double>(0.0, path->length_m() - 0.5)(rng);
    // The root where the path is at that arc, heading along it, up to 45 cm off it each way.
    std::uniform_real_distribution<double> off(-0.45, 0.45);
    const Vec2 at = path->point_at(start.arc_m) + Vec2(off(rng), off(rng));
    start.placement = context.placement_heading(start.node, at, path->direction_at(start.arc_m));
    cost.start_search(start.arc_m);
    horizon_only.start_search(start.arc_m);
    const std::string what = "trial " + std::to_string(trial);
    const double best = test::expect_search_exact(graph, context.tracks, start, cost, 14, tally, what);
    const double blind_best = test::expect_search_exact(graph, context.tracks, start, horizon_only, 14, blind, what);
    if (best > blind_best + 1e-9) ++took_terminal;
  }
  EXPECT_GT(tally.node_bounded, 100) << tally.partial_walks;  // partial walks checked with a node bound
  EXPECT_GT(tally.cut, 6);  // the node bound cut branches in many searches
  EXPECT_LT(tally.with_bound, tally.without_bound);
  EXPECT_GT(took_terminal, 6);  // the cost-to-go mattered
}

// Where every frame moves the root by the graph's fastest step, the frames a walk surely plays in
// a segment are exactly those it plays there, and a bound counting one too many is caught: random
// graphs whose walks all go east at 5 cm a frame along a straight path cut into segments of
// 0.2-0.7 m asking for tag 1, tag 2 or nothing (an eighth of the frames carry one), searches
// started up to 45 cm beside it (where the bound of the distance from the path adds to it).
TEST(PathCost, TheBoundsHoldAtTheFastestStep) {
  constexpr double kStep = 0.05;
  std::mt19937 rng(5);
  MotionDatabase db;  // the frame rate only
  test::BoundTally tally, blind;
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
        tracks.tags.push_back(static_cast<TagMask>(rng() % 8 == 0 ? 1u << (rng() % 2) : 0));
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
    SearchState start;
    start.node = static_cast<int>(rng() % 9);
    start.arc_m = std::uniform_real_distribution<double>(0.0, 5.0)(rng);
    start.placement = {0.0, start.arc_m, std::uniform_real_distribution<double>(0.0, 0.45)(rng)};
    cost.start_search(start.arc_m);
    horizon_only.start_search(start.arc_m);
    const std::string what = "trial " + std::to_string(trial);
    const double best = test::expect_search_exact(graph, context.tracks, start, cost, 16, tally, what);
    if (best > test::expect_search_exact(graph, context.tracks, start, horizon_only, 16, blind, what) + 1e-9) {
      ++took_terminal;
    }
  }
  EXPECT_GT(tally.node_bounded, 1000) << tally.partial_walks;
  EXPECT_LT(tally.with_bound, tally.without_bound) << tally.with_bound << " " << tally.without_bound;
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
