#include "motiongraph/synthesis/path_synthesis.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/synthesis/loaded_graph.h"
#include "synthesis/subject16_graph.h"
#include "test_data.h"

namespace mg {
namespace {

// The figure 8 of 4 m loops asking for `first` over its first half and `second` over the rest.
FloorPath figure8_halves(const std::string& first, const std::string& second) {
  auto shape = make_shape("figure8:4");
  if (!shape) throw std::runtime_error(shape.error().to_string());
  const double half = shape->length_m() / 2;
  auto path = FloorPath::create(shape->points(), {{0.0, half, first}, {half, shape->length_m() + 1.0, second}});
  if (!path) throw std::runtime_error(path.error().to_string());
  return *path;
}

TEST(PathSynthesis, FollowsTheBuiltInShapes) {
  const auto& s = test::subject16();
  int first_attempts = 0;  // shapes both searches follow at their first attempt
  for (const char* spec : {"line:20", "circle:5", "figure8:4", "s-curve:100"}) {
    auto path = make_shape(spec);
    ASSERT_TRUE(path.ok());
    auto result = synthesize_path(s.context(), *path);
    ASSERT_TRUE(result.ok()) << result.error().to_string();
    EXPECT_TRUE(result->reached_end) << spec;
    EXPECT_LT(result->mean_deviation_m, 0.15) << spec;
    EXPECT_GE(result->arc_covered_m, path->length_m() - kEndReachedM) << spec;
    EXPECT_LE(result->arc_covered_m, path->length_m()) << spec;
    // The deviation, the way along the path and the end's distance are measured again here,
    // from the motion's own root, against the path; the motion stops at the first frame
    // furthest along it.
    double sum = 0.0;
    std::vector<Vec2> roots;
    for (int f = 0; f < result->motion.frame_count; ++f) {
      const Vec3& root = result->motion.translations(f)[0];
      roots.emplace_back(root.x(), root.z());
      sum += path->distance_to(roots.back());
    }
    EXPECT_NEAR(sum / result->motion.frame_count, result->mean_deviation_m, 1e-9) << spec;
    const std::vector<double> arcs = path->followed_arcs(roots);
    EXPECT_EQ(arcs.back(), result->arc_covered_m) << spec;
    for (size_t f = 0; f + 1 < arcs.size(); ++f) ASSERT_LT(arcs[f], arcs.back()) << spec << " frame " << f;
    EXPECT_NEAR((roots.back() - path->points().back()).norm(), result->end_distance_m, 1e-12) << spec;
    EXPECT_LT(result->end_distance_m, 1.0) << spec;
    // The walk is the one that plays those frames: its last edge plays the last of them.
    const MotionGraph& graph = *s.context().graph;
    const long long frames = result->walk.frame_count(graph) + 1;
    EXPECT_GE(frames, result->motion.frame_count) << spec;
    EXPECT_LT(frames - graph.edges[result->walk.edges.back()].frame_count, result->motion.frame_count) << spec;
    // The graph follows the path by itself; the edit (on by default) bends its motion closer.
    EXPECT_TRUE(result->edit.edited) << spec;
    EXPECT_LT(result->graph_mean_deviation_m, 0.15) << spec;
    EXPECT_LT(result->mean_deviation_m, result->graph_mean_deviation_m) << spec;
    // Without the edit the search finds the same walk up to where its root has travelled the
    // path's length (there each looks at how far along the path its motion got, edited or not,
    // and may go on), and its motion is the graph's. That is for the first attempts: where one
    // of the two needed another (retries search otherwise), the walks differ from the start.
    PathSynthesisSettings unedited;
    unedited.edit_path = false;
    auto plain = synthesize_path(s.context(), *path, unedited);
    ASSERT_TRUE(plain.ok());
    EXPECT_TRUE(plain->reached_end) << spec;
    EXPECT_FALSE(plain->edit.edited);
    EXPECT_EQ(plain->graph_mean_deviation_m, plain->mean_deviation_m) << spec;
    EXPECT_EQ(plain->graph_max_deviation_m, plain->max_deviation_m) << spec;
    if (plain->attempts > 1 || result->attempts > 1) continue;
    ++first_attempts;
    EXPECT_EQ(plain->motion.translations(0)[0], result->motion.translations(0)[0]) << spec;
    size_t travelled_edges = 0;
    double travelled = 0.0;
    for (size_t f = 1, frame_end = 1; f < plain->roots.size() && travelled < path->length_m(); ++f) {
      travelled += (plain->roots[f] - plain->roots[f - 1]).norm();
      while (frame_end <= f) frame_end += graph.edges[plain->walk.edges[travelled_edges++]].frame_count;
    }
    ASSERT_GT(travelled_edges, 0u);
    ASSERT_LE(travelled_edges, std::min(plain->walk.edges.size(), result->walk.edges.size())) << spec;
    EXPECT_TRUE(std::equal(plain->walk.edges.begin(), plain->walk.edges.begin() + travelled_edges,
                           result->walk.edges.begin()))
        << spec;
  }
  EXPECT_GE(first_attempts, 2);  // subject 16: the line and the figure 8; without the edit the others retry
}

// The root's mean direction of travel (the travel axis), not the hips' facing, goes along the path.
// Asked to come to rest at the end, the character walks the path and stands at its end: the walk
// goes on to the end of a clip that ends standing still, played as captured, and its root stands
// still from the frame the result gives to the last; the motion is the walk's edges and that clip's
// frames, edited onto the path.
TEST(PathSynthesis, ComesToRestAtThePathsEndWhenAsked) {
  const auto& s = test::subject16();
  const MotionGraph& graph = *s.context().graph;
  PathSynthesisSettings settings;
  settings.rest_at_end = true;
  for (const char* spec : {"line:12", "circle:4", "square:6"}) {
    auto path = make_shape(spec);
    ASSERT_TRUE(path.ok());
    auto plain = synthesize_path(s.context(), *path);
    ASSERT_TRUE(plain.ok());
    EXPECT_EQ(plain->rest, nullptr);
    EXPECT_TRUE(plain->walk.rest_frames.empty());
    auto result = synthesize_path(s.context(), *path, settings);
    ASSERT_TRUE(result.ok()) << spec << ": " << result.error().to_string();
    ASSERT_NE(result->rest, nullptr) << spec;
    const RestEnding& ending = *result->rest;
    EXPECT_EQ(result->walk.rest_frames, ending.frames(graph)) << spec;
    EXPECT_TRUE(check_walk(graph, result->walk).ok()) << spec;
    EXPECT_EQ(result->motion.frame_count,
              result->walk.frame_count(graph) + static_cast<long long>(result->walk.rest_frames.size()));
    EXPECT_EQ(result->rest_frame, result->motion.frame_count - 1 - (ending.last_frame - ending.rest_frame)) << spec;
    // Standing at the path's end: within half a metre of it, still from the rest frame on.
    EXPECT_LT(result->end_distance_m, 0.5) << spec;
    EXPECT_TRUE(result->reached_end) << spec;
    const Vec2 still = result->roots[static_cast<size_t>(result->rest_frame)];
    for (size_t f = static_cast<size_t>(result->rest_frame); f < result->roots.size(); ++f) {
      EXPECT_LT((result->roots[f] - still).norm(), 0.1) << spec << " frame " << f;
    }
    // Walking before it (two seconds before, more than half a metre from where it stands); the frames
    // carry the tags of the frames they play (the clip's own at rest).
    EXPECT_GT((result->roots[static_cast<size_t>(result->rest_frame) - 60] - still).norm(), 0.5) << spec;
    ASSERT_EQ(result->frame_tags.size(), static_cast<size_t>(result->motion.frame_count));
    EXPECT_EQ(result->frame_tags.back(), s.context().frame_tags[static_cast<size_t>(ending.last_frame)]);
  }
  // A graph with no clip that ends standing still: an error saying so.
  SynthesisContext nowhere = s.context();
  nowhere.set_rest({});
  auto refused = synthesize_path(nowhere, *make_shape("line:12"), settings);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("no clip of the graph ends standing still"), std::string::npos);
}

// A path shorter than the way to rest from where its walk starts (the 1 m line's walk started
// running, and stood 5.3 m past the end) starts at a node of a clip that stops instead, the
// ending whose travel to standing is nearest the path's length; a start node given is kept.
TEST(PathSynthesis, AShortPathEndingAtRestStartsAtAClipThatStops) {
  const auto& s = test::subject16();
  const MotionGraph& graph = *s.context().graph;
  PathSynthesisSettings settings;
  settings.rest_at_end = true;
  for (const char* spec : {"line:1", "line:1.5"}) {
    auto path = make_shape(spec);
    ASSERT_TRUE(path.ok());
    auto result = synthesize_path(s.context(), *path, settings);
    ASSERT_TRUE(result.ok()) << spec << ": " << result.error().to_string();
    ASSERT_NE(result->rest, nullptr) << spec;
    EXPECT_LT(result->end_distance_m, kEndReachedM) << spec;
    if (std::string(spec) == "line:1") {  // (its walk's own way stood 5.3 m past the end)
      EXPECT_NE(s.context().rest().at(result->walk.start_node), nullptr) << spec << ": started at a clip that stops";
    }
    EXPECT_TRUE(check_walk(graph, result->walk).ok()) << spec;
    const Vec2 still = result->roots[static_cast<size_t>(result->rest_frame)];
    for (size_t f = static_cast<size_t>(result->rest_frame); f < result->roots.size(); ++f) {
      EXPECT_LT((result->roots[f] - still).norm(), 0.1) << spec << " frame " << f;
    }
  }
  // Its start node given: kept, and the way to rest stands where it can.
  auto line = make_shape("line:1");
  ASSERT_TRUE(line.ok());
  auto walked = synthesize_path(s.context(), *line);
  ASSERT_TRUE(walked.ok());
  settings.start_node = walked->walk.start_node;
  auto kept = synthesize_path(s.context(), *line, settings);
  ASSERT_TRUE(kept.ok()) << kept.error().to_string();
  EXPECT_EQ(kept->walk.start_node, walked->walk.start_node);
}

TEST(PathSynthesis, StartsAtThePathsStartHeadingAlongIt) {
  const auto& s = test::subject16();
  auto path = FloorPath::create({{3.0, 4.0}, {13.0, 4.0}});  // heading east (+x)
  ASSERT_TRUE(path.ok());
  auto result = synthesize_path(s.context(), *path);
  ASSERT_TRUE(result.ok());
  const Vec3& root = result->motion.translations(0)[0];
  EXPECT_LT((Vec2(root.x(), root.z()) - Vec2(3.0, 4.0)).norm(), 1e-9);
  const Vec2 heading = facing_on_floor(result->motion.rotations(0)[0], s.context().tracks.travel_axis);
  EXPECT_GT(heading.dot(Vec2(1.0, 0.0)), 0.999999);
}

TEST(PathSynthesis, StopsWhenAsked) {
  const auto& s = test::subject16();
  auto path = FloorPath::create({{0.0, 0.0}, {10.0, 0.0}});
  ASSERT_TRUE(path.ok());
  PathSynthesisSettings settings;
  std::stop_source stop;
  settings.stop = stop.get_token();
  ASSERT_TRUE(synthesize_path(s.context(), *path, settings).ok());  // not asked: made
  stop.request_stop();
  auto result = synthesize_path(s.context(), *path, settings);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().kind, ErrorKind::kStopped);
}

TEST(PathSynthesis, WalksThenRunsWhereTheSegmentsAsk) {
  const auto& s = test::subject16();
  const FloorPath path = figure8_halves("walk", "run");
  const double half = path.length_m() / 2;
  auto result = synthesize_path(s.context(), path);
  ASSERT_TRUE(result.ok()) << result.error().to_string();
  EXPECT_TRUE(result->reached_end);
  EXPECT_GT(result->tag_match, 0.85);
  // Running covers the second half faster than walking covered the first.
  int half_frame = 0;
  double arc = 0.0;
  for (size_t f = 1; f < result->roots.size() && arc < half; ++f) {
    arc += (result->roots[f] - result->roots[f - 1]).norm();
    half_frame = static_cast<int>(f);
  }
  EXPECT_LT(result->motion.frame_count - half_frame, half_frame);
}

// Bridges lead into the motion type asked for: walking then running and running then walking,
// the walk changes type through bridges into the type of the second half (subject 16's walking
// and running join only through them), not by way of a jump or any third type.
TEST(PathSynthesis, BridgesLeadIntoTheMotionTypeAsked) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  for (const auto& [first, second] : {std::pair{"walk", "run"}, std::pair{"run", "walk"}}) {
    auto result = synthesize_path(context, figure8_halves(first, second));
    ASSERT_TRUE(result.ok()) << result.error().to_string();
    int bridges = 0;
    for (int e : result->walk.edges) {
      const GraphEdge& edge = context.graph->edges[e];
      if (!edge.bridge) continue;
      ++bridges;
      EXPECT_NE(bridge_landing_tags(context, edge) & *context.tag_mask(second), 0u)
          << first << " then " << second << ": edge " << e;
    }
    EXPECT_GE(bridges, 1) << first << " then " << second;
  }
}

// Each segment's frames and match, counted again here from the motion's roots followed along the
// path and its frames' tags: overlapping segments give their frames to the last given (as the
// search asks), one beyond the end gets none, and together they make the whole match.
TEST(PathSynthesis, EachSegmentsMatchIsItsFrames) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  auto shape = make_shape("figure8:4");
  ASSERT_TRUE(shape.ok());
  const double length = shape->length_m();
  auto path = FloorPath::create(shape->points(), {{0.0, 30.0, "walk"},
                                                  {20.0, 40.0, "run"},  // over the walk's last 10 m
                                                  {35.0, 45.0, "jump"},
                                                  {length + 5.0, length + 9.0, "walk"}});
  ASSERT_TRUE(path.ok());
  auto result = synthesize_path(context, *path);
  ASSERT_TRUE(result.ok()) << result.error().to_string();
  const auto& segments = path->segments();
  ASSERT_EQ(result->segment_tag_matches.size(), segments.size());
  const std::vector<double> arcs = path->followed_arcs(result->roots);
  ASSERT_EQ(arcs.size(), result->frame_tags.size());
  std::vector<int> frames(segments.size(), 0), matched(segments.size(), 0);
  for (size_t f = 0; f < arcs.size(); ++f) {
    int owner = -1;
    for (size_t i = 0; i < segments.size(); ++i) {
      if (arcs[f] >= segments[i].from_m && arcs[f] < segments[i].to_m) owner = static_cast<int>(i);
    }
    if (owner < 0) continue;
    ++frames[static_cast<size_t>(owner)];
    matched[static_cast<size_t>(owner)] += (result->frame_tags[f] & *context.tag_mask(segments[owner].tag)) != 0;
  }
  int all = 0, all_matched = 0;
  for (size_t i = 0; i < segments.size(); ++i) {
    EXPECT_EQ(result->segment_tag_matches[i].frames, frames[i]) << i;
    EXPECT_EQ(result->segment_tag_matches[i].matched, matched[i]) << i;
    all += frames[i];
    all_matched += matched[i];
  }
  EXPECT_GT(frames[0], 0);
  EXPECT_GT(frames[1], 0);
  EXPECT_GT(frames[2], 0);
  EXPECT_EQ(frames[3], 0);  // past the path's end
  EXPECT_DOUBLE_EQ(result->tag_match, static_cast<double>(all_matched) / all);
}

TEST(PathSynthesis, UnknownTagsAndBadSettingsAreErrors) {
  const auto& s = test::subject16();
  auto path = FloorPath::create({{0.0, 0.0}, {5.0, 0.0}}, {{0.0, 5.0, "swim"}});
  ASSERT_TRUE(path.ok());
  auto result = synthesize_path(s.context(), *path);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("'swim' is not a motion tag"), std::string::npos);
  PathSynthesisSettings bad;
  bad.commit_s = 5.0;  // longer than the horizon
  EXPECT_FALSE(bad.validate().ok());
  bad = {};
  bad.min_speed_mps = -1.0;
  EXPECT_FALSE(bad.validate().ok());
  bad = {};
  bad.behind_penalty_m = -0.5;
  EXPECT_FALSE(bad.validate().ok());
  bad = {};
  bad.beam_width = -1;
  EXPECT_FALSE(bad.validate().ok());
  // Beams and retries that would take memory or time without end (a beam of 2e9 ran out of memory).
  bad.beam_width = kMaxBeamWidth + 1;
  EXPECT_FALSE(bad.validate().ok());
  bad.beam_width = kMaxBeamWidth;
  EXPECT_TRUE(bad.validate().ok());
  bad = {};
  bad.progress_retries = 101;
  EXPECT_FALSE(bad.validate().ok());
  bad = {};
  bad.start_node = -2;  // -1: the search's choice
  EXPECT_FALSE(bad.validate().ok());
  bad.start_node = -1;
  EXPECT_TRUE(bad.validate().ok());
  bad = {};
  bad.retry_horizon_s = -1.0;
  EXPECT_FALSE(bad.validate().ok());
  bad.retry_horizon_s = 0.5;  // shorter than the commit
  EXPECT_FALSE(bad.validate().ok());
  bad.retry_horizon_s = 0.0;  // the first search's
  EXPECT_TRUE(bad.validate().ok());
  for (double share : {-0.1, 1.5, std::nan("")}) {
    bad.retry_tag_match = share;
    EXPECT_FALSE(bad.validate().ok()) << share;
  }
  for (auto penalty : {&PathSynthesisSettings::tag_penalty_m2, &PathSynthesisSettings::transition_penalty_m2,
                       &PathSynthesisSettings::bridge_penalty_m2, &PathSynthesisSettings::min_speed_mps,
                       &PathSynthesisSettings::behind_penalty_m, &PathSynthesisSettings::retry_deviation_m,
                       &PathSynthesisSettings::retry_horizon_s, &PathSynthesisSettings::horizon_s}) {
    bad = {};
    bad.*penalty = std::numeric_limits<double>::infinity();  // a motion of one frame, with min_speed
    auto refused = bad.validate();
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("not inf"), std::string::npos) << refused.error().message;
  }
  // Horizons of at most a minute (1e5 s ran out of memory).
  bad = {};
  bad.horizon_s = kMaxHorizonS;
  EXPECT_TRUE(bad.validate().ok());
  bad.horizon_s = 61.0;
  EXPECT_EQ(bad.validate().error().message, "path search: the horizon must be above 0 s and at most 60 s, not 61 s");
  bad = {};
  bad.retry_horizon_s = 61.0;
  EXPECT_FALSE(bad.validate().ok());
  // Said of what is wrong (an infinite turn was called a smoothing).
  bad = {};
  bad.path_edit.max_turn_deg_per_m = std::numeric_limits<double>::infinity();
  EXPECT_EQ(bad.validate().error().message,
            "path edit: the turning it may add must be finite and >= 0 degrees per metre, not inf");
}

// A walk that misses the motion type a segment asks for is searched again, the tag priced 4x
// higher at each retry while the best so far misses it: asked to walk then run round subject 16's
// figure 8 with a tag penalty too low to matter, the first search walks on (reaching the end,
// close to the path); the retries run.
TEST(PathSynthesis, AWalkThatMissesTheTypeAskedIsSearchedAgainPricingItHigher) {
  const auto& s = test::subject16();
  const FloorPath path = figure8_halves("walk", "run");
  PathSynthesisSettings once;
  once.tag_penalty_m2 = 0.01;
  once.progress_retries = 0;
  auto missed = synthesize_path(s.context(), path, once);
  ASSERT_TRUE(missed.ok()) << missed.error().to_string();
  ASSERT_TRUE(missed->reached_end);
  ASSERT_LE(missed->mean_deviation_m, once.retry_deviation_m);
  const auto& run = missed->segment_tag_matches[1];
  ASSERT_GE(run.frames, kTagMissMinSeconds * s.context().db->fps);
  ASSERT_LT(run.matched, once.retry_tag_match * run.frames);  // walked on
  EXPECT_EQ(missed->tag_penalty_m2, once.tag_penalty_m2);
  EXPECT_EQ(missed->missed_segments, std::vector<int>{1});  // the kept attempt's shortfall, said to the user

  PathSynthesisSettings pushing = once;
  pushing.progress_retries = 4;
  auto ran = synthesize_path(s.context(), path, pushing);
  ASSERT_TRUE(ran.ok());
  EXPECT_GT(ran->attempts, 1);
  EXPECT_TRUE(ran->reached_end);
  const auto& running = ran->segment_tag_matches[1];
  EXPECT_GE(running.matched, pushing.retry_tag_match * running.frames) << running.matched << " of " << running.frames;
  EXPECT_TRUE(ran->missed_segments.empty());
  // The kept attempt's penalty: 4x per retry made while the best missed the run.
  bool stepped = false;
  for (double p = 4.0 * once.tag_penalty_m2; p <= std::pow(4.0, pushing.progress_retries) * once.tag_penalty_m2;
       p *= 4.0) {
    stepped = stepped || std::abs(ran->tag_penalty_m2 - p) < 1e-12;
  }
  EXPECT_TRUE(stepped) << ran->tag_penalty_m2;

  // Not for a missed type: the first search is good enough; nor with no tag penalty to raise.
  PathSynthesisSettings indifferent = pushing;
  indifferent.retry_tag_match = 0.0;
  PathSynthesisSettings untagged = pushing;
  untagged.tag_penalty_m2 = 0.0;
  for (const PathSynthesisSettings& settings : {indifferent, untagged}) {
    auto walked = synthesize_path(s.context(), path, settings);
    ASSERT_TRUE(walked.ok());
    ASSERT_TRUE(walked->reached_end);
    ASSERT_LE(walked->mean_deviation_m, settings.retry_deviation_m);
    EXPECT_LT(walked->segment_tag_matches[1].matched, pushing.retry_tag_match * walked->segment_tag_matches[1].frames);
    EXPECT_EQ(walked->attempts, 1) << settings.tag_penalty_m2;
  }
}

// A segment asking for a motion type the graph plays in no frame (its frames pruned away) asks
// the search for nothing: subject 16's graph with a tag no frame carries, asked for over the
// figure 8's second half, plays what the path asking nothing there plays, frame for frame, and is
// not searched again for the type it cannot play.
TEST(PathSynthesis, ASegmentAskingForATypeTheGraphCannotPlayAsksForNothing) {
  GraphFile file = test::subject16().file();
  file.database.tag_names.push_back("swim");
  auto swimmer = LoadedGraph::create(std::move(file), "subject16 with swim");
  ASSERT_TRUE(swimmer) << swimmer.error().to_string();
  const SynthesisContext& context = (*swimmer)->context();
  const TagMask swim = *context.tag_mask("swim");
  ASSERT_EQ(graph_frames_with(context, swim), 0);
  auto shape = make_shape("figure8:4");
  ASSERT_TRUE(shape.ok());
  const double half = shape->length_m() / 2;
  auto asked = FloorPath::create(shape->points(), {{0.0, half, "walk"}, {half, shape->length_m() + 1.0, "swim"}});
  auto nothing = FloorPath::create(shape->points(), {{0.0, half, "walk"}});
  ASSERT_TRUE(asked && nothing);
  PathSynthesisSettings settings;
  auto swum = synthesize_path(context, *asked, settings);
  auto walked = synthesize_path(context, *nothing, settings);
  ASSERT_TRUE(swum.ok()) << swum.error().to_string();
  ASSERT_TRUE(walked.ok()) << walked.error().to_string();
  ASSERT_EQ(swum->segment_tag_matches.size(), 2u);
  EXPECT_GT(swum->segment_tag_matches[1].frames, kTagMissMinSeconds * context.db->fps);
  EXPECT_EQ(swum->segment_tag_matches[1].matched, 0);
  EXPECT_EQ(swum->attempts, walked->attempts);
  EXPECT_EQ(swum->tag_penalty_m2, walked->tag_penalty_m2);
  ASSERT_EQ(swum->frame_tags.size(), walked->frame_tags.size());
  ASSERT_EQ(swum->roots.size(), walked->roots.size());
  for (size_t f = 0; f < swum->roots.size(); ++f) {
    ASSERT_EQ(swum->roots[f], walked->roots[f]) << f;
    ASSERT_EQ(swum->frame_tags[f], walked->frame_tags[f]) << f;
  }
}

// A modifier tag (a stop, a turn: how a motion goes, not a type of its own) is not chased:
// subject 16's figure 8 asking to walk then stop, the stop priced too low to matter, keeps its
// first search though few of its frames stop.
TEST(PathSynthesis, AModifierTagMissedIsNotSearchedAgain) {
  const auto& s = test::subject16();
  ASSERT_TRUE(is_modifier_tag("stop"));
  PathSynthesisSettings settings;
  settings.tag_penalty_m2 = 0.01;
  auto stopped = synthesize_path(s.context(), figure8_halves("walk", "stop"), settings);
  ASSERT_TRUE(stopped.ok()) << stopped.error().to_string();
  ASSERT_TRUE(stopped->reached_end);
  ASSERT_LE(stopped->mean_deviation_m, settings.retry_deviation_m);
  const auto& stop = stopped->segment_tag_matches[1];
  ASSERT_GE(stop.frames, kTagMissMinSeconds * s.context().db->fps);
  ASSERT_LT(stop.matched, settings.retry_tag_match * stop.frames);
  EXPECT_EQ(stopped->attempts, 1);
}

// A root that sways 0.4 m from side to side at 1 Hz travels half as far again as it gets along
// the path: the walk goes on until its motion reaches the end, not until its root has travelled
// the path's length (where the motion would stop a third of the way short), with and without the
// edit (whose own path averages the sway out over a second).
TEST(PathSynthesis, AWalkIsDoneWhereItsMotionReachesTheEndNotWhereItsRootTravelledTheLength) {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  const int n = db.frame_count();
  const int k = 10;
  Motion& walk = db.clips[0].motion;
  for (int f = 0; f < n; ++f) walk.translations(f)[0].x() += 0.4 * std::sin(2.0 * std::numbers::pi * f / db.fps);
  auto root = [&](int frame) { return walk.translations(frame)[0]; };
  // Walk on: from near the clip's end back to near its start, at the same phase of the sway, the
  // arrival window's last root placed on the departure window's last root.
  const int from = n - 2 * k - (n - 3 * k) % static_cast<int>(db.fps), to = 2 * k - 1;
  Transition t;
  t.from_frame = from;
  t.to_frame = to;
  const Vec3 shift = root(from + k - 1) - root(to);
  t.x_m = static_cast<float>(shift.x());
  t.z_m = static_cast<float>(shift.z());
  const std::vector<Transition> transitions{t};
  auto graph = build_motion_graph(db, transitions, k);
  ASSERT_TRUE(graph.ok()) << graph.error().to_string();
  ASSERT_TRUE(prune_motion_graph(*graph, {}).ok());  // the loop alone: no dead end at the clip's end
  auto context = make_synthesis_context(db, *graph);
  ASSERT_TRUE(context.ok()) << context.error().to_string();
  auto path = make_shape("line:30");
  ASSERT_TRUE(path.ok());
  for (const bool edit : {false, true}) {
    PathSynthesisSettings once;
    once.progress_retries = 0;
    once.edit_path = edit;
    auto result = synthesize_path(*context, *path, once);
    ASSERT_TRUE(result.ok()) << result.error().to_string();
    EXPECT_TRUE(result->reached_end) << edit;
    EXPECT_GE(result->arc_covered_m, path->length_m() - kEndReachedM) << edit;
    EXPECT_NEAR(result->end_distance_m, (result->roots.back() - path->points().back()).norm(), 1e-12) << edit;
    if (edit) {
      EXPECT_LT(result->end_distance_m, 0.6);  // unedited, the clip's own veer leaves it aside
    }
    double travelled = 0.0;
    for (size_t f = 1; f < result->roots.size(); ++f) travelled += (result->roots[f] - result->roots[f - 1]).norm();
    if (!edit) {
      EXPECT_GT(travelled, 1.4 * path->length_m());
    }
    EXPECT_EQ(path->followed_arcs(result->roots).back(), result->arc_covered_m) << edit;
  }
}

// A path that turns back on itself within a step (a scribble 4 cm wide, 40 m long) or a
// zigzag far sharper than a walk turns: the way along it a frame is given may lie tens of metres
// from where the frame stands, so reaching the end asks for the end's place too; and where the
// edit would take the motion further from the path than the graph played it, it is taken back.
TEST(PathSynthesis, ThePathsEndIsReachedWhereTheCharacterStandsAndTheEditNeverTakesItFurtherOff) {
  const auto& s = test::subject16();
  std::vector<Vec2> scribble, zigzag;
  for (int i = 0; i < 1000; ++i) scribble.emplace_back(0.04 * (i % 2), 0.0);
  for (int i = 0; i < 30; ++i) zigzag.emplace_back(0.5 * i, 2.0 * (i % 2));
  int undone = 0;
  for (const auto& points : {scribble, zigzag}) {
    auto path = FloorPath::create(points);
    ASSERT_TRUE(path.ok()) << path.error().to_string();
    auto result = synthesize_path(s.context(), *path);
    ASSERT_TRUE(result.ok()) << result.error().to_string();
    const std::vector<double> arcs = path->followed_arcs(result->roots);
    const double near = std::max(kEndReachedDistanceM, kEndReachedShare * path->length_m());
    auto reaches = [&](size_t f) {
      return arcs[f] >= path->length_m() - kEndReachedM && (result->roots[f] - path->points().back()).norm() <= near;
    };
    if (result->reached_end) {
      EXPECT_TRUE(reaches(arcs.size() - 1)) << points.size();
      EXPECT_LE(result->end_distance_m, near) << points.size();
    } else {
      // Nothing trimmed: the deviations are of the whole motion, edited or as played.
      EXPECT_EQ(result->roots.size(), static_cast<size_t>(result->motion.frame_count));
      EXPECT_LE(result->mean_deviation_m, result->graph_mean_deviation_m) << points.size();
      for (size_t f = 0; f < arcs.size(); ++f) ASSERT_FALSE(reaches(f)) << points.size() << " frame " << f;
    }
    if (result->edit_undone) {
      ++undone;
      EXPECT_FALSE(result->edit.edited);
      EXPECT_EQ(result->mean_deviation_m, result->graph_mean_deviation_m);
      EXPECT_EQ(result->max_deviation_m, result->graph_max_deviation_m);
    }
    if (points.size() == scribble.size()) {
      EXPECT_FALSE(result->reached_end);  // its walk heads off, 36 m from the end
    }
  }
  EXPECT_GE(undone, 1);  // subject 16: both
}

// The cost of falling behind a slowest speed acts: asking for more than walking pace (2 m/s)
// on a straight line makes the character run most of the way, and arrive much sooner, where
// the default (0.5 m/s, which every clip of subject 16 exceeds) lets it walk.
TEST(PathSynthesis, ASlowestSpeedAboveWalkingPaceMakesItRun) {
  const auto& s = test::subject16();
  auto path = make_shape("line:20");
  auto run = s.context().tag_mask("run");
  ASSERT_TRUE(path.ok() && run.ok());
  auto share_running = [&](const PathSynthesisResult& r) {
    int running = 0;
    for (TagMask t : r.frame_tags) running += (t & *run) != 0 ? 1 : 0;
    return static_cast<double>(running) / static_cast<double>(r.frame_tags.size());
  };
  auto walked = synthesize_path(s.context(), *path);
  PathSynthesisSettings hurry;
  hurry.min_speed_mps = 2.0;
  auto hurried = synthesize_path(s.context(), *path, hurry);
  ASSERT_TRUE(walked.ok() && hurried.ok());
  EXPECT_TRUE(walked->reached_end && hurried->reached_end);
  EXPECT_LT(share_running(*walked), 0.2);
  EXPECT_GT(share_running(*hurried), 0.5);
  EXPECT_LT(hurried->motion.frame_count, 0.6 * walked->motion.frame_count);
  EXPECT_LT(hurried->mean_deviation_m, 0.15);
}

// The time a walk may take: each segment at the slowest speed, or at its type's typical speed
// where that is slower, a second more for each; subject 16 walks at about 0.9 m/s and runs faster.
TEST(PathSynthesis, TheSlowestTimeOfEachSegmentIsItsTypesOrTheSlowestSpeeds) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const double walk = typical_speed_mps(context, *context.tag_mask("walk"));
  const double run = typical_speed_mps(context, *context.tag_mask("run"));
  EXPECT_GT(walk, 0.8);
  EXPECT_LT(walk, 2.0);
  EXPECT_GT(run, walk + 1.0);
  EXPECT_EQ(typical_speed_mps(context, TagMask{1} << 40), 0.0);  // no frame carries it
  // A median: about as many of the walking frames the graph plays step at or below it as above
  // it, each step read from the database (the frame to the next one of its clip).
  long below = 0, above = 0;
  const TagMask walk_mask = *context.tag_mask("walk");
  const MotionDatabase& db = *context.db;
  for (const GraphEdge& edge : context.graph->edges) {
    if (edge.transition) continue;
    for (int q = 0; q < edge.frame_count; ++q) {
      const int f = context.graph->nodes[edge.from_node].frame + q;
      const DatabaseClip& clip = db.clips[db.clip_of(f)];
      if ((context.frame_tags[f] & walk_mask) == 0 || f + 1 >= clip.first_frame + clip.frame_count) continue;
      const Vec3 step = clip.motion.translations(f + 1 - clip.first_frame)[0] - clip.motion.translations(f - clip.first_frame)[0];
      (std::hypot(step.x(), step.z()) * db.fps <= walk + 1e-6 ? below : above) += 1;
    }
  }
  EXPECT_GT(below + above, 500);
  EXPECT_LE(std::abs(below - above), (below + above) / 20) << below << " " << above;

  auto line = make_shape("line:20");
  ASSERT_TRUE(line.ok());
  auto no_segments = slowest_seconds(context, *line, 0.5);
  ASSERT_EQ(no_segments.size(), 1u);
  EXPECT_NEAR(no_segments[0], 20.0 / 0.5 + 1.0, 0.11);
  auto two = FloorPath::create(line->points(), {{0.0, 10.0, "walk"}, {12.0, 20.0, "run"}});
  ASSERT_TRUE(two.ok());
  auto slow = slowest_seconds(context, *two, 0.5);  // both types faster than 0.5 m/s
  ASSERT_EQ(slow.size(), 3u);
  EXPECT_NEAR(slow[0], 10.0 / 0.5 + 1.0, 0.11);
  EXPECT_NEAR(slow[1], 8.0 / 0.5 + 1.0, 0.11);
  EXPECT_NEAR(slow[2], 2.0 / 0.5 + 1.0, 0.11);  // 10-12 m: no segment
  auto fast = slowest_seconds(context, *two, 3.0);  // faster than walking: walking's own speed
  EXPECT_NEAR(fast[0], 10.0 / walk + 1.0, 0.05);
  EXPECT_NEAR(fast[1], 8.0 / std::min(3.0, run) + 1.0, 0.05);
  EXPECT_NEAR(fast[2], 2.0 / 3.0 + 1.0, 0.05);
}

// A walk that reaches the end but slower than the slowest speed asked for dawdled too (the 8
// subjects' figure 8, run then walk, looped in a dance beside the path for 155 s): subject 16's
// circle of 5 m at 1.4 m/s walks round it at its first search, within a few centimetres of it,
// and is searched again, pushing on, until it goes round at that speed (at the sixth retry).
TEST(PathSynthesis, AWalkSlowerThanTheSlowestSpeedIsSearchedAgain) {
  const auto& s = test::subject16();
  auto path = make_shape("circle:5");
  ASSERT_TRUE(path.ok());
  PathSynthesisSettings once;
  once.min_speed_mps = 1.4;
  once.progress_retries = 0;
  auto seconds = [&](const PathSynthesisResult& r) { return r.motion.frame_count / s.context().db->fps; };
  const double slowest_s = path->length_m() / once.min_speed_mps + 1.0;  // a second for the start
  auto first = synthesize_path(s.context(), *path, once);
  ASSERT_TRUE(first.ok()) << first.error().to_string();
  ASSERT_TRUE(first->reached_end);
  ASSERT_LE(first->mean_deviation_m, once.retry_deviation_m);
  ASSERT_GT(seconds(*first), slowest_s);  // good but for its speed
  PathSynthesisSettings pushing = once;
  pushing.progress_retries = 6;  // the sixth rung, the behind penalty 16x, pushes it on
  auto pushed = synthesize_path(s.context(), *path, pushing);
  ASSERT_TRUE(pushed.ok());
  EXPECT_GT(pushed->attempts, 1);
  EXPECT_TRUE(pushed->reached_end);
  EXPECT_LE(seconds(*pushed), slowest_s);
  // A segment asking for walking is judged at walking's pace: the first search, round the
  // circle at that pace, is kept.
  PathSynthesisSettings walking = pushing;
  auto walk_path = FloorPath::create(path->points(), {{0.0, path->length_m(), "walk"}});
  ASSERT_TRUE(walk_path.ok());
  auto walked = synthesize_path(s.context(), *walk_path, walking);
  ASSERT_TRUE(walked.ok());
  ASSERT_TRUE(walked->reached_end);
  ASSERT_LE(walked->mean_deviation_m, walking.retry_deviation_m);
  EXPECT_EQ(walked->attempts, 1);
  EXPECT_GT(seconds(*walked), slowest_s);  // slower than 1.4 m/s, as walking is
}

// A library that can stand still or walk straight ahead (16_15), and a path it cannot follow by
// walking, an S-curve: Kovar's cost prefers standing at the start, on the path, to walking off
// it, and the walk dawdles until the search gives up. Searched again pushing on harder (the
// behind penalty higher, the edit in the search), it walks, and covers the path's length; with
// the edit in the search sooner, at a lower penalty, since the edit bends its straight walk
// onto the curve.
TEST(PathSynthesis, AWalkThatDawdlesIsSearchedAgainPushingOn) {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  const int n = db.frame_count();
  const int k = 10;
  DatabaseClip stand;
  stand.name = "stand";
  stand.first_frame = n;
  stand.frame_count = 90;
  stand.motion = db.clips[0].motion.slice(0, 1);
  for (int f = 1; f < stand.frame_count; ++f) {
    Motion more = db.clips[0].motion.slice(0, 1);
    stand.motion.local_rotations.insert(stand.motion.local_rotations.end(), more.local_rotations.begin(),
                                        more.local_rotations.end());
    stand.motion.local_translations_m.insert(stand.motion.local_translations_m.end(),
                                             more.local_translations_m.begin(), more.local_translations_m.end());
    ++stand.motion.frame_count;
  }
  db.clips.push_back(stand);
  const Motion& walk = db.clips[0].motion;
  // A transition leaving at `from` and arriving at `to`, placed so that the arrival window's last
  // root lands on the departure window's last root (the clips walk north, unturned).
  auto transition = [&](int from, int to) {
    auto root = [&](int frame) {
      return frame < n ? walk.translations(frame)[0] : walk.translations(0)[0];
    };
    const Vec3 shift = root(from + k - 1) - root(to);
    Transition t;
    t.from_frame = from;
    t.to_frame = to;
    t.x_m = static_cast<float>(shift.x());
    t.z_m = static_cast<float>(shift.z());
    return t;
  };
  const std::vector<Transition> transitions{
      transition(n + 60, n + 20 + k - 1),  // stand on
      transition(n + 30, k - 1),           // start walking
      transition(n - 2 * k, n + k - 1),    // stop
      transition(n - 2 * k, 2 * k - 1)};   // walk on
  auto graph = build_motion_graph(db, transitions, k);
  ASSERT_TRUE(graph.ok()) << graph.error().to_string();
  auto context = make_synthesis_context(db, *graph);
  ASSERT_TRUE(context.ok()) << context.error().to_string();
  auto path = make_shape("s-curve:30");
  ASSERT_TRUE(path.ok());
  PathSynthesisSettings once;
  once.progress_retries = 0;
  once.start_node = graph->node_at_frame(n);  // standing
  auto dawdled = synthesize_path(*context, *path, once);
  ASSERT_TRUE(dawdled.ok()) << dawdled.error().to_string();
  EXPECT_FALSE(dawdled->reached_end);
  EXPECT_EQ(dawdled->attempts, 1);
  EXPECT_EQ(dawdled->behind_penalty_m, 1.0);

  std::array<double, 2> kept_penalty{};
  for (const bool edit : {false, true}) {
    PathSynthesisSettings pushing = once;
    pushing.progress_retries = 5;
    pushing.edit_path = edit;
    auto pushed = synthesize_path(*context, *path, pushing);
    ASSERT_TRUE(pushed.ok());
    EXPECT_TRUE(pushed->reached_end) << edit;
    ASSERT_GT(pushed->attempts, 1);
    EXPECT_GT(pushed->searches, dawdled->searches);  // every attempt's searches are counted
    EXPECT_GE(pushed->arc_covered_m, path->length_m() - kEndReachedM);
    // The ladder, every rung looking retry_horizon_s ahead: the same search; the arc corrected
    // as the walk goes; 4x; when edited, then the edit in the search at 1x and 4x; then 16x,
    // with and without it when edited; ...
    struct Rung {
      bool anchor, in_search;
      double factor;
    };
    // The attempts stop at the first that reaches the end within retry_deviation_m; else all are
    // made and the one kept (reaching the end, the least deviation) is one of them.
    const std::array<Rung, 5> edited{{{false, false, 1.0}, {true, false, 1.0}, {false, false, 4.0},
                                      {false, true, 1.0}, {false, true, 4.0}}};
    const std::array<Rung, 5> plain{{{false, false, 1.0}, {true, false, 1.0}, {false, false, 4.0},
                                     {false, false, 16.0}, {false, false, 64.0}}};
    ASSERT_NE(pushing.retry_horizon_s, pushing.horizon_s);
    EXPECT_EQ(pushed->horizon_s, pushing.retry_horizon_s) << edit;
    const auto& ladder = edit ? edited : plain;
    const auto made = static_cast<size_t>(pushed->attempts - 1);
    ASSERT_LE(made, ladder.size());
    if (made < ladder.size()) {
      EXPECT_LE(pushed->mean_deviation_m, pushing.retry_deviation_m) << edit;
      EXPECT_EQ(pushed->behind_penalty_m, ladder[made - 1].factor) << edit;
      EXPECT_EQ(pushed->edit_in_search, ladder[made - 1].in_search) << edit;
      EXPECT_EQ(pushed->anchor_arc, ladder[made - 1].anchor) << edit;
    } else {
      EXPECT_TRUE(std::any_of(ladder.begin(), ladder.end(), [&](const Rung& r) {
        return r.factor == pushed->behind_penalty_m && r.in_search == pushed->edit_in_search &&
               r.anchor == pushed->anchor_arc;
      })) << edit;
    }
    kept_penalty[edit ? 1 : 0] = pushed->behind_penalty_m;
    if (pushed->edit_in_search) {
      EXPECT_LT(pushed->mean_deviation_m, 0.15);
    }
    // What was kept is the search with those settings.
    PathSynthesisSettings at = pushing;
    at.progress_retries = 0;
    at.behind_penalty_m = pushed->behind_penalty_m;
    at.edit_in_search = pushed->edit_in_search;
    at.anchor_arc = pushed->anchor_arc;
    at.horizon_s = pushed->horizon_s;
    auto direct = synthesize_path(*context, *path, at);
    ASSERT_TRUE(direct.ok());
    EXPECT_EQ(direct->walk.edges, pushed->walk.edges);
    EXPECT_EQ(direct->walk.start_node, pushed->walk.start_node);
  }
  EXPECT_LE(kept_penalty[1], kept_penalty[0]);
  // With the retries' horizon the first search's (0, or the same value), the ladder has no rung
  // repeating the first search: its first retry corrects the arc.
  for (const double retry_horizon : {0.0, once.horizon_s}) {
    PathSynthesisSettings same = once;
    same.progress_retries = 1;
    same.edit_path = false;
    same.retry_horizon_s = retry_horizon;
    auto retried = synthesize_path(*context, *path, same);
    ASSERT_TRUE(retried.ok());
    EXPECT_EQ(retried->attempts, 2);
    EXPECT_EQ(retried->horizon_s, once.horizon_s);
    if (retried->reached_end) {
      EXPECT_TRUE(retried->anchor_arc);  // else the first may be kept
    }
  }
  // No behind penalty, no pushing.
  PathSynthesisSettings kovar = once;
  kovar.progress_retries = 3;
  kovar.behind_penalty_m = 0.0;
  auto plain = synthesize_path(*context, *path, kovar);
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->attempts, 1);
}

}  // namespace
}  // namespace mg
