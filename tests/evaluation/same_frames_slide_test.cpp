#include "motiongraph/evaluation/same_frames_slide.h"

#include <cmath>

#include <gtest/gtest.h>

#include "motiongraph/evaluation/synthesis_run.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/synthesis/floor_path.h"
#include "synthesis/subject16_graph.h"
#include "test_data.h"

namespace mg {
namespace {

// The walk from a graph's node at database frame `first` along each node's last out-edge (the
// transition when there is one) until the node at frame `last`.
Walk walk_between(const MotionGraph& graph, int first, int last) {
  Walk walk{graph.node_at_frame(first), {}};
  for (int node = walk.start_node; graph.nodes[node].frame != last;) {
    const GraphEdge& edge = graph.out_edges(node).back();
    walk.edges.push_back(static_cast<int>(&edge - graph.edges.data()));
    node = edge.to_node;
  }
  return walk;
}

// The database frames of a walk, as the synthesis context gives them.
std::vector<FrameSource> sources_of(const MotionAssembler& assembler, const MotionGraph& graph, const Walk& walk) {
  std::vector<FrameSource> sources;
  for (int e : walk.edges) assembler.append_edge_sources(e, sources);
  const int end = graph.nodes[walk.end_node(graph)].frame;
  sources.push_back({end, end, 1.0});
  return sources;
}

// A clip played whole, as captured, is its capture step for step: the steps are the measure's own
// on that clip, and the speeds the same, wherever the walk is placed.
TEST(SameFramesSlide, AClipPlayedAsCapturedIsItsCapture) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  const int n = db.clips[0].frame_count;
  auto graph = build_motion_graph(db, std::vector<Transition>{}, 10);
  ASSERT_TRUE(graph.ok()) << graph.error().to_string();
  auto assembler = MotionAssembler::create(db, *graph, 0);
  ASSERT_TRUE(assembler.ok());
  const Walk walk = walk_between(*graph, 0, n - 1);
  auto capture = measure_foot_slide(db.skeletons[0], db.clips[0].motion);
  ASSERT_TRUE(capture.ok());
  ASSERT_GT(capture->contact_steps, 20);
  for (const FloorTransform& start : {FloorTransform{}, FloorTransform{1.1, 3.0, -2.0}}) {
    auto motion = assemble_walk(db, *graph, walk, start, 0);
    ASSERT_TRUE(motion.ok()) << motion.error().to_string();
    ASSERT_EQ(motion->frame_count, n);
    auto same = same_frames_foot_slide(db, *assembler, *motion, sources_of(*assembler, *graph, walk));
    ASSERT_TRUE(same.ok()) << same.error().to_string();
    EXPECT_EQ(same->steps, capture->contact_steps);
    EXPECT_NEAR(same->mean_mps, capture->mean_mps, 1e-9);
    EXPECT_NEAR(same->source_mean_mps, capture->mean_mps, 1e-9);
  }
}

// A second copy of the clip captured 10 cm higher (another floor), entered by a transition
// between the same frames: the result is the clip's motion, judged frame by frame on each copy's
// own floor it is the capture; the result's one floor loses the raised copy's steps.
TEST(SameFramesSlide, EachFrameIsJudgedOnItsOwnClipsFloor) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc"}, true, 0.0, Vec3(0.0, 0.1, 0.0));
  const int n = db.clips[0].frame_count;
  const int k = 10, a = n / 3;
  Transition t;
  t.from_frame = a;
  t.to_frame = n + a + k - 1;
  auto graph = build_motion_graph(db, std::vector<Transition>{t}, k);
  ASSERT_TRUE(graph.ok()) << graph.error().to_string();
  auto assembler = MotionAssembler::create(db, *graph, 0);
  ASSERT_TRUE(assembler.ok());
  const Walk walk = walk_between(*graph, 0, 2 * n - 1);
  ASSERT_EQ(walk.transition_count(*graph), 1);
  auto motion = assemble_walk(db, *graph, walk, {}, 0);
  ASSERT_TRUE(motion.ok()) << motion.error().to_string();
  ASSERT_EQ(motion->frame_count, n);
  auto capture = measure_foot_slide(db.skeletons[0], db.clips[0].motion);
  ASSERT_TRUE(capture.ok());
  auto same = same_frames_foot_slide(db, *assembler, *motion, sources_of(*assembler, *graph, walk));
  ASSERT_TRUE(same.ok()) << same.error().to_string();
  EXPECT_EQ(same->steps, capture->contact_steps);
  EXPECT_NEAR(same->mean_mps, capture->mean_mps, 1e-9);
  EXPECT_NEAR(same->source_mean_mps, capture->mean_mps, 1e-9);
  auto one_floor = measure_foot_slide(db.skeletons[0], *motion);
  ASSERT_TRUE(one_floor.ok());
  EXPECT_LT(one_floor->contact_steps, capture->contact_steps * 2 / 3);
}

// A subject 1.2 times larger played on the smaller one's skeleton: its speeds are counted at the
// scale the result plays it, so the walk into it, which is the smaller clip, is its capture
// (its contacts are its own: 2 cm on a larger figure, fewer steps than the smaller clip's).
TEST(SameFramesSlide, AnotherSubjectIsJudgedAtTheScaleItIsPlayed) {
  const int k = 10;
  const test::ScaledPair pair = test::scaled_pair(1.2, 40, k);
  const MotionDatabase& db = pair.db;
  const int n = pair.small.motion.frame_count;
  const Transition& t = pair.transition;
  auto graph = build_motion_graph(db, std::vector<Transition>{t}, k);
  ASSERT_TRUE(graph.ok()) << graph.error().to_string();
  auto assembler = MotionAssembler::create(db, *graph, 0);
  ASSERT_TRUE(assembler.ok());
  const Walk walk = walk_between(*graph, 0, 2 * n - 1);
  auto motion = assemble_walk(db, *graph, walk, {}, 0);
  ASSERT_TRUE(motion.ok()) << motion.error().to_string();
  auto same = same_frames_foot_slide(db, *assembler, *motion, sources_of(*assembler, *graph, walk));
  ASSERT_TRUE(same.ok()) << same.error().to_string();
  auto capture = measure_foot_slide(pair.small.skeleton, pair.small.motion);
  ASSERT_TRUE(capture.ok());
  EXPECT_GT(same->steps, capture->contact_steps / 2);
  EXPECT_LT(same->steps, capture->contact_steps);
  ASSERT_GT(same->source_mean_mps, 0.05);
  EXPECT_NEAR(same->mean_mps / same->source_mean_mps, 1.0, 1e-4);  // float storage of the alignment
}

// On the bundled graph, a path with transitions: the clean-up holds the planted toes the played
// motion lets slide, the capture the same in both; the report carries the measure.
TEST(SameFramesSlide, TheCleanUpHoldsWhatThePlayedMotionLetsSlide) {
  const SynthesisContext& context = test::subject16().context();
  auto path = make_shape("s-curve:30");
  ASSERT_TRUE(path.ok());
  SynthesisRunSettings run;
  run.cleanup = false;
  auto played = run_path_synthesis(context, *path, PathSynthesisSettings{}, run);
  ASSERT_TRUE(played.ok()) << played.error().to_string();
  run.cleanup = true;
  auto cleaned = run_path_synthesis(context, *path, PathSynthesisSettings{}, run);
  ASSERT_TRUE(cleaned.ok()) << cleaned.error().to_string();
  ASSERT_EQ(played->walk.edges, cleaned->walk.edges);
  ASSERT_GT(played->walk.transition_count(*context.graph), 5);
  const std::vector<FrameSource> sources = context.walk_sources(played->walk);
  ASSERT_GE(static_cast<int>(sources.size()), played->motion.frame_count);
  auto as_played = same_frames_foot_slide(*context.db, context.assembler, played->motion, sources);
  auto as_cleaned = same_frames_foot_slide(*context.db, context.assembler, cleaned->motion, sources);
  ASSERT_TRUE(as_played.ok() && as_cleaned.ok());
  ASSERT_GT(as_played->steps, 100);
  EXPECT_EQ(as_played->steps, as_cleaned->steps);
  EXPECT_EQ(as_played->source_mean_mps, as_cleaned->source_mean_mps);
  EXPECT_LT(as_cleaned->mean_mps, 0.5 * as_played->mean_mps);
  const nlohmann::json& report = cleaned->report["foot_slide"]["same_frames"];
  EXPECT_EQ(report["steps"].get<long long>(), as_cleaned->steps);
  EXPECT_DOUBLE_EQ(report["mean_mps"].get<double>(), as_cleaned->mean_mps);
  EXPECT_DOUBLE_EQ(report["ratio"].get<double>(), as_cleaned->mean_mps / as_cleaned->source_mean_mps);
}

TEST(SameFramesSlide, TooFewSourcesAndFootlessSkeletonsAreErrors) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  auto graph = build_motion_graph(db, std::vector<Transition>{}, 10);
  ASSERT_TRUE(graph.ok());
  auto assembler = MotionAssembler::create(db, *graph, 0);
  ASSERT_TRUE(assembler.ok());
  const Motion& clip = db.clips[0].motion;
  std::vector<FrameSource> sources(static_cast<size_t>(clip.frame_count - 1));
  auto short_of_one = same_frames_foot_slide(db, *assembler, clip, sources);
  ASSERT_FALSE(short_of_one.ok());
  EXPECT_NE(short_of_one.error().message.find("sources"), std::string::npos);
  FootSlideSettings wrong;
  wrong.joint_names.left_toe = "no_such_joint";
  sources.resize(static_cast<size_t>(clip.frame_count));
  EXPECT_FALSE(same_frames_foot_slide(db, *assembler, clip, sources, wrong).ok());
}

}  // namespace
}  // namespace mg
