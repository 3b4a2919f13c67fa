#include "motiongraph/evaluation/same_frames_slide.h"

#include <cmath>

#include <gtest/gtest.h>

#include "motiongraph/evaluation/synthesis_run.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/motion/forward_kinematics.h"
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
// One clip as a database, its graph without transitions, and the walk that plays it whole.
struct WholeClip {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  int n = db.clips[0].frame_count;
  Result<MotionGraph> graph = build_motion_graph(db, std::vector<Transition>{}, 10);
  Result<MotionAssembler> assembler =
      graph.ok() ? MotionAssembler::create(db, *graph, 0) : Result<MotionAssembler>(graph.error());
  Walk walk = graph.ok() ? walk_between(*graph, 0, n - 1) : Walk{};
};

TEST(SameFramesSlide, AClipPlayedAsCapturedIsItsCapture) {
  const WholeClip whole_clip;
  const auto& [db, n, graph, assembler, walk] = whole_clip;
  ASSERT_TRUE(graph.ok() && assembler.ok());
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

// The same clip played with the whole figure raised 5 cm over a stretch of frames (as the foot
// clean-up lifts a foot stepping to a new plant): the capture's planted steps there are off the
// floor in the result, counted as lifted and not as slide (2.5 cm too); raised by 1 or 1.5 cm
// (within the contacts' 2 cm), they count as before.
TEST(SameFramesSlide, AFootTheResultLiftsIsNotSliding) {
  const WholeClip whole_clip;
  const auto& [db, n, graph, assembler, walk] = whole_clip;
  ASSERT_TRUE(graph.ok() && assembler.ok());
  const std::vector<FrameSource> sources = sources_of(*assembler, *graph, walk);
  auto motion = assemble_walk(db, *graph, walk, {}, 0);
  ASSERT_TRUE(motion.ok());
  auto whole = same_frames_foot_slide(db, *assembler, *motion, sources);
  ASSERT_TRUE(whole.ok());
  EXPECT_EQ(whole->lifted_steps, 0);
  const int root = db.skeletons[0].translation_slot(0);
  ASSERT_GE(root, 0);
  for (double lift : {0.05, 0.025, 0.015, 0.01}) {  // either side of the 2 cm
    Motion raised = *motion;
    for (int f = n / 3; f < 2 * n / 3; ++f) raised.translations(f)[root].y() += lift;
    // The steps into the raised frames, measured on the motion as played.
    auto part = same_frames_foot_slide(db, *assembler, motion->slice(0, 2 * n / 3), sources);
    auto before = same_frames_foot_slide(db, *assembler, motion->slice(0, n / 3), sources);
    ASSERT_TRUE(part.ok() && before.ok());
    const long long raised_steps = part->steps - before->steps;
    ASSERT_GT(raised_steps, 10);
    auto same = same_frames_foot_slide(db, *assembler, raised, sources);
    ASSERT_TRUE(same.ok());
    if (lift > 0.02) {
      EXPECT_EQ(same->lifted_steps, raised_steps);
      EXPECT_EQ(same->steps, whole->steps - raised_steps);
    } else {
      EXPECT_EQ(same->lifted_steps, 0);
      EXPECT_EQ(same->steps, whole->steps);
    }
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

// A blend from a walk into a clip that stands still (every frame the walk's frame `still`, both
// toes planted): on a blended step the capture's speed is the walk's times its weight (the
// still clip adds nothing), and a step counts by the frame that weighs more, the walk's own
// contacts while it does and the still clip's (always planted) after. Worked out here from the
// clips' positions and the blend weights, step by step.
TEST(SameFramesSlide, ABlendWeighsItsTwoSourcesAsItBlendsThem) {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  const Skeleton& skeleton = db.skeletons[0];
  const Motion walk = db.clips[0].motion;  // a copy: the clips grow below
  const int n = walk.frame_count, joints = skeleton.joint_count();
  auto feet = find_foot_joints(skeleton);
  ASSERT_TRUE(feet.ok());
  const int toes[2] = {feet->left.toe, feet->right.toe};
  const std::vector<Vec3> p = world_positions(skeleton, walk);
  auto contacts = detect_foot_contacts(p, joints, walk.fps, *feet, foot_slide_contact_settings());
  ASSERT_TRUE(contacts.ok());
  std::vector<const std::vector<uint8_t>*> planted;
  for (const FootContactTrack& track : contacts->tracks) {
    if (track.part == FootPart::kToe) planted.push_back(&track.planted);
  }
  ASSERT_EQ(planted.size(), 2u);
  int still = 0;
  while (!((*planted[0])[still] && (*planted[1])[still])) ++still;
  Motion standing = walk;
  for (int f = 0; f < n; ++f) {
    std::copy(walk.rotations(still).begin(), walk.rotations(still).end(), standing.rotations(f).begin());
    std::copy(walk.translations(still).begin(), walk.translations(still).end(), standing.translations(f).begin());
  }
  db.clips.push_back({"standing", "", 0, n, n, standing});
  const int k = 10, a = n / 2;
  Transition t;
  t.from_frame = a;
  t.to_frame = n + 2 * k;
  auto graph = build_motion_graph(db, std::vector<Transition>{t}, k);
  ASSERT_TRUE(graph.ok()) << graph.error().to_string();
  auto assembler = MotionAssembler::create(db, *graph, 0);
  ASSERT_TRUE(assembler.ok());
  const Walk played = walk_between(*graph, 0, 2 * n - 1);
  ASSERT_EQ(played.transition_count(*graph), 1);
  auto motion = assemble_walk(db, *graph, played, {}, 0);
  ASSERT_TRUE(motion.ok()) << motion.error().to_string();
  const std::vector<FrameSource> sources = sources_of(*assembler, *graph, played);
  const std::vector<Vec3> out = world_positions(skeleton, *motion);
  auto speed = [&](const std::vector<Vec3>& at, int f, int toe) {
    const Vec3 step = at[static_cast<size_t>(f) * joints + toe] - at[static_cast<size_t>(f - 1) * joints + toe];
    return std::hypot(step.x(), step.z()) * walk.fps;
  };
  long long steps = 0, blended = 0;
  double source = 0.0, output = 0.0;
  for (int f = 1; f < motion->frame_count; ++f) {
    const FrameSource& s = sources[f];
    for (int side = 0; side < 2; ++side) {
      const int g = s.dominant();
      if (g < n && !(g >= 1 && (*planted[side])[g - 1] && (*planted[side])[g])) continue;
      if (s.departure < n) source += s.alpha * speed(p, s.departure, toes[side]);  // only the walk moves
      output += speed(out, f, toes[side]);
      ++steps;
      blended += s.alpha < 1.0 ? 1 : 0;
    }
  }
  ASSERT_GT(blended, 6);
  auto same = same_frames_foot_slide(db, *assembler, *motion, sources);
  ASSERT_TRUE(same.ok()) << same.error().to_string();
  EXPECT_EQ(same->steps, steps);
  EXPECT_NEAR(same->source_mean_mps, source / steps, 1e-12);
  EXPECT_NEAR(same->mean_mps, output / steps, 1e-12);
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
