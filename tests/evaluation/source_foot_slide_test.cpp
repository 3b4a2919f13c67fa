#include "motiongraph/evaluation/source_foot_slide.h"

#include <cmath>

#include <gtest/gtest.h>

#include "test_data.h"

namespace mg {
namespace {

// Four nodes in three clips; edges: 0 clip edge in clip 0, 1 transition clip 0 -> clip 2,
// 2 clip edge in clip 2, 3 transition clip 2 -> clip 0.
MotionGraph three_clip_graph() {
  MotionGraph graph;
  graph.window = 10;
  graph.nodes = {{0, 0}, {20, 0}, {100, 1}, {150, 2}, {180, 2}};
  graph.edges = {{0, 1, false, -1, 20}, {1, 3, true, 0, 9}, {3, 4, false, -1, 30}, {4, 0, true, 1, 9}};
  return graph;
}

TEST(SourceFootSlide, TheSourceClipsAreThoseTheEdgesRead) {
  const MotionGraph graph = three_clip_graph();
  EXPECT_EQ(walk_source_clips(graph, 0, std::vector<int>{0}), (std::vector<int>{0}));
  EXPECT_EQ(walk_source_clips(graph, 0, std::vector<int>{0, 1}), (std::vector<int>{0, 2}));   // a transition: both
  EXPECT_EQ(walk_source_clips(graph, 3, std::vector<int>{2, 3, 0, 1, 2}), (std::vector<int>{0, 2}));  // once each
  EXPECT_EQ(walk_source_clips(graph, 2, std::vector<int>{}), (std::vector<int>{1}));          // where it stands
}

TEST(SourceFootSlide, AClipMeasuredAgainstItselfIsOnceTheCapture) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc"});
  const DatabaseClip& walk = db.clips[0];
  auto same = compare_foot_slide(db.skeletons[0], walk.motion, db, std::vector<int>{0});
  ASSERT_TRUE(same) << same.error().to_string();
  EXPECT_EQ(same->output.contact_steps, same->source.contact_steps);
  EXPECT_GT(same->output.contact_steps, 0);
  EXPECT_DOUBLE_EQ(times_the_source(same->output.mean_mps, same->source.mean_mps), 1.0);
  EXPECT_DOUBLE_EQ(times_the_source(same->output.p95_mps, same->source.p95_mps), 1.0);
  EXPECT_DOUBLE_EQ(times_the_source(same->output.max_joint_step_m, same->source.max_joint_step_m), 1.0);
  EXPECT_EQ(same->source_clips, (std::vector<int>{0}));
}

TEST(SourceFootSlide, SeveralSourceClipsPoolTheirSteps) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc"});
  auto both = compare_foot_slide(db.skeletons[0], db.clips[0].motion, db, std::vector<int>{0, 1});
  ASSERT_TRUE(both) << both.error().to_string();
  auto walk = measure_foot_slide(db.skeletons[0], db.clips[0].motion);
  auto run = measure_foot_slide(db.skeletons[0], db.clips[1].motion);
  ASSERT_TRUE(walk && run);
  EXPECT_EQ(both->source.contact_steps, walk->contact_steps + run->contact_steps);
  EXPECT_NEAR(both->source.mean_mps * both->source.contact_steps,
              walk->mean_mps * walk->contact_steps + run->mean_mps * run->contact_steps, 1e-9);
  EXPECT_EQ(both->source.max_joint_step_m, std::max(walk->max_joint_step_m, run->max_joint_step_m));
  EXPECT_NEAR(both->output.mean_mps, walk->mean_mps, 1e-12);
}

TEST(SourceFootSlide, FeetThatCannotBeFoundAndNoSourceSlide) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  std::vector<JointDef> joints = {JointDef{.name = "root", .parent = -1, .animated_translation = true},
                                  JointDef{.name = "head", .parent = 0, .rest_offset_m = Vec3(0.0, 0.5, 0.0)}};
  const Skeleton footless(std::move(joints));
  const Motion motion(footless, 5, 30.0);
  EXPECT_FALSE(compare_foot_slide(footless, motion, db, std::vector<int>{0}));
  EXPECT_TRUE(std::isnan(times_the_source(0.1, 0.0)));
  EXPECT_DOUBLE_EQ(times_the_source(0.3, 0.1), 3.0);
}

}  // namespace
}  // namespace mg
