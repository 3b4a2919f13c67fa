#include "motiongraph/synthesis/path_rest.h"

#include <gtest/gtest.h>

#include "motiongraph/synthesis/path_synthesis.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// The way to rest goes on from a node of the walk through the graph's edges to a node whose clip
// ends standing still; with no such clip there is none.
TEST(PathRest, TheWayGoesOnFromTheWalkThroughTheGraphToAnEnding) {
  const auto& s = test::subject16();
  const MotionGraph& graph = *s.context().graph;
  for (const char* spec : {"line:12", "circle:4"}) {
    auto path = make_shape(spec);
    ASSERT_TRUE(path.ok());
    auto searched = synthesize_path(s.context(), *path);
    ASSERT_TRUE(searched.ok());
    const PathRestWay way = nearest_rest_way(s.context(), *path, searched->walk, searched->start, searched->roots,
                                             rest_ending_travel(s.context()));
    ASSERT_NE(way.ending, nullptr) << spec;
    ASSERT_LE(way.kept_edges, searched->walk.edges.size());
    Walk walk{searched->walk.start_node,
              std::vector<int>(searched->walk.edges.begin(),
                               searched->walk.edges.begin() + static_cast<long>(way.kept_edges))};
    walk.edges.insert(walk.edges.end(), way.edges.begin(), way.edges.end());
    EXPECT_TRUE(check_walk(graph, walk).ok()) << spec;
    EXPECT_EQ(walk.end_node(graph), way.ending->node) << spec;
    EXPECT_EQ(s.context().rest().at(way.ending->node), way.ending);
    for (int e : way.edges) EXPECT_FALSE(graph.edges[e].bridge);
    // Nowhere to rest: no way.
    SynthesisContext nowhere = s.context();
    nowhere.set_rest({});
    EXPECT_EQ(nearest_rest_way(nowhere, *path, searched->walk, searched->start, searched->roots,
                               rest_ending_travel(nowhere))
                  .ending,
              nullptr);
  }
}

}  // namespace
}  // namespace mg
