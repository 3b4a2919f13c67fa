// Which frames of a graph's edges travel (a second around their database frame covering the pace,
// within its clip), and the way to them as a steering decision asked for no motion type prices it.
#include "motiongraph/synthesis/travelling_frames.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "motiongraph/synthesis/assembler.h"
#include "motiongraph/synthesis/tag_distance.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// By hand, from the clips' own root translations: the database frame each edge frame plays
// (a clip piece's from its node on, a blended frame its weightier side's), and whether its clip's
// root covers the pace from half a second before it to half a second after (as far as the clip
// goes), and half the pace from there to it and from it on.
TEST(TravellingFrames, EachFramePlaysItsDatabaseFramesPace) {
  const SynthesisContext& context = test::subject16().context();
  const MotionDatabase& db = *context.db;
  const MotionGraph& graph = *context.graph;
  const int half = static_cast<int>(0.5 * db.fps);
  auto root_of = [&](int frame, const DatabaseClip*& in) {
    for (const DatabaseClip& clip : db.clips) {
      if (frame >= clip.first_frame && frame < clip.first_frame + clip.frame_count) {
        in = &clip;
        const Vec3 t = clip.motion.translations(frame - clip.first_frame)[0];
        return Vec2(t.x(), t.z());
      }
    }
    ADD_FAILURE() << "no clip holds frame " << frame;
    return Vec2(0.0, 0.0);
  };
  std::vector<int> counts;  // travelling frames at each pace
  for (const double pace : {0.5, 1.5}) {
    const std::vector<TagMask> marks = travelling_frames(context, pace);
    ASSERT_EQ(marks.size(), context.tracks.roots.size());
    int travelling = 0, standing = 0;
    for (int e = 0; e < graph.edge_count(); ++e) {
      const GraphEdge& edge = graph.edges[e];
      const EdgeTrack& track = context.tracks.edges[e];
      for (int p = 0; p < track.count; ++p) {
        int frame = graph.nodes[edge.from_node].frame + p;
        if (edge.transition) {
          const Transition& t = graph.transitions[edge.transition_index];
          const int k = edge.frame_count + 1;
          frame = blend_weight(p, k) >= 0.5 ? t.from_frame + p : t.to_frame - k + 1 + p;  // the weightier side
        }
        const DatabaseClip* clip = nullptr;
        root_of(frame, clip);
        ASSERT_NE(clip, nullptr);
        const int a = std::max(clip->first_frame, frame - half);
        const int b = std::min(clip->first_frame + clip->frame_count - 1, frame + half);
        const DatabaseClip* unused = nullptr;
        auto covers = [&](int from, int to, double share) {
          return (root_of(to, unused) - root_of(from, unused)).norm() >= share * pace * (to - from) / db.fps;
        };
        const bool travels = b > a && covers(a, b, 1.0) && covers(a, frame, 0.5) && covers(frame, b, 0.5);
        EXPECT_EQ(marks[track.first + p], travels ? kTravellingMark : TagMask{0})
            << "edge " << e << " frame " << p << " (database frame " << frame << ")";
        (travels ? travelling : standing) += 1;
      }
    }
    EXPECT_GT(standing, 0) << pace;
    EXPECT_GT(travelling, 0) << pace;
    counts.push_back(travelling);
    if (pace == 0.5) {
      EXPECT_GT(travelling, standing);  // subject 16 walks and runs, at a metre a second and more
    }
  }
  EXPECT_LT(counts[1], counts[0]);  // at 1.5 m/s only its runs
}

// The searched costs: per node, the way to the first travelling frame (cost_to_mark's, with the
// transition penalty for each transition), kept in the context's cache per pace and price.
TEST(TravellingFrames, TheWayToThemIsTheMarksCostToGo) {
  const SynthesisContext& context = test::subject16().context();
  const MotionGraph& graph = *context.graph;
  const TravelCosts costs = searched_costs_to_travel(context, 0.5, 1.0, 2.0, 30.0);
  ASSERT_NE(costs.marks, nullptr);
  ASSERT_NE(costs.to_travel, nullptr);
  EXPECT_EQ(*costs.marks, travelling_frames(context, 0.5));
  auto marks_of = [&](int e) {
    return std::span<const TagMask>(*costs.marks).subspan(static_cast<size_t>(context.tracks.edges[e].first),
                                                          static_cast<size_t>(context.tracks.edges[e].count));
  };
  auto edge_cost = [&](int e) {
    const GraphEdge& edge = graph.edges[e];
    return edge.transition ? transition_price(context, edge, 0, 2.0, 30.0) : 0.0;
  };
  EXPECT_EQ(*costs.to_travel, cost_to_mark(graph, marks_of, kTravellingMark, 1.0, edge_cost));
  // Every node of a strongly connected graph with travelling frames reaches them; some at once.
  EXPECT_TRUE(std::all_of(costs.to_travel->begin(), costs.to_travel->end(), [](double c) { return c >= 0.0; }));
  EXPECT_TRUE(std::any_of(costs.to_travel->begin(), costs.to_travel->end(), [](double c) { return c == 0.0; }));
  EXPECT_TRUE(std::any_of(costs.to_travel->begin(), costs.to_travel->end(), [](double c) { return c > 0.0; }));
  // Asked again, the cache's.
  const TravelCosts again = searched_costs_to_travel(context, 0.5, 1.0, 2.0, 30.0);
  EXPECT_EQ(again.marks, costs.marks);
  EXPECT_EQ(again.to_travel, costs.to_travel);
  EXPECT_NE(searched_costs_to_travel(context, 0.5, 2.0, 2.0, 30.0).to_travel, costs.to_travel);  // another price
}

}  // namespace
}  // namespace mg
