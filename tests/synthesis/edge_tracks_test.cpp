// The edge tracks (filled on all cores) against each edge played by the assembler alone: the
// same roots, facings, first headings and tags, edge by edge, and the longest root step found again serially;
// the headings, each frame's facing turned by its sources' travel turns as blended.
#include "motiongraph/synthesis/edge_tracks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "motiongraph/synthesis/facing.h"
#include "motiongraph/synthesis/travel_heading.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

TEST(EdgeTracks, EveryEdgeAsTheAssemblerPlaysIt) {
  const SynthesisContext& c = test::subject16().context();
  const MotionGraph& graph = *c.graph;
  ASSERT_GT(graph.edge_count(), 512) << "too few edges to fill on more than one thread";
  const EdgeTracks tracks = compute_edge_tracks(c.assembler, graph, c.frame_tags, c.tracks.forward_axis, c.tracks.travel_axis);
  ASSERT_EQ(tracks.edges.size(), static_cast<size_t>(graph.edge_count()));
  double max_step = 0.0;
  int first = 0;
  for (int e = 0; e < graph.edge_count(); ++e) {
    std::vector<RootPose> roots;
    FloorTransform placement;
    c.assembler.append_edge_roots(e, placement, roots);
    const EdgeTrack& track = tracks.edges[static_cast<size_t>(e)];
    ASSERT_EQ(track.first, first);
    ASSERT_EQ(track.count, static_cast<int>(roots.size()));
    first += track.count;
    EXPECT_EQ(track.change.apply(Vec3(1.0, 0.0, 2.0)), placement.apply(Vec3(1.0, 0.0, 2.0)));
    ASSERT_EQ(track.first_heading, facing_on_floor(roots.front().rotation, c.tracks.travel_axis)) << e;
    Vec3 next3 = c.assembler.root_position(graph.nodes[graph.edges[e].to_node].frame, placement);
    Vec2 next(next3.x(), next3.z());
    for (int p = track.count; p-- > 0;) {
      const Vec2 root(roots[static_cast<size_t>(p)].position.x(), roots[static_cast<size_t>(p)].position.z());
      ASSERT_EQ(tracks.roots_of(e)[static_cast<size_t>(p)], root) << e << ":" << p;
      ASSERT_EQ(tracks.facings_of(e)[static_cast<size_t>(p)],
                facing_on_floor(roots[static_cast<size_t>(p)].rotation, c.tracks.forward_axis));
      max_step = std::max(max_step, (next - root).norm());
      next = root;
    }
    if (!graph.edges[e].transition) {
      for (int p = 0; p < track.count; ++p) {
        ASSERT_EQ(tracks.tags_of(e)[static_cast<size_t>(p)], c.frame_tags[graph.nodes[graph.edges[e].from_node].frame + p]);
      }
    }
  }
  EXPECT_EQ(static_cast<size_t>(first), tracks.roots.size());
  // The longest step is the longest of any two edges played one after the other, as the
  // assembler plays them (a transition's first frame is already blended).
  for (int e = 0; e < graph.edge_count(); ++e) {
    for (int f = graph.edge_offsets[graph.edges[e].to_node]; f < graph.edge_offsets[graph.edges[e].to_node + 1]; ++f) {
      std::vector<RootPose> roots;
      FloorTransform placement;
      c.assembler.append_edge_roots(e, placement, roots);
      c.assembler.append_edge_roots(f, placement, roots);
      for (size_t p = 1; p < roots.size(); ++p) {
        const Vec3 step = roots[p].position - roots[p - 1].position;
        max_step = std::max(max_step, Vec2(step.x(), step.z()).norm());
      }
    }
  }
  EXPECT_NEAR(tracks.max_root_step_m, max_step, 1e-12);
  // The context's own tracks are these.
  EXPECT_EQ(c.tracks.roots, tracks.roots);
  EXPECT_EQ(c.tracks.tags, tracks.tags);
  EXPECT_TRUE(tracks.headings.empty());  // no turns given
}

TEST(EdgeTracks, HeadingsAreFacingsTurnedByTheirSourcesTravelTurns) {
  const SynthesisContext& c = test::subject16().context();
  const MotionGraph& graph = *c.graph;
  HeadingEditSettings held;
  held.hold_travel = true;
  const std::vector<float> turns = travel_turns(*c.db, c.assembler, c.tracks.forward_axis, held);
  const EdgeTracks tracks =
      compute_edge_tracks(c.assembler, graph, c.frame_tags, c.tracks.forward_axis, c.tracks.travel_axis, turns);
  ASSERT_EQ(tracks.headings.size(), tracks.facings.size());
  double largest_deg = 0.0;
  int blended = 0;
  for (int e = 0; e < graph.edge_count(); ++e) {
    std::vector<FrameSource> sources;
    c.assembler.append_edge_sources(e, sources);
    ASSERT_EQ(sources.size(), tracks.headings_of(e).size());
    for (size_t p = 0; p < sources.size(); ++p) {
      const FrameSource& s = sources[p];
      const double turn_rad = s.alpha * turns[static_cast<size_t>(s.departure)] +
                              (1.0 - s.alpha) * turns[static_cast<size_t>(s.arrival)];
      const Vec2 facing = tracks.facings_of(e)[p];
      const Vec2 want(std::cos(turn_rad) * facing.x() + std::sin(turn_rad) * facing.y(),
                      -std::sin(turn_rad) * facing.x() + std::cos(turn_rad) * facing.y());
      ASSERT_LT((tracks.headings_of(e)[p] - want).norm(), 1e-12) << e << ":" << p;
      largest_deg = std::max(largest_deg, std::abs(turn_rad) * 180.0 / std::numbers::pi);
      if (s.departure != s.arrival && std::abs(turns[static_cast<size_t>(s.departure)] - turns[static_cast<size_t>(s.arrival)]) > 1e-3) ++blended;
    }
  }
  // Subject 16's walks travel a few degrees off their hips (docs/performance.md: 3.9 degrees
  // left on its held walk); transitions join frames of different turns.
  EXPECT_GT(largest_deg, 2.0);
  EXPECT_LT(largest_deg, 45.0);
  EXPECT_GT(blended, 0);
  // The context's tracks carry these headings.
  EXPECT_EQ(c.tracks.headings, tracks.headings);
}

}  // namespace
}  // namespace mg
