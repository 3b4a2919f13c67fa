// The edge tracks (filled on all cores) against each edge played by the assembler alone: the
// same roots, facings, first headings and tags, edge by edge, and the longest root step found again serially.
#include "motiongraph/synthesis/edge_tracks.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "motiongraph/synthesis/facing.h"
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
  EXPECT_EQ(tracks.max_root_step_m, max_step);
  // The context's own tracks are these.
  EXPECT_EQ(c.tracks.roots, tracks.roots);
  EXPECT_EQ(c.tracks.tags, tracks.tags);
}

}  // namespace
}  // namespace mg
