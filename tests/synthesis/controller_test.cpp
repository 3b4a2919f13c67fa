#include "motiongraph/synthesis/controller.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>

#include "motiongraph/motion/forward_kinematics.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// Seconds after `from_s` until the facing is within `degrees` of `want`; -1 if never.
double response_time(const Motion& motion, const Vec3& axis, double from_s, const Vec2& want, double degrees) {
  for (int f = static_cast<int>(from_s * motion.fps); f < motion.frame_count; ++f) {
    if (facing_on_floor(motion.rotations(f)[0], axis).dot(want) >= std::cos(degrees * std::numbers::pi / 180.0)) {
      return f / motion.fps - from_s;
    }
  }
  return -1.0;
}

TEST(Controller, FollowsAScriptedTurnWithinAboutTwoSeconds) {
  const auto& s = test::subject16();
  auto walk = s.context().tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  ControlInput input{bearing_direction(0.0), *walk};
  auto controller = Controller::create(s.context(), {}, input);
  ASSERT_TRUE(controller.ok()) << controller.error().to_string();
  Motion motion = s.context().assembler.empty_motion();
  const double fps = motion.fps;
  while (motion.frame_count < 4 * fps) controller->step(motion);
  const double turn_at = motion.frame_count / fps;
  controller->set_input({bearing_direction(90.0), *walk});
  while (motion.frame_count < (turn_at + 5) * fps) {
    const ControllerDecision d = controller->step(motion);
    EXPECT_GT(d.frames, 0);
  }
  const double response =
      response_time(motion, s.context().tracks.forward_axis, turn_at, bearing_direction(90.0), 20.0);
  EXPECT_GE(response, 0.0);
  EXPECT_LE(response, 2.5);  // "within a second or two"; 2.1-2.2 s measured on subject 16
  // Still walking the new way a few seconds later: mean facing over the last second.
  Vec2 mean = Vec2::Zero();
  for (int f = motion.frame_count - static_cast<int>(fps); f < motion.frame_count; ++f) {
    mean += facing_on_floor(motion.rotations(f)[0], s.context().tracks.forward_axis);
  }
  EXPECT_GT(mean.normalized().dot(bearing_direction(90.0)), std::cos(30.0 * std::numbers::pi / 180.0));
}

TEST(Controller, SwitchesToTheTagAskedFor) {
  const auto& s = test::subject16();
  auto walk = s.context().tag_mask("walk"), run = s.context().tag_mask("run");
  ASSERT_TRUE(walk.ok() && run.ok());
  auto controller = Controller::create(s.context(), {}, {bearing_direction(0.0), *walk});
  ASSERT_TRUE(controller.ok());
  Motion motion = s.context().assembler.empty_motion();
  std::vector<TagMask> tags;
  auto play = [&](double until_s) {
    while (motion.frame_count < until_s * motion.fps) {
      const ControllerDecision d = controller->step(motion);
      for (int e : d.edges) {
        for (TagMask t : s.context().tracks.tags_of(e)) tags.push_back(t);
      }
    }
  };
  play(3.0);
  const size_t switch_frame = tags.size();
  controller->set_input({bearing_direction(0.0), *run});
  play(10.0);
  ASSERT_EQ(tags.size(), static_cast<size_t>(motion.frame_count));
  // Within two seconds of asking, and most of the time after, the frames are running.
  const size_t settle = switch_frame + static_cast<size_t>(2 * motion.fps);
  int running = 0;
  for (size_t f = settle; f < tags.size(); ++f) running += (tags[f] & *run) != 0 ? 1 : 0;
  EXPECT_GT(running, 0.8 * static_cast<double>(tags.size() - settle));
  int walking_before = 0;
  for (size_t f = 0; f < switch_frame; ++f) walking_before += (tags[f] & *walk) != 0 ? 1 : 0;
  EXPECT_GT(walking_before, 0.8 * static_cast<double>(switch_frame));
}

// Looking a third of a second ahead, no walk within the horizon reaches running from the walks
// of subject 16, so every one is as far from it: priced by how far each leaves the character
// from the tag (ControllerSettings::tag_lookahead), the search heads for it and runs within
// three seconds of being asked; seeing its horizon only (tag_lookahead 0), later or not at all.
TEST(Controller, ATagBeyondTheHorizonIsReached) {
  const auto& s = test::subject16();
  auto walk = s.context().tag_mask("walk"), run = s.context().tag_mask("run");
  ASSERT_TRUE(walk.ok() && run.ok());
  auto first_run_s = [&](bool beyond) -> double {
    ControllerSettings settings;
    settings.horizon_s = 0.3;
    if (!beyond) settings.tag_lookahead = 0.0;
    auto controller = Controller::create(s.context(), settings, {bearing_direction(0.0), *walk});
    EXPECT_TRUE(controller.ok());
    Motion motion = s.context().assembler.empty_motion();
    std::vector<TagMask> tags;
    const double asked = 3.0;
    while (motion.frame_count < 12.0 * motion.fps) {
      if (motion.frame_count >= asked * motion.fps) controller->set_input({bearing_direction(0.0), *run});
      for (int e : controller->step(motion).edges) {
        for (TagMask t : s.context().tracks.tags_of(e)) tags.push_back(t);
      }
    }
    for (size_t f = static_cast<size_t>(asked * motion.fps); f < tags.size(); ++f) {
      if ((tags[f] & *run) != 0) return f / motion.fps - asked;
    }
    return std::numeric_limits<double>::infinity();
  };
  const double beyond = first_run_s(true), horizon_only = first_run_s(false);
  EXPECT_LE(beyond, 3.0);
  EXPECT_GT(horizon_only, beyond);
}

// The costs to a tag are the context's: a second controller asking for the same tag with the
// same penalties finds them made, other penalties make their own.
TEST(Controller, TheWayToATagIsPricedOncePerContext) {
  const auto& s = test::subject16();
  SynthesisContext context = s.context();  // a copy: its own cache, not the other tests'
  context.tag_costs = std::make_shared<TagCostCache>();
  auto run = context.tag_mask("run");
  ASSERT_TRUE(run.ok());
  auto decide = [&](const ControllerSettings& settings) {
    auto controller = Controller::create(context, settings, {bearing_direction(0.0), *run});
    ASSERT_TRUE(controller.ok());
    Motion motion = context.assembler.empty_motion();
    controller->step(motion);
  };
  EXPECT_EQ(context.tag_costs->size(), 0u);
  decide({});
  EXPECT_EQ(context.tag_costs->size(), 1u);
  decide({});
  EXPECT_EQ(context.tag_costs->size(), 1u);
  ControllerSettings other;
  other.bridge_penalty = 5.0;
  decide(other);
  EXPECT_EQ(context.tag_costs->size(), 2u);
  ControllerSettings none;
  none.tag_lookahead = 0.0;
  decide(none);
  EXPECT_EQ(context.tag_costs->size(), 2u);
}

// Asked for no motion type, the character starts among the walking (the type most nodes carry;
// subject 16's node 0 is a jump, whose only ways out are bridges) and steers there: every heading
// reached, no bridge taken. Started on node 0 with bridges priced as any transition, the same
// session takes bridges.
TEST(Controller, AskedForNoMotionTypeItKeepsItsOwnWithoutBridges) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  const int start = controller_start_node(context, 0);
  EXPECT_NE(context.tracks.tags_of(context.graph->edge_offsets[start]).front() & *walk, 0u);
  EXPECT_EQ(controller_start_node(context, *walk), start);  // the first walking node
  auto session = [&](const ControllerSettings& settings, int* bridges) {
    auto controller = Controller::create(context, settings, {bearing_direction(0.0), 0});
    EXPECT_TRUE(controller.ok());
    Motion motion = context.assembler.empty_motion();
    const std::vector<double> headings = {0.0, 90.0, 200.0, 300.0, 45.0, 180.0};
    std::vector<double> responses;
    *bridges = 0;
    for (size_t i = 0; i < headings.size(); ++i) {
      controller->set_input({bearing_direction(headings[i]), 0});
      const double from_s = motion.frame_count / motion.fps;
      while (motion.frame_count < 4.0 * static_cast<double>(i + 1) * motion.fps) {
        for (int e : controller->step(motion).edges) *bridges += context.graph->edges[e].bridge ? 1 : 0;
      }
      responses.push_back(response_time(motion, context.tracks.forward_axis, from_s,
                                        bearing_direction(headings[i]), 20.0));
    }
    return responses;
  };
  int bridges = 0;
  for (double response : session({}, &bridges)) EXPECT_GE(response, 0.0);
  EXPECT_EQ(bridges, 0);
  ControllerSettings free;
  free.bridge_penalty = 0.0;
  free.start_node = 0;
  int free_bridges = 0;
  session(free, &free_bridges);
  EXPECT_GT(free_bridges, 0);
}

// Steering's heading edit (heading_edit.h): subject 16 walking east for 15 s weaved 0.34 m
// either side of its line as the graph plays it; edited it walks straight (1-2 cm), and every
// frame's floor step is as long as the one the graph plays for the same edges (the edit folded
// into the placement of what follows: no jump between decisions).
TEST(Controller, HeldToOneHeadingItWalksStraight) {
  const auto& s = test::subject16();
  auto walk = s.context().tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  auto play = [&](double max_turn) {
    ControllerSettings settings;
    settings.heading_edit.max_turn_deg_per_m = max_turn;
    auto controller = Controller::create(s.context(), settings, {bearing_direction(90.0), *walk});
    EXPECT_TRUE(controller.ok());
    Motion motion = s.context().assembler.empty_motion();
    Motion unedited = s.context().assembler.empty_motion();
    FloorTransform placement = controller->state().placement;
    while (motion.frame_count < 15 * motion.fps) {
      for (int e : controller->step(motion).edges) s.context().assembler.append_edge(e, placement, unedited);
    }
    EXPECT_EQ(unedited.frame_count, motion.frame_count);
    for (int f = 1; f < std::min(motion.frame_count, unedited.frame_count); ++f) {
      auto step = [f](const Motion& m) {
        const Vec3 d = m.translations(f)[0] - m.translations(f - 1)[0];
        return std::hypot(d.x(), d.z());
      };
      EXPECT_NEAR(step(motion), step(unedited), 1e-9) << f;
    }
    return motion;
  };
  // RMS distance of the root from its least-squares line after the first 3 s, and how far the
  // line is from east.
  auto weave = [](const Motion& m, double* line_bearing_deg) {
    std::vector<Vec2> roots;
    for (int f = 90; f < m.frame_count; ++f) roots.emplace_back(m.translations(f)[0].x(), m.translations(f)[0].z());
    Vec2 mean = Vec2::Zero();
    for (const Vec2& p : roots) mean += p;
    mean /= static_cast<double>(roots.size());
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    for (const Vec2& p : roots) scatter += (p - mean) * (p - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
    const Vec2 across = eig.eigenvectors().col(0);  // the least spread
    const Vec2 along = eig.eigenvectors().col(1);
    *line_bearing_deg = std::abs(std::asin(std::abs(along.y()))) * 180.0 / std::numbers::pi;  // 0: east-west
    double sum = 0.0;
    for (const Vec2& p : roots) sum += std::pow((p - mean).dot(across), 2);
    return std::sqrt(sum / static_cast<double>(roots.size()));
  };
  const Motion edited = play(HeadingEditSettings{}.max_turn_deg_per_m);
  const Motion unedited = play(0.0);
  double edited_line = 0.0, unedited_line = 0.0;
  const double edited_weave = weave(edited, &edited_line);
  const double unedited_weave = weave(unedited, &unedited_line);
  EXPECT_LT(edited_weave, 0.1);
  EXPECT_LT(edited_line, 10.0);
  EXPECT_GT(unedited_weave, 2.0 * edited_weave);
  EXPECT_GT(edited.translations(edited.frame_count - 1)[0].x(), 10.0);  // it went east
}

// The studio gives each step a motion of its own: the controller keeps what the edit needs, so
// the frames are those of one motion stepped through.
TEST(Controller, AMotionPerStepPlaysTheSameFrames) {
  const auto& s = test::subject16();
  auto walk = s.context().tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  auto one = Controller::create(s.context(), {}, {bearing_direction(0.0), *walk});
  auto each = Controller::create(s.context(), {}, {bearing_direction(0.0), *walk});
  ASSERT_TRUE(one.ok() && each.ok());
  Motion whole = s.context().assembler.empty_motion();
  std::vector<Quat> rotations;
  std::vector<Vec3> translations;
  for (int i = 0; i < 40; ++i) {
    const ControlInput input{bearing_direction(i < 20 ? 0.0 : 135.0), *walk};
    one->set_input(input);
    each->set_input(input);
    one->step(whole);
    Motion part = s.context().assembler.empty_motion();
    each->step(part);
    for (int f = 0; f < part.frame_count; ++f) {
      rotations.push_back(part.rotations(f)[0]);
      translations.push_back(part.translations(f)[0]);
    }
  }
  ASSERT_EQ(static_cast<int>(translations.size()), whole.frame_count);
  for (int f = 0; f < whole.frame_count; ++f) {
    ASSERT_EQ(whole.translations(f)[0], translations[f]) << f;
    ASSERT_EQ(whole.rotations(f)[0].coeffs(), rotations[f].coeffs()) << f;
  }
  EXPECT_GT(one->heading_edit_stats().added_turn_rad, 0.0);
}

// Default settings have no wall-clock budget: the same script gives the same motion, frame for
// frame, whatever the machine's load (a time budget made a loaded CI machine turn late).
TEST(Controller, SameInputsGiveTheSameMotion) {
  const auto& s = test::subject16();
  auto walk = s.context().tag_mask("walk"), run = s.context().tag_mask("run");
  ASSERT_TRUE(walk.ok() && run.ok());
  EXPECT_EQ(ControllerSettings{}.time_budget_s, 0.0);
  auto play = [&] {
    auto controller = Controller::create(s.context(), {}, {bearing_direction(0.0), *walk});
    EXPECT_TRUE(controller.ok());
    Motion motion = s.context().assembler.empty_motion();
    std::vector<int> edges;
    for (int turn = 0; turn < 6; ++turn) {
      controller->set_input({bearing_direction(60.0 * turn), turn >= 3 ? *run : *walk});
      while (motion.frame_count < (turn + 1) * 2 * motion.fps) {
        const ControllerDecision d = controller->step(motion);
        edges.insert(edges.end(), d.edges.begin(), d.edges.end());
      }
    }
    return std::make_pair(edges, motion);
  };
  const auto [edges_a, motion_a] = play();
  const auto [edges_b, motion_b] = play();
  EXPECT_EQ(edges_a, edges_b);
  ASSERT_EQ(motion_a.frame_count, motion_b.frame_count);
  for (int f = 0; f < motion_a.frame_count; ++f) {
    ASSERT_EQ(motion_a.translations(f)[0], motion_b.translations(f)[0]) << f;
  }
}

// The root's floor distance between two frames of a motion.
double floor_distance(const Motion& motion, int a, int b) {
  const Vec3 d = motion.translations(b)[0] - motion.translations(a)[0];
  return std::hypot(d.x(), d.z());
}

// The largest step of any joint from frame to frame in `m` from frame `from` on.
double largest_step(const SynthesisContext& context, const Motion& m, int from) {
  const std::vector<Vec3> world = world_positions(context.assembler.skeleton(), m);
  const size_t joints = static_cast<size_t>(m.joint_count);
  double largest = 0.0;
  for (int f = from + 1; f < m.frame_count; ++f) {
    for (size_t j = 0; j < joints; ++j) {
      largest = std::max(largest, (world[static_cast<size_t>(f) * joints + j] -
                                   world[static_cast<size_t>(f - 1) * joints + j]).norm());
    }
  }
  return largest;
}

// The context with no start from rest (rest_starts.h) from any frame its endings hold.
SynthesisContext without_starts(const SynthesisContext& context) {
  SynthesisContext out = context;
  out.start_cache = std::make_shared<SynthesisContext::StartCache>();
  for (const RestEnding& ending : context.rest().endings) out.start_cache->starts[ending.last_frame] = {};
  return out;
}

// A controller on `context` that walked north from its start asked to rest, played until it
// stands; its frames in `motion`.
Controller rested(const SynthesisContext& context, TagMask walk, Motion& motion) {
  auto controller = Controller::create(context, {}, {bearing_direction(0.0), walk});
  EXPECT_TRUE(controller.ok());
  motion = context.assembler.empty_motion();
  controller->set_input({bearing_direction(0.0), walk, true});
  while (!controller->standing() && motion.frame_count < 30 * motion.fps) controller->step(motion);
  EXPECT_TRUE(controller->standing()) << "not at rest";
  return std::move(*controller);
}

// Asked to rest, the character walks on to the end of a clip that ends standing (subject 16's
// stop is a dead end its pruning leaves out), plays it as captured, stands still, and where there
// is no start from the frame it holds, stays so whatever it is asked next.
TEST(Controller, ComesToRestWhenAskedAndStaysThere) {
  const auto& s = test::subject16();
  const SynthesisContext context = without_starts(s.context());
  const MotionGraph& graph = *context.graph;
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  auto controller = Controller::create(context, {}, {bearing_direction(0.0), *walk});
  ASSERT_TRUE(controller.ok());
  Motion motion = context.assembler.empty_motion();
  const double fps = motion.fps;
  while (motion.frame_count < 3 * fps) EXPECT_TRUE(controller->step(motion).rest_frames.empty());
  EXPECT_FALSE(controller->resting());
  EXPECT_EQ(controller->rest_frame(), -1);
  const int asked = motion.frame_count;
  controller->set_input({bearing_direction(0.0), *walk, true});
  std::vector<int> rest_frames;  // every frame played at rest, as the decisions say
  int ending_decision_first = -1;
  while (motion.frame_count < 12 * fps) {
    const int first = motion.frame_count;
    const bool was_resting = controller->resting();
    const ControllerDecision d = controller->step(motion);
    ASSERT_EQ(motion.frame_count - first, d.frames);
    int edge_frames = 0;
    for (int e : d.edges) edge_frames += graph.edges[e].frame_count;
    EXPECT_EQ(d.frames, edge_frames + static_cast<int>(d.rest_frames.size()));
    if (was_resting) {
      EXPECT_TRUE(d.edges.empty());
    }
    // A decision's worth of frames at a time, the stopping clip's too (a game shows each as it comes).
    EXPECT_LE(static_cast<long>(d.rest_frames.size()), std::lround(ControllerSettings{}.commit_s * motion.fps))
        << first;
    if (!was_resting && controller->resting()) ending_decision_first = first + edge_frames;
    rest_frames.insert(rest_frames.end(), d.rest_frames.begin(), d.rest_frames.end());
    if (motion.frame_count > 9 * fps) controller->set_input({bearing_direction(90.0), *walk});  // no way back
  }
  ASSERT_TRUE(controller->resting());
  EXPECT_TRUE(controller->rest_is_for_good());  // subject 16's stopping clips end where its graph does not go on
  EXPECT_TRUE(controller->starts().empty());
  const RestEnding* ending = controller->rest_ending();
  ASSERT_NE(ending, nullptr);
  // The ending as captured: its node's frame to the clip's last, then that last frame held.
  const std::vector<int> played = ending->frames(graph);
  ASSERT_GT(rest_frames.size(), played.size());
  EXPECT_TRUE(std::equal(played.begin(), played.end(), rest_frames.begin()));
  for (size_t i = played.size(); i < rest_frames.size(); ++i) ASSERT_EQ(rest_frames[i], ending->last_frame);
  // Standing from rest_frame: within a few seconds of asking, and still from there on.
  const long long still = controller->rest_frame();
  EXPECT_EQ(still, ending_decision_first + ending->frames_to_rest(graph));
  EXPECT_GT(still, asked);
  EXPECT_LT(still, asked + 6 * fps);
  EXPECT_GT(floor_distance(motion, asked, static_cast<int>(still)), 0.5);  // it walked there
  EXPECT_LT(floor_distance(motion, static_cast<int>(still), motion.frame_count - 1), 0.1);
  const int held = ending_decision_first + static_cast<int>(played.size()) - 1;
  for (int f = held + 1; f < motion.frame_count; ++f) {
    ASSERT_EQ(motion.translations(f)[0], motion.translations(held)[0]) << f;
    ASSERT_TRUE(motion.rotations(f)[0].isApprox(motion.rotations(held)[0], 0.0)) << f;
  }
}

// Where the frame held at rest is a node of the graph (a clip that stands and then starts off
// again), asked to move the character goes on from there: the frame it held, placed where it held
// it, then the graph's edges. Subject 16 has no such ending; one is made of two nodes of a clip.
TEST(Controller, GoesOnFromRestWhereTheGraphHasAWayOn) {
  const auto& s = test::subject16();
  SynthesisContext context = s.context();
  const MotionGraph& graph = *context.graph;
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  int held = 1;  // a node whose node before is of the same clip, a few frames back
  while (graph.nodes[held - 1].clip != graph.nodes[held].clip ||
         graph.nodes[held].frame - graph.nodes[held - 1].frame < 5) {
    ++held;
  }
  RestEndings made;
  made.of_node.assign(static_cast<size_t>(graph.node_count()), -1);
  made.of_node[static_cast<size_t>(held - 1)] = 0;
  made.endings.push_back({held - 1, graph.nodes[held].frame - 2, graph.nodes[held].frame});
  context.set_rest(std::move(made));
  auto controller = Controller::create(context, {}, {bearing_direction(0.0), *walk});
  ASSERT_TRUE(controller.ok());
  Motion motion = context.assembler.empty_motion();
  while (motion.frame_count < 2 * motion.fps) controller->step(motion);
  controller->set_input({bearing_direction(0.0), *walk, true});
  while (!controller->standing()) {  // on its way, then playing the clip it rests at a decision at a time
    ASSERT_LT(motion.frame_count, 20 * motion.fps) << "not at rest";
    controller->step(motion);
  }
  EXPECT_TRUE(controller->resting());
  EXPECT_FALSE(controller->rest_is_for_good());
  controller->step(motion);  // holding
  const int last_held = motion.frame_count - 1;
  controller->set_input({bearing_direction(0.0), *walk});
  const ControllerDecision on = controller->step(motion);
  EXPECT_FALSE(controller->resting());
  ASSERT_FALSE(on.edges.empty());
  EXPECT_TRUE(on.rest_frames.empty());
  EXPECT_EQ(graph.edges[on.edges.front()].from_node, held);
  // Its first frame is the frame held, where it was held (the heading edit turns it about its own
  // root by a little at most).
  EXPECT_LT(floor_distance(motion, last_held, last_held + 1), 0.01);
  while (motion.frame_count < last_held + 4 * motion.fps) controller->step(motion);
  EXPECT_GT(floor_distance(motion, last_held, motion.frame_count - 1), 2.0);
  EXPECT_EQ(controller->rest_frames().size(), 1u);
}

// Standing at the end of a stopping clip where the graph does not go on, asked to move, the
// character starts off (rest_starts.h): one decision blends the frame it holds into a lead-in and
// plays the lead-in on to its node, into the motion type it came to rest from when none is asked,
// and it then walks the way asked.
TEST(Controller, StartsOffFromRestWhenAskedToMove) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const MotionGraph& graph = *context.graph;
  const Vec3& axis = context.tracks.forward_axis;
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  for (const double heading : {90.0, 180.0}) {
    auto controller = Controller::create(context, {}, {bearing_direction(0.0), *walk});
    ASSERT_TRUE(controller.ok());
    Motion motion = context.assembler.empty_motion();
    const double fps = motion.fps;
    while (motion.frame_count < 2 * fps) controller->step(motion);
    controller->set_input({bearing_direction(0.0), *walk, true});
    while (!controller->standing() || motion.frame_count < 9 * fps) {
      controller->step(motion);
      ASSERT_LT(motion.frame_count, 30 * fps) << "not at rest";
    }
    const int held = motion.frame_count - 1;
    const RestEnding* ending = controller->rest_ending();
    ASSERT_NE(ending, nullptr);
    ASSERT_LT(graph.node_at_frame(ending->last_frame), 0) << "(a graph that goes on from the frame held)";
    EXPECT_FALSE(controller->rest_is_for_good());
    controller->set_input({bearing_direction(heading), 0});  // no motion type asked
    const ControllerDecision d = controller->step(motion);
    EXPECT_FALSE(controller->resting());
    ASSERT_EQ(controller->starts().size(), 1u);
    EXPECT_EQ(controller->starts()[0].frame, held + 1);
    const RestStart& start = controller->starts()[0].start;
    EXPECT_TRUE(d.edges.empty());
    EXPECT_TRUE(d.rest_frames.empty());
    ASSERT_EQ(d.frames, start.frames(graph));
    ASSERT_EQ(motion.frame_count, held + 1 + d.frames);
    ASSERT_EQ(d.start_frames.size(), static_cast<size_t>(d.frames));
    ASSERT_EQ(decision_transitions(graph, d), 1);
    // The frame held blended into the lead-in, then the lead-in as captured up to the node; each
    // frame with the contacts of the source weighing most, a gap where the weights cross filled.
    std::vector<ContactMask> contacts = context.sources_contacts(d.start_frames);
    fill_contact_gaps(contacts, FootContactSettings{}.max_gap_frames(fps));
    EXPECT_EQ(d.contacts, contacts);
    for (int i = 0; i < d.frames; ++i) {
      const FrameSource& source = d.start_frames[static_cast<size_t>(i)];
      EXPECT_EQ(source.arrival, start.first_frame + i);
      if (i < start.blend_frames) {
        EXPECT_EQ(source.departure, ending->last_frame);
        EXPECT_EQ(source.alpha, blend_weight(i, start.blend_frames));
      } else {
        EXPECT_EQ(source, (FrameSource{start.first_frame + i, start.first_frame + i, 1.0}));
      }
    }
    EXPECT_EQ(decision_sources(context, d), d.start_frames);
    // Into the motion type it came to rest from (subject 16 walked there).
    EXPECT_NE(context.frame_tag(graph.nodes[static_cast<size_t>(start.node)].frame) & *walk, 0u);
    // From where it stood: the first frame a blend weighing the frame held 0.98 or more, a few
    // millimetres off it; no joint steps from frame to frame across the start more than in the
    // lead-in as captured (the blend eases it in).
    EXPECT_LT(floor_distance(motion, held, held + 1), 0.01);
    Motion captured = context.assembler.empty_motion();
    for (int f = start.first_frame; f <= graph.nodes[static_cast<size_t>(start.node)].frame; ++f) {
      context.assembler.append_frame(f, FloorTransform{}, captured);
    }
    EXPECT_LE(largest_step(context, motion, held), largest_step(context, captured, 0) + 0.005) << "heading " << heading;
    // Then on through the graph, walking the way asked.
    while (motion.frame_count < held + 8 * fps) {
      EXPECT_TRUE(controller->step(motion).start_frames.empty());
    }
    EXPECT_GT(floor_distance(motion, held, motion.frame_count - 1), 3.0) << "heading " << heading;
    EXPECT_GT(facing_on_floor(motion.rotations(motion.frame_count - 1)[0], axis).dot(bearing_direction(heading)),
              std::cos(30.0 * std::numbers::pi / 180.0))
        << "heading " << heading;
    EXPECT_EQ(controller->starts().size(), 1u);
  }
}

// Asked to move once it stands still, before the stopping clip has played to its last frame, it
// starts off at once, from the frame it stands in (the still tail is no wait).
TEST(Controller, StartsOffAsSoonAsItStandsStill) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  auto controller = Controller::create(context, {}, {bearing_direction(0.0), *walk});
  ASSERT_TRUE(controller.ok());
  Motion motion = context.assembler.empty_motion();
  while (motion.frame_count < 2 * motion.fps) controller->step(motion);
  controller->set_input({bearing_direction(0.0), *walk, true});
  int last_played = -1;
  while (!controller->resting() || controller->rest_frame() < 0 || motion.frame_count <= controller->rest_frame()) {
    const ControllerDecision d = controller->step(motion);
    if (!d.rest_frames.empty()) last_played = d.rest_frames.back();
    ASSERT_LT(motion.frame_count, 30 * motion.fps) << "not at rest";
  }
  ASSERT_FALSE(controller->standing()) << "(the still tail played in one decision: nothing to show)";
  ASSERT_NE(last_played, controller->rest_ending()->last_frame);
  controller->set_input({bearing_direction(0.0), *walk});
  const ControllerDecision d = controller->step(motion);
  ASSERT_EQ(controller->starts().size(), 1u);
  ASSERT_FALSE(d.start_frames.empty());
  EXPECT_EQ(d.start_frames.front().departure, last_played);
  EXPECT_FALSE(controller->resting());
}

// A start turns toward the heading asked, about where the character stands, by at most
// kStartMaxTurnDeg (its lead-ins go the way the pose held faces): asked east it turns clockwise,
// asked west the other way, from the same rest; the heading edit adds no more than its rate over
// the start's travel.
TEST(Controller, AStartTurnsTowardTheHeadingAskedByAtMostItsLimit) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const Vec3& axis = context.tracks.forward_axis;
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  Motion motion;
  const Controller controller = rested(context, *walk, motion);
  const int held = motion.frame_count - 1;
  const Vec2 stood = facing_on_floor(motion.rotations(held)[0], axis);
  const double clockwise = yaw_between(Vec2(0.0, -1.0), Vec2(1.0, 0.0)) > 0.0 ? 1.0 : -1.0;  // north to east
  std::vector<double> turned;
  for (const double heading : {90.0, 270.0}) {
    Controller off = controller;
    Motion m = motion;
    off.set_input({bearing_direction(heading), *walk});
    const ControllerDecision d = off.step(m);
    ASSERT_FALSE(d.start_frames.empty());
    double travel = 0.0;
    for (int f = held + 1; f < m.frame_count; ++f) {
      travel += std::hypot(m.translations(f)[0].x() - m.translations(f - 1)[0].x(),
                           m.translations(f)[0].z() - m.translations(f - 1)[0].z());
    }
    // The captured lead-in's own turn over the start, as aligned on the pose held.
    const RestStart& start = off.starts().front().start;
    const double own = yaw_between(
        facing_on_floor(context.assembler.root_rotation(start.first_frame, start.alignment), axis),
        facing_on_floor(context.assembler.root_rotation(start.first_frame + d.frames - 1, start.alignment), axis));
    const double after = yaw_between(stood, facing_on_floor(m.rotations(m.frame_count - 1)[0], axis));
    const double deg = clockwise * (after - own) * 180.0 / std::numbers::pi;
    const double edit = ControllerSettings{}.heading_edit.max_turn_deg_per_m * travel;
    EXPECT_LE(std::abs(deg), kStartMaxTurnDeg + edit + 5.0) << "heading " << heading;
    turned.push_back(deg);
  }
  EXPECT_GT(turned[0], 20.0) << "east: clockwise";
  EXPECT_LT(turned[1], -20.0) << "west: the other way";
}

// The starts from the frame it will hold are found while it stops, before anything asks it to move
// (in the background: the 8-subject library's take 0.1 s); the controller waits
// for them when it goes.
TEST(Controller, FindsTheStartsWhileItStops) {
  const auto& s = test::subject16();
  SynthesisContext context = s.context();
  context.start_cache = std::make_shared<SynthesisContext::StartCache>();  // (none found yet)
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  int held = -1;
  {
    Motion motion;
    const Controller controller = rested(context, *walk, motion);
    held = controller.rest_ending()->last_frame;
  }
  const std::lock_guard<std::mutex> lock(context.start_cache->mutex);
  const auto found = context.start_cache->starts.find(held);
  ASSERT_NE(found, context.start_cache->starts.end());
  EXPECT_EQ(found->second.size(), find_rest_starts(*context.db, *context.graph, context.assembler, held).size());
}

// Asked for a motion type as it starts off, the start leads into it where one of the starts does.
TEST(Controller, StartsOffIntoTheMotionTypeAsked) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const MotionGraph& graph = *context.graph;
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  int tested = 0;
  for (const std::string& name : context.db->tag_names) {
    const TagMask tag = *context.tag_mask(name);
    Motion motion;
    Controller controller = rested(context, *walk, motion);
    const std::vector<RestStart>& starts = context.rest_starts(controller.rest_ending()->last_frame);
    const bool any = std::any_of(starts.begin(), starts.end(), [&](const RestStart& start) {
      return (context.frame_tag(graph.nodes[static_cast<size_t>(start.node)].frame) & tag) != 0;
    });
    controller.set_input({bearing_direction(0.0), tag});
    controller.step(motion);
    ASSERT_EQ(controller.starts().size(), 1u);
    const int node_frame = graph.nodes[static_cast<size_t>(controller.starts()[0].start.node)].frame;
    EXPECT_EQ((context.frame_tag(node_frame) & tag) != 0, any) << name;
    tested += any ? 1 : 0;
  }
  EXPECT_GE(tested, 2);  // walk, and another
  // (asking none, the type it came to rest from, or else the one the graph holds most of: walk)
  EXPECT_EQ(most_played_type(context), *walk);
}

// Asked to rest and then to walk before it stands, the character walks on; a graph with nowhere
// to rest does not hear rest at all.
TEST(Controller, RestTakenBackInTimeOrWithNowhereToRestWalksOn) {
  const auto& s = test::subject16();
  auto walk = s.context().tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  for (const bool nowhere : {false, true}) {
    SynthesisContext context = s.context();
    if (nowhere) context.set_rest({});
    auto controller = Controller::create(context, {}, {bearing_direction(0.0), *walk});
    ASSERT_TRUE(controller.ok());
    Motion motion = context.assembler.empty_motion();
    while (motion.frame_count < 2 * motion.fps) controller->step(motion);
    controller->set_input({bearing_direction(0.0), *walk, true});
    const ControllerDecision first = controller->step(motion);
    if (nowhere) {
      EXPECT_TRUE(first.rest_frames.empty());
      EXPECT_FALSE(controller->resting());
    }
    if (controller->resting()) continue;  // (its first decision took an ending: nothing to take back)
    const int from = motion.frame_count;
    if (!nowhere) controller->set_input({bearing_direction(0.0), *walk});
    while (motion.frame_count < from + 4 * motion.fps) {
      EXPECT_TRUE(controller->step(motion).rest_frames.empty());
    }
    EXPECT_FALSE(controller->resting());
    EXPECT_GT(floor_distance(motion, from, motion.frame_count - 1), 3.0)
        << (nowhere ? "nowhere to rest" : "taken back");
  }
}

// Asked to move on its way to rest, at each decision of its stopping clip before it stands still,
// the character takes the rest back: the rest it was coming to is none, and it goes on at once,
// on from a node of the graph the clip reaches (searching from it, or playing the clip on to it)
// or by a start from the frames it is playing (blended from them as they come), with no joint
// stepping more than in the captured clips; it travels farther in the next 1.5 s than by coming to
// rest first and starting off from there.
TEST(Controller, TakesARestBackOnItsWayThere) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const MotionGraph& graph = *context.graph;
  const MotionAssembler& assembler = context.assembler;
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  auto controller = Controller::create(context, {}, {bearing_direction(0.0), *walk});
  ASSERT_TRUE(controller.ok());
  Motion motion = context.assembler.empty_motion();
  const double fps = motion.fps;
  while (motion.frame_count < 2 * fps) controller->step(motion);
  controller->set_input({bearing_direction(0.0), *walk, true});
  std::vector<int> played;  // the stopping clip's frames played
  while (!controller->resting()) {
    const ControllerDecision d = controller->step(motion);
    played.insert(played.end(), d.rest_frames.begin(), d.rest_frames.end());
    ASSERT_LT(motion.frame_count, 30 * fps) << "not on its way to rest";
  }
  const RestEnding ending = *controller->rest_ending();
  const std::vector<int> ending_frames = ending.frames(graph);
  // (the captured stopping clip, and the walk before it)
  Motion captured = assembler.empty_motion();
  for (const int f : ending_frames) assembler.append_frame(f, FloorTransform{}, captured);
  const double captured_step =
      std::max(largest_step(context, captured, 0), largest_step(context, motion, 0));
  int starts = 0, early = 0;
  while (!controller->still()) {
    Controller back = *controller;
    Motion m = motion;
    const int asked = m.frame_count;
    back.set_input({bearing_direction(90.0), *walk});
    const ControllerDecision d = back.step(m);
    EXPECT_FALSE(back.resting());
    EXPECT_TRUE(back.rest_frames().empty());
    EXPECT_EQ(back.rest_ending(), nullptr);
    // Going on from the frame asked, or from the node the stop played on to.
    const long long went_on = asked + (d.start_frames.empty() ? std::ssize(d.rest_frames) : 0);
    EXPECT_EQ(back.rests_taken_back(), std::vector<long long>{went_on});
    if (!d.start_frames.empty()) {
      // Blended from the frames the stopping clip plays next (its last repeated) into the lead-in.
      ++starts;
      ASSERT_EQ(back.starts().size(), 1u);
      EXPECT_TRUE(back.starts()[0].under_way);
      const RestStart& start = back.starts()[0].start;
      for (int p = 0; p < start.blend_frames; ++p) {
        const size_t next = std::min(played.size() + static_cast<size_t>(p), ending_frames.size() - 1);
        EXPECT_EQ(d.start_frames[static_cast<size_t>(p)],
                  (FrameSource{ending_frames[next], start.first_frame + p, blend_weight(p, start.blend_frames)}));
      }
      std::vector<ContactMask> contacts = context.sources_contacts(d.start_frames);
      fill_contact_gaps(contacts, FootContactSettings{}.max_gap_frames(fps));
      EXPECT_EQ(d.contacts, contacts);
    } else if (!d.rest_frames.empty()) {
      // On to a node the clip reaches, as captured.
      EXPECT_TRUE(d.edges.empty());
      const size_t next = played.size() + d.rest_frames.size();
      ASSERT_LT(next, ending_frames.size());
      EXPECT_EQ(back.state().node, graph.node_at_frame(ending_frames[next]));
      EXPECT_LE(d.rest_frames.size(), static_cast<size_t>(std::lround(kStartBlendS * fps)));
    } else {
      // On from the clip's node where it has played nothing of the clip.
      EXPECT_TRUE(played.empty());
      EXPECT_FALSE(d.edges.empty());
      EXPECT_EQ(graph.edges[static_cast<size_t>(d.edges.front())].from_node, ending.node);
    }
    while (m.frame_count < asked + 1.5 * fps) back.step(m);
    EXPECT_LE(largest_step(context, m, asked - 1), captured_step + 0.01) << "asked at " << asked;
    // Coming to rest first, and asked to move once it stands still.
    Controller stopped = *controller;
    Motion n = motion;
    while (!stopped.still()) stopped.step(n);
    stopped.set_input({bearing_direction(90.0), *walk});
    while (n.frame_count < asked + 1.5 * fps) stopped.step(n);
    // (asked with less than a blend's time before it would stand still, about as far)
    const double went = floor_distance(m, asked - 1, asked + static_cast<int>(1.5 * fps) - 1);
    const double stopped_went = floor_distance(n, asked - 1, asked + static_cast<int>(1.5 * fps) - 1);
    const int before_still = ending.rest_frame - ending_frames[played.size()];
    if (before_still > std::lround(kStartBlendS * fps)) {
      EXPECT_GT(went, stopped_went + 0.2) << "asked at " << asked;
      ++early;
    } else {
      EXPECT_GT(went, stopped_went - 0.1) << "asked at " << asked;
    }
    const ControllerDecision d2 = controller->step(motion);
    played.insert(played.end(), d2.rest_frames.begin(), d2.rest_frames.end());
  }
  EXPECT_GE(early, 2);
  EXPECT_GE(starts, 1);
}

// A turn asked with rest: the way to rest is the same whatever the heading (the cheapest), but the
// heading edit turns it toward the heading asked, the stopping clip too as far as it travels, so
// that the character stands facing nearer the way asked than it would have.
TEST(Controller, ATurnAskedWithRestTurnsTheStoppingClipToo) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  const Vec3& axis = context.tracks.forward_axis;
  struct Run {
    Motion motion;
    std::vector<int> edges, rest_frames;
    int ending_first = -1;  // the motion's frame where the stopping clip starts
    double ending_travel_m = 0.0;
  };
  auto run = [&](double rest_heading_deg) {
    Run r{context.assembler.empty_motion(), {}, {}};
    auto controller = Controller::create(context, {}, {bearing_direction(0.0), *walk});
    EXPECT_TRUE(controller.ok());
    while (r.motion.frame_count < 2 * r.motion.fps) controller->step(r.motion);
    controller->set_input({bearing_direction(rest_heading_deg), *walk, true});
    while (!controller->standing() || r.motion.frame_count < 8 * r.motion.fps) {
      const int first = r.motion.frame_count;
      const ControllerDecision d = controller->step(r.motion);
      int edge_frames = 0;
      for (int e : d.edges) edge_frames += context.graph->edges[e].frame_count;
      if (r.ending_first < 0 && !d.rest_frames.empty()) r.ending_first = first + edge_frames;
      r.edges.insert(r.edges.end(), d.edges.begin(), d.edges.end());
      r.rest_frames.insert(r.rest_frames.end(), d.rest_frames.begin(), d.rest_frames.end());
      if (r.motion.frame_count > 20 * r.motion.fps) break;
    }
    EXPECT_TRUE(controller->standing());
    return r;
  };
  const Run north = run(0.0);
  const Run east = run(90.0);
  // The same way to rest and the same stopping clip.
  ASSERT_EQ(north.edges, east.edges);
  ASSERT_EQ(north.rest_frames, east.rest_frames);
  ASSERT_EQ(north.ending_first, east.ending_first);
  ASSERT_GT(north.ending_first, 0);
  // How much further clockwise (toward east) the east run faces, frame by frame.
  auto turned = [&](int f) {
    return yaw_between(facing_on_floor(north.motion.rotations(f)[0], axis),
                       facing_on_floor(east.motion.rotations(f)[0], axis));
  };
  const int last = east.motion.frame_count - 1;
  double travel = 0.0;
  for (int f = east.ending_first + 1; f <= last; ++f) {
    const Vec3 a = east.motion.translations(f - 1)[0], b = east.motion.translations(f)[0];
    travel += std::hypot(b.x() - a.x(), b.z() - a.z());
  }
  const double before = turned(east.ending_first), after = turned(last);
  const double sign = yaw_between(Vec2(0.0, -1.0), Vec2(1.0, 0.0)) > 0.0 ? 1.0 : -1.0;  // north to east
  EXPECT_GT(sign * before, 0.0) << "the way there turns toward east";
  // The stopping clip turns on by 5 degrees or more, within what the edit may add over its travel
  // (each of the two runs at most max_turn_deg_per_m, the one turning one way, the other the other).
  const double limit = 2.0 * ControllerSettings{}.heading_edit.max_turn_deg_per_m * travel;
  EXPECT_GT(sign * (after - before) * 180.0 / std::numbers::pi, 5.0) << "travel " << travel << " m";
  EXPECT_LE(std::abs(after - before) * 180.0 / std::numbers::pi, limit + 1e-6);
  // It stands facing nearer east than north does (closer to the way asked).
  const Vec2 held_east = facing_on_floor(east.motion.rotations(last)[0], axis);
  const Vec2 held_north = facing_on_floor(north.motion.rotations(last)[0], axis);
  EXPECT_GT(held_east.dot(Vec2(1.0, 0.0)), held_north.dot(Vec2(1.0, 0.0)));
}

// Turned toward a heading as it stops, cleaned as the CLI's steer cleans each decision, the
// character stands as the stopping clip stands: its ankles as far apart as in the clip's last
// frame (the turn went on while a foot was planted for good, and the clean-up held that foot
// where it planted: 3 cm apart for 8 on a right turn, 16 on a left).
TEST(Controller, ATurnAskedWithRestKeepsTheStanceItStopsIn) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  const Skeleton& skeleton = context.assembler.skeleton();
  const FootJoints& feet = context.feet;
  auto apart = [&](const Motion& motion, int f) {
    const std::vector<Vec3> world = world_positions(skeleton, motion.slice(f, 1));
    const Vec3 d = world[static_cast<size_t>(feet.right.ankle)] - world[static_cast<size_t>(feet.left.ankle)];
    return std::hypot(d.x(), d.z());
  };
  for (const double heading : {90.0, 135.0, 270.0}) {
    auto controller = Controller::create(context, {}, {bearing_direction(0.0), *walk});
    ASSERT_TRUE(controller.ok());
    auto cleanup = context.foot_cleanup({});
    ASSERT_TRUE(cleanup.ok()) << cleanup.error().to_string();
    Motion motion = context.assembler.empty_motion();
    while (!controller->standing() || motion.frame_count < 10 * motion.fps) {
      if (motion.frame_count >= 3 * motion.fps) controller->set_input({bearing_direction(heading), *walk, true});
      const int first = motion.frame_count;
      const ControllerDecision d = controller->step(motion);
      ASSERT_EQ(d.contacts.size(), static_cast<size_t>(d.frames));
      ASSERT_TRUE(cleanup->clean(motion, first, d.contacts).ok());
      ASSERT_LT(motion.frame_count, 30 * motion.fps) << "not at rest";
    }
    const RestEnding* ending = controller->rest_ending();
    ASSERT_NE(ending, nullptr);
    Motion captured = context.assembler.empty_motion();
    context.assembler.append_frame(ending->last_frame, FloorTransform{}, captured);
    EXPECT_NEAR(apart(motion, motion.frame_count - 1), apart(captured, 0), 0.015) << "heading " << heading;
  }
}

// A decision's contacts are its frames' own (the edges', then the rest frames'), but for the foot a
// stopping clip pivots on while the heading edit turns it; with no heading edit, all its own.
TEST(Controller, ADecisionsContactsAreItsFramesButThePivotingFoot) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  auto walk = context.tag_mask("walk");
  ASSERT_TRUE(walk.ok());
  for (const double max_turn : {45.0, 0.0}) {
    ControllerSettings settings;
    settings.heading_edit.max_turn_deg_per_m = max_turn;
    auto controller = Controller::create(context, settings, {bearing_direction(0.0), *walk});
    ASSERT_TRUE(controller.ok());
    Motion motion = context.assembler.empty_motion();
    int freed = 0;
    while (!controller->standing() || motion.frame_count < 10 * motion.fps) {
      if (motion.frame_count >= 3 * motion.fps) controller->set_input({bearing_direction(90.0), *walk, true});
      const ControllerDecision d = controller->step(motion);
      std::vector<ContactMask> own = context.edges_contacts(d.edges);
      const std::vector<ContactMask> resting = context.frames_contacts(d.rest_frames);
      own.insert(own.end(), resting.begin(), resting.end());
      ASSERT_EQ(d.contacts.size(), own.size());
      for (size_t i = 0; i < own.size(); ++i) {
        ASSERT_EQ(d.contacts[i] & ~own[i], 0) << "a contact the frame has not";
        freed += d.contacts[i] != own[i] ? 1 : 0;
      }
      ASSERT_LT(motion.frame_count, 30 * motion.fps) << "not at rest";
    }
    if (max_turn > 0.0) {
      EXPECT_GT(freed, 0);
    } else {
      EXPECT_EQ(freed, 0);
    }
  }
  // A graph whose feet are not known: no contacts, on the way to rest, at it and starting off.
  SynthesisContext footless = context;
  footless.frame_contacts.clear();
  auto controller = Controller::create(footless, {}, {bearing_direction(0.0), *walk, true});
  ASSERT_TRUE(controller.ok());
  Motion motion = footless.assembler.empty_motion();
  while (!controller->standing() || motion.frame_count < 8 * motion.fps) {
    const ControllerDecision d = controller->step(motion);
    EXPECT_TRUE(d.contacts.empty()) << motion.frame_count;
    ASSERT_LT(motion.frame_count, 30 * motion.fps) << "not at rest";
  }
  controller->set_input({bearing_direction(90.0), *walk});
  const ControllerDecision off = controller->step(motion);
  EXPECT_FALSE(off.start_frames.empty());
  EXPECT_TRUE(off.contacts.empty());
}

// A wall-clock budget far too small for any search still gets frames from every decision.
TEST(Controller, AStarvedTimeBudgetStillAnswers) {
  const auto& s = test::subject16();
  ControllerSettings settings;
  settings.time_budget_s = 1e-9;
  auto controller = Controller::create(s.context(), settings, {bearing_direction(90.0), 0});
  ASSERT_TRUE(controller.ok());
  Motion motion = s.context().assembler.empty_motion();
  for (int i = 0; i < 50; ++i) {
    const ControllerDecision d = controller->step(motion);
    EXPECT_GT(d.frames, 0);
    EXPECT_FALSE(d.edges.empty());
  }
  EXPECT_GE(motion.frame_count, 50 * static_cast<int>(settings.commit_s * motion.fps));
  // Each setting out of range said by its name.
  for (auto [spoil, named] : {std::pair{+[](ControllerSettings& c) { c.time_budget_s = -1.0; }, "time budget"},
                              {+[](ControllerSettings& c) { c.beam_width = -1; }, "beam width"},
                              {+[](ControllerSettings& c) { c.max_expansions = 0; }, "search budget"},
                              {+[](ControllerSettings& c) { c.tag_penalty = -1.0; }, "tag penalty"},
                              {+[](ControllerSettings& c) { c.travel_mps = -1.0; }, "travel pace"},
                              {+[](ControllerSettings& c) { c.travel_mps = 1e16; }, "travel pace must be at most"},
                              {+[](ControllerSettings& c) { c.travel_penalty = 1e308; }, "its penalty at most"},
                              {+[](ControllerSettings& c) { c.start_node = -2; }, "start node must be >= 0, not -2"}}) {
    ControllerSettings bad;
    spoil(bad);
    ASSERT_FALSE(bad.validate().ok());
    EXPECT_NE(bad.validate().error().message.find(named), std::string::npos) << bad.validate().error().message;
    EXPECT_FALSE(Controller::create(s.context(), bad, {bearing_direction(0.0), 0}).ok());
  }
}

}  // namespace
}  // namespace mg
