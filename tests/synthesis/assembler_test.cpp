#include "motiongraph/synthesis/assembler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "motiongraph/motion/forward_kinematics.h"
#include "synthesis/subject16_graph.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(BlendWeight, LeavesSmoothlyAndEndsOnTheArrival) {
  for (int k : {2, 5, 10, 40}) {
    EXPECT_DOUBLE_EQ(blend_weight(k - 1, k), 0.0);
    double previous = 1.0;
    for (int p = 0; p < k; ++p) {
      const double a = blend_weight(p, k);
      EXPECT_GE(a, 0.0);
      EXPECT_LE(a, previous);  // monotone: we only ever move towards the arrival
      previous = a;
    }
  }
}

// The largest world-space step of any joint between consecutive frames of a motion.
double largest_joint_step(const Skeleton& skeleton, const Motion& motion) {
  const std::vector<Vec3> p = world_positions(skeleton, motion);
  const int joints = skeleton.joint_count();
  double largest = 0.0;
  for (int f = 1; f < motion.frame_count; ++f) {
    for (int j = 0; j < joints; ++j) {
      largest = std::max(largest, (p[static_cast<size_t>(f) * joints + j] - p[static_cast<size_t>(f - 1) * joints + j]).norm());
    }
  }
  return largest;
}

TEST(Assembler, AClipPieceIsTheDatabaseItself) {
  const auto& s = test::subject16();
  const MotionGraph& graph = s.file().graph;
  const MotionDatabase& db = s.file().database;
  int checked = 0;
  for (int e = 0; e < graph.edge_count() && checked < 20; ++e) {
    const GraphEdge& edge = graph.edges[e];
    if (edge.transition) continue;
    ++checked;
    auto motion = assemble_walk(db, graph, Walk{edge.from_node, {e}});
    ASSERT_TRUE(motion.ok()) << motion.error().to_string();
    ASSERT_EQ(motion->frame_count, edge.frame_count + 1);
    const int first = graph.nodes[edge.from_node].frame;
    const DatabaseClip& clip = db.clips[db.clip_of(first)];
    for (int p = 0; p <= edge.frame_count; ++p) {
      const int local = first + p - clip.first_frame;
      for (int j = 0; j < motion->joint_count; ++j) {
        EXPECT_LT(motion->rotations(p)[j].angularDistance(clip.motion.rotations(local)[j]), 1e-12);
      }
      EXPECT_LT((motion->translations(p)[0] - clip.motion.translations(local)[0]).norm(), 1e-12);
    }
  }
  EXPECT_EQ(checked, 20);
}

TEST(Assembler, RandomWalksHaveNoPopsAtTransitions) {
  const auto& s = test::subject16();
  const MotionGraph& graph = s.file().graph;
  const MotionDatabase& db = s.file().database;
  const Skeleton& skeleton = s.context().assembler.skeleton();
  double data_step = 0.0;
  for (const DatabaseClip& clip : db.clips) data_step = std::max(data_step, largest_joint_step(skeleton, clip.motion));
  std::mt19937 rng(3);
  int transitions = 0;
  for (int w = 0; w < 30; ++w) {
    Walk walk{static_cast<int>(rng() % graph.node_count()), {}};
    int node = walk.start_node;
    for (int step = 0; step < 60; ++step) {
      const auto out = graph.out_edges(node);
      const GraphEdge& edge = out[rng() % out.size()];
      walk.edges.push_back(static_cast<int>(&edge - graph.edges.data()));
      transitions += edge.transition ? 1 : 0;
      node = edge.to_node;
    }
    const FloorTransform start{0.3 * w, 2.0 * w, -1.0 * w};
    auto motion = assemble_walk(db, graph, walk, start);
    ASSERT_TRUE(motion.ok()) << motion.error().to_string();
    EXPECT_EQ(motion->frame_count, walk.frame_count(graph) + 1);
    // No joint moves further between two frames than the capture itself ever does (with a
    // little room for the blend of two differently paced windows).
    EXPECT_LE(largest_joint_step(skeleton, *motion), 1.25 * data_step) << "walk " << w;
  }
  EXPECT_GT(transitions, 100);
}

TEST(Assembler, TheStartPlacementMovesTheWholeWalkRigidly) {
  const auto& s = test::subject16();
  const MotionGraph& graph = s.file().graph;
  Walk walk{0, {}};
  for (int node = 0; walk.edges.size() < 40;) {
    const auto out = graph.out_edges(node);
    const GraphEdge& edge = out.back();  // prefer transitions
    walk.edges.push_back(static_cast<int>(&edge - graph.edges.data()));
    node = edge.to_node;
  }
  const FloorTransform start{1.1, -30.0, 12.0};
  auto a = assemble_walk(s.file().database, graph, walk);
  auto b = assemble_walk(s.file().database, graph, walk, start);
  ASSERT_TRUE(a.ok() && b.ok());
  const Skeleton& skeleton = s.context().assembler.skeleton();
  const std::vector<Vec3> pa = world_positions(skeleton, *a), pb = world_positions(skeleton, *b);
  ASSERT_EQ(pa.size(), pb.size());
  for (size_t i = 0; i < pa.size(); ++i) EXPECT_LT((start.apply(pa[i]) - pb[i]).norm(), 1e-6);  // a micrometre
}

TEST(Assembler, RootTracksAreTheRootsOfTheWholePoses) {
  const auto& s = test::subject16();
  const MotionAssembler& assembler = s.context().assembler;
  for (int e = 0; e < s.file().graph.edge_count(); e += 7) {
    FloorTransform a{0.2, 1.0, -2.0}, b = a;
    Motion motion = assembler.empty_motion();
    std::vector<RootPose> roots;
    assembler.append_edge(e, a, motion);
    assembler.append_edge_roots(e, b, roots);
    ASSERT_EQ(static_cast<int>(roots.size()), motion.frame_count);
    EXPECT_EQ(a.yaw_rad, b.yaw_rad);
    EXPECT_EQ(a.x_m, b.x_m);
    for (int p = 0; p < motion.frame_count; ++p) {
      EXPECT_EQ(roots[p].position, motion.translations(p)[0]);
      EXPECT_EQ(roots[p].rotation.coeffs(), motion.rotations(p)[0].coeffs());
    }
  }
}

// Each played frame knows the database frames it is made of (both the same frame for a clip
// edge, the blend's two with its weight for a transition) and carries the contacts of the one
// that weighs most.
TEST(Assembler, PlayedFramesCarryTheContactsOfTheFramesThatWeighMost) {
  const auto& s = test::subject16();
  const MotionGraph& graph = s.file().graph;
  // Every database frame its own mask, so that the source of each played mask shows.
  std::vector<ContactMask> masks(static_cast<size_t>(s.file().database.frame_count()));
  for (size_t f = 0; f < masks.size(); ++f) masks[f] = static_cast<ContactMask>(f % 251);
  int transitions = 0;
  for (int e = 0; e < graph.edge_count(); ++e) {
    const GraphEdge& edge = graph.edges[e];
    std::vector<ContactMask> played;
    std::vector<FrameSource> sources;
    s.context().assembler.append_edge_contacts(e, masks, played);
    s.context().assembler.append_edge_sources(e, sources);
    ASSERT_EQ(static_cast<int>(played.size()), edge.frame_count);
    ASSERT_EQ(static_cast<int>(sources.size()), edge.frame_count);
    for (int p = 0; p < edge.frame_count; ++p) {
      const int clip_frame = graph.nodes[edge.from_node].frame + p;
      FrameSource want{clip_frame, clip_frame, 1.0};
      int frame = clip_frame;
      if (edge.transition) {
        const Transition& t = graph.transitions[edge.transition_index];
        const int length = blend_frames(edge);
        want = {t.from_frame + p, t.to_frame - length + 1 + p, blend_weight(p, length)};
        frame = want.alpha >= 0.5 ? want.departure : want.arrival;
      }
      ASSERT_EQ(played[p], masks[frame]) << "edge " << e << " frame " << p;
      ASSERT_EQ(sources[p], want) << "edge " << e << " frame " << p;
      ASSERT_EQ(sources[p].dominant(), frame);
    }
    transitions += edge.transition ? 1 : 0;
  }
  EXPECT_GT(transitions, 10);
  // The context's: a walk's frames and its end node's frame, as assemble_walk plays them;
  // steering's record of edges (no start node) its edges' frames alone.
  ASSERT_EQ(s.context().frame_contacts.size(), masks.size());
  const Walk walk{0, {graph.edge_offsets[0]}};
  EXPECT_EQ(static_cast<long long>(s.context().walk_contacts(walk).size()), walk.frame_count(graph) + 1);
  const std::vector<FrameSource> sources = s.context().walk_sources(walk);
  ASSERT_EQ(static_cast<long long>(sources.size()), walk.frame_count(graph) + 1);
  EXPECT_EQ(sources.back().departure, graph.nodes[walk.end_node(graph)].frame);
  EXPECT_EQ(static_cast<long long>(s.context().walk_sources(Walk{-1, walk.edges}).size()), walk.frame_count(graph));
}

TEST(Assembler, RejectsAWalkThatDoesNotFollowTheGraph) {
  const auto& s = test::subject16();
  const MotionGraph& graph = s.file().graph;
  int wrong = 0;
  while (graph.edges[wrong].from_node == 0) ++wrong;
  auto motion = assemble_walk(s.file().database, graph, Walk{0, {wrong}});
  ASSERT_FALSE(motion.ok());
  EXPECT_NE(motion.error().message.find("leaves node"), std::string::npos);
  EXPECT_FALSE(assemble_walk(s.file().database, graph, Walk{graph.node_count(), {}}).ok());
}

// A walk that comes to rest plays its rest frames as captured where the end node's frame would
// be, placed as the walk's last frame; its sources and contacts are those frames'.
TEST(Assembler, AWalkThatComesToRestPlaysItsRestFramesAsCaptured) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const MotionGraph& graph = *context.graph;
  ASSERT_FALSE(context.rest().empty());
  // An edge into a node that can rest, and that ending.
  int edge = 0;
  while (context.rest().at(graph.edges[static_cast<size_t>(edge)].to_node) == nullptr) ++edge;
  const RestEnding& ending = *context.rest().at(graph.edges[static_cast<size_t>(edge)].to_node);
  Walk walk{graph.edges[static_cast<size_t>(edge)].from_node, {edge}};
  walk.rest_frames = ending.frames(graph);
  walk.rest_frames.push_back(ending.last_frame);  // held a frame
  const FloorTransform start{0.7, 2.0, -1.0};
  auto motion = assemble_walk(*context.db, graph, walk, start);
  ASSERT_TRUE(motion.ok()) << motion.error().to_string();
  ASSERT_EQ(motion->frame_count, walk.frame_count(graph) + static_cast<long long>(walk.rest_frames.size()));
  const int first = static_cast<int>(walk.frame_count(graph));
  FloorTransform placement = start;
  Motion scratch = context.assembler.empty_motion();
  context.assembler.append_edge(edge, placement, scratch);
  for (size_t i = 0; i < walk.rest_frames.size(); ++i) {
    const RootPose want = context.assembler.root_pose(walk.rest_frames[i], placement);
    EXPECT_LT((motion->translations(first + static_cast<int>(i))[0] - want.position).norm(), 1e-9) << i;
  }
  const std::vector<FrameSource> sources = context.walk_sources(walk);
  ASSERT_EQ(sources.size(), static_cast<size_t>(motion->frame_count));
  for (size_t i = 0; i < walk.rest_frames.size(); ++i) {
    EXPECT_EQ(sources[static_cast<size_t>(first) + i], (FrameSource{walk.rest_frames[i], walk.rest_frames[i], 1.0}));
  }
  EXPECT_EQ(context.walk_contacts(walk).size(), sources.size());
  // Rest frames that do not start where the walk ends are refused.
  Walk astray = walk;
  astray.rest_frames.front() += 1;
  auto refused = assemble_walk(*context.db, graph, astray, start);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("comes to rest from frame"), std::string::npos);
}

}  // namespace
}  // namespace mg

namespace mg {
namespace {

// A second subject that is the first one 1.2 times larger (the same clip read with a larger
// unit): played on the first subject's skeleton, a walk that crosses to it by a transition
// between the same frames must be the original clip itself.
TEST(Assembler, OtherSubjectsAreScaledToTheTarget) {
  const int k = 10;
  const test::ScaledPair pair = test::scaled_pair(1.2, 40, k);
  const Clip& small = pair.small;
  const Clip& large = pair.large;
  const MotionDatabase& db = pair.db;
  const int n = small.motion.frame_count;
  const Transition& t = pair.transition;
  auto graph = build_motion_graph(db, std::vector<Transition>{t}, k);
  ASSERT_TRUE(graph.ok()) << graph.error().to_string();
  // From the small clip's first frame to the transition, across it, to the large clip's end.
  Walk walk{graph->node_at_frame(0), {}};
  for (int node = walk.start_node; graph->nodes[node].frame != 2 * n - 1;) {
    const auto out = graph->out_edges(node);
    const GraphEdge& edge = out.back();
    walk.edges.push_back(static_cast<int>(&edge - graph->edges.data()));
    node = edge.to_node;
  }
  auto motion = assemble_walk(db, *graph, walk, {}, 0);
  ASSERT_TRUE(motion.ok()) << motion.error().to_string();
  ASSERT_EQ(motion->frame_count, n);
  const std::vector<Vec3> got = world_positions(small.skeleton, *motion);
  const std::vector<Vec3> want = world_positions(small.skeleton, small.motion);
  EXPECT_LT(test::max_position_error(got, want), 1e-4);  // float storage of the alignment
  // On the large skeleton, the same walk is the large clip.
  auto on_large = assemble_walk(db, *graph, walk, {}, 1);
  ASSERT_TRUE(on_large.ok());
  EXPECT_LT(test::max_position_error(world_positions(large.skeleton, *on_large),
                                     world_positions(large.skeleton, large.motion)), 1.2e-4);
}

TEST(Assembler, ALongerBlendReadsItsOwnLengthOnBothSides) {
  // Two copies of one clip; a transition of blend length L from frame a of the first to the
  // same frames of the second (b = a + L - 1) blends each frame with itself, so the walk
  // across it is the clip, frame for frame, only when both windows are read over L frames.
  const Clip clip = test::load_data_clip("bvh/131_01.bvh", 0.056444);
  MotionDatabase db;
  db.fps = clip.motion.fps;
  db.skeletons = {clip.skeleton};
  db.skeleton_names = {"s"};
  const int n = clip.motion.frame_count;
  db.clips.push_back({"one", "", 0, 0, n, clip.motion});
  db.clips.push_back({"two", "", 0, n, n, clip.motion});
  const int k = 10, a = 40;
  for (const int length : {10, 17, 30}) {
    SCOPED_TRACE(length);
    Transition t;
    t.from_frame = a;
    t.to_frame = n + a + length - 1;
    auto graph = build_motion_graph(db, std::vector<Transition>{t}, k, std::vector<int>{length});
    ASSERT_TRUE(graph.ok()) << graph.error().to_string();
    Walk walk{graph->node_at_frame(0), {}};
    for (int node = walk.start_node; graph->nodes[node].frame != 2 * n - 1;) {
      const GraphEdge& edge = graph->out_edges(node).back();
      walk.edges.push_back(static_cast<int>(&edge - graph->edges.data()));
      node = edge.to_node;
    }
    auto motion = assemble_walk(db, *graph, walk, {}, 0);
    ASSERT_TRUE(motion.ok()) << motion.error().to_string();
    ASSERT_EQ(motion->frame_count, n);
    EXPECT_LT(test::max_position_error(world_positions(clip.skeleton, *motion),
                                       world_positions(clip.skeleton, clip.motion)), 1e-9);
  }
}

}  // namespace
}  // namespace mg
