// A graph file and its synthesis context owned together: the context reads the very file the
// object holds, a skeleton the graph lacks and a file that is not there fail with the file's
// name, and the object can be neither copied nor moved (the context points into it).
#include "motiongraph/synthesis/loaded_graph.h"

#include <gtest/gtest.h>

#include <type_traits>

#include "motiongraph/pipeline/build_graph.h"
#include "test_data.h"

namespace mg {
namespace {

static_assert(!std::is_copy_constructible_v<LoadedGraph> && !std::is_move_constructible_v<LoadedGraph>);

GraphFile built_graph() {
  BuildSettings settings;
  settings.threshold_mode = ThresholdMode::kRmsCm;
  settings.threshold_value = 5.0;
  auto built = build_graph(std::vector<std::string>{test::data_path("cmu/16")}, settings);
  if (!built || !built->graph_status) throw std::runtime_error("the subject-16 graph was not built");
  return std::move(built->file);
}

TEST(LoadedGraph, TheContextReadsTheFileItHolds) {
  GraphFile file = built_graph();
  const int frames = file.database.frame_count();
  const size_t edges = file.graph.edges.size();
  auto loaded = LoadedGraph::create(std::move(file), "s16.mgraph");
  ASSERT_TRUE(loaded) << loaded.error().to_string();
  const LoadedGraph& g = **loaded;
  EXPECT_EQ(g.file().database.frame_count(), frames);
  EXPECT_EQ(g.file().graph.edges.size(), edges);
  EXPECT_EQ(g.context().db, &g.file().database);
  EXPECT_EQ(g.context().graph, &g.file().graph);
  EXPECT_EQ(g.context().tracks.edges.size(), edges);
  EXPECT_EQ(static_cast<int>(g.context().frame_tags.size()), frames);
}

TEST(LoadedGraph, FailsOnAMissingSkeletonOrFile) {
  auto no_skeleton = LoadedGraph::create(built_graph(), "s16.mgraph", 1);  // one skeleton: 0
  ASSERT_FALSE(no_skeleton);
  EXPECT_EQ(no_skeleton.error().file, "s16.mgraph");
  EXPECT_NE(no_skeleton.error().message.find("1 skeleton"), std::string::npos);
  auto missing = LoadedGraph::load(testing::TempDir() + "no-such-graph.mgraph");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().file.find("no-such-graph.mgraph"), std::string::npos);
}

}  // namespace
}  // namespace mg
