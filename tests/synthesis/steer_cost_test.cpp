#include "motiongraph/synthesis/steer_cost.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "motiongraph/synthesis/travelling_frames.h"
#include "synthesis/search_test_graphs.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// Subject 16's graph, decisions started anywhere facing anywhere, asked for walk, run, jump or
// no tag, judging facings or (holding the travel) headings: every partial walk's node bound stays
// below the least cost of the walks that complete it, and the branch and bound with the steering
// cost, its cost-to-go and its node bound finds the least cost of every walk; without
// the node bound it finds the same and expands more; and the cost-to-go changes the walk chosen.
TEST(SteerCost, TheSearchWithTheTagsCostToGoIsExact) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const MotionGraph& graph = *context.graph;
  std::mt19937 rng(61);
  const char* tags[] = {"walk", "run", "jump", ""};
  test::BoundTally tally, blind_tally;
  int took_terminal = 0, took_travel_terminal = 0;
  for (int trial = 0; trial < 24; ++trial) {
    ControlInput input;
    const double bearing = std::uniform_real_distribution<double>(0.0, 360.0)(rng);
    input.direction = bearing_direction(bearing);
    const char* tag = tags[trial % 4];
    input.tag = *tag == '\0' ? TagMask{0} : *context.tag_mask(tag);
    ControllerSettings settings;
    settings.tag_lookahead = trial % 3 == 0 ? 1.0 : 0.5;
    settings.heading_edit.hold_travel = trial % 2 == 1;
    SearchState start;
    start.node = std::uniform_int_distribution<int>(0, graph.node_count() - 1)(rng);
    if (input.tag == 0) {
      // With no tag, from a node further from frames that travel than the horizon reaches (a jump
      // on the spot, a stop), where what lies past it matters.
      const double per_frame = settings.travel_penalty * settings.travel_mps;
      const TravelCosts to_travel = searched_costs_to_travel(context, settings.travel_mps, per_frame,
                                                             settings.transition_penalty, settings.bridge_penalty);
      for (int tried = 0; (*to_travel.to_travel)[static_cast<size_t>(start.node)] < 20 * per_frame; ++tried) {
        ASSERT_LT(tried, graph.node_count()) << "no node 20 frames from travelling frames";
        start.node = (start.node + 1) % graph.node_count();
      }
    }
    start.placement = context.placement_facing(start.node, Vec2(0.3 * trial, -0.2 * trial),
                                               bearing_direction(std::uniform_real_distribution<double>(0, 360)(rng)));
    const Vec3 root = context.assembler.root_position(graph.nodes[static_cast<size_t>(start.node)].frame,
                                                      start.placement);
    start.last_root = Vec2(root.x(), root.z());
    start.has_last = true;
    const SteerCost cost(context, input, settings);
    ControllerSettings blind = settings;
    blind.tag_lookahead = 0.0;
    const SteerCost horizon_only(context, input, blind);
    EXPECT_EQ(cost.uses_heading(), settings.heading_edit.hold_travel);
    const std::string what = "trial " + std::to_string(trial);
    // With no tag, the pace asked along the heading too (a cost of every frame's root).
    // Past the horizon, what any walk from there still pays before a frame that travels at the
    // pace (travelling_frames.h).
    if (input.tag == 0) {
      const SteerCost travelling(context, input, settings, &start);
      const double with_travel = test::expect_search_exact(graph, context.tracks, start, travelling, 14, tally, what);
      EXPECT_GE(with_travel, test::expect_search_exact(graph, context.tracks, start, cost, 14, tally, what) - 1e-12);
      const SteerCost travelling_blind(context, input, blind, &start);
      const double horizon_travel =
          test::expect_search_exact(graph, context.tracks, start, travelling_blind, 14, blind_tally, what);
      EXPECT_GE(with_travel, horizon_travel - 1e-12);
      if (with_travel > horizon_travel + 1e-9) ++took_travel_terminal;
    }
    const double best = test::expect_search_exact(graph, context.tracks, start, cost, 14, tally, what);
    const double blind_best =
        test::expect_search_exact(graph, context.tracks, start, horizon_only, 14, blind_tally, what);
    if (best > blind_best + 1e-9) ++took_terminal;
    if (input.tag == 0) {
      EXPECT_NEAR(best, blind_best, 1e-12);  // no tag, nothing to look for
    }
  }
  EXPECT_GT(tally.node_bounded, 150) << tally.partial_walks;
  EXPECT_LT(tally.with_bound, tally.without_bound) << tally.with_bound << " " << tally.without_bound;
  EXPECT_GT(took_terminal, 6) << took_terminal;
  EXPECT_GE(took_travel_terminal, 2) << took_travel_terminal;
}

// With no motion type asked, a frame also pays travel_penalty per metre its root is behind a
// point that leaves the decision's start at travel_mps along the heading; ahead of it, nothing.
// Not with a tag asked, nor without a start, nor with travel_mps 0.
TEST(SteerCost, WithNoTagAFrameBehindThePaceAskedPaysPerMetreBehind) {
  const SynthesisContext& context = test::subject16().context();
  const double fps = context.db->fps;
  ControlInput input;
  input.direction = bearing_direction(90.0);  // east, +x
  ControllerSettings settings;
  SearchState from;
  from.last_root = Vec2(2.0, 3.0);
  from.has_last = true;
  const SteerCost cost(context, input, settings, &from);
  const Vec2 facing = input.direction;
  auto frame_cost = [&](const SteerCost& c, int frame, double east_m) {
    return c.cost(frame, from.last_root + Vec2(east_m, 0.7), facing, 0.0, 0, nullptr);
  };
  const int frame = 29;  // its 30th frame: the pace has gone travel_mps * 1 s
  const double pace_m = settings.travel_mps * (frame + 1) / fps;
  EXPECT_NEAR(frame_cost(cost, frame, pace_m), 0.0, 1e-12);
  EXPECT_NEAR(frame_cost(cost, frame, pace_m + 0.4), 0.0, 1e-12);
  EXPECT_NEAR(frame_cost(cost, frame, pace_m - 0.25), settings.travel_penalty * 0.25, 1e-12);
  EXPECT_NEAR(frame_cost(cost, frame, -1.0), settings.travel_penalty * (pace_m + 1.0), 1e-12);
  const SteerCost no_start(context, input, settings);
  EXPECT_EQ(frame_cost(no_start, frame, -1.0), 0.0);
  ControllerSettings still = settings;
  still.travel_mps = 0.0;
  EXPECT_EQ(frame_cost(SteerCost(context, input, still, &from), frame, -1.0), 0.0);
  ControlInput walk = input;
  walk.tag = *context.tag_mask("walk");
  const SteerCost tagged(context, walk, settings, &from);
  EXPECT_EQ(tagged.cost(frame, from.last_root - Vec2(1.0, 0.0), facing, 0.0, walk.tag, nullptr), 0.0);
}

// Asked for no tag, a walk that reaches the horizon in edge e after `costed` of its frames pays
// tag_lookahead times, for each later frame of e before one that travels, a second behind the pace
// (travel_penalty * travel_mps), and, when none of them travels, the cost-to-go of e's end node;
// counted here from the marks of the edges' own frames.
TEST(SteerCost, PastTheHorizonAWalkWithNoTagPaysForTheFramesBeforeOneThatTravels) {
  const SynthesisContext& context = test::subject16().context();
  const MotionGraph& graph = *context.graph;
  ControllerSettings settings;
  settings.tag_lookahead = 0.75;
  ControlInput input;
  input.direction = bearing_direction(30.0);
  SearchState from;
  from.has_last = true;
  const SteerCost cost(context, input, settings, &from);
  const double per_frame = settings.travel_penalty * settings.travel_mps;
  const TravelCosts travel = searched_costs_to_travel(context, settings.travel_mps, per_frame,
                                                      settings.transition_penalty, settings.bridge_penalty);
  int paid_in_edge = 0, paid_beyond = 0;
  for (int e = 0; e < graph.edge_count(); ++e) {
    const EdgeTrack& track = context.tracks.edges[static_cast<size_t>(e)];
    for (int costed = 1; costed <= track.count; costed += std::max(1, track.count / 3)) {
      double want = 0.0;
      int f = costed;
      while (f < track.count && (*travel.marks)[static_cast<size_t>(track.first + f)] != kTravellingMark) ++f;
      want = per_frame * (f - costed);
      const int end = graph.edges[static_cast<size_t>(e)].to_node;
      if (f == track.count) want += std::max(0.0, (*travel.to_travel)[static_cast<size_t>(end)]);
      SearchState at;
      at.node = end;
      EXPECT_NEAR(cost.terminal_cost(e, static_cast<size_t>(costed), 0.0, at), settings.tag_lookahead * want, 1e-9)
          << "edge " << e << ", " << costed << " frames costed";
      if (f > costed && f < track.count) ++paid_in_edge;
      if (f == track.count && want > 0.0) ++paid_beyond;
    }
  }
  EXPECT_GT(paid_in_edge, 0);
  EXPECT_GT(paid_beyond, 0);
  // With no start to count the pace from, none of it.
  SearchState at;
  at.node = graph.edges[0].to_node;
  EXPECT_EQ(SteerCost(context, input, settings).terminal_cost(0, 1, 0.0, at), 0.0);
}

}  // namespace
}  // namespace mg
