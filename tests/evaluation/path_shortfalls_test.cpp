// What a path falls short of, in sentences: each shortfall the retries judge by, said with its
// figures, and none for a result they would keep; on subject 16, paths a walk cannot follow
// (a U-turn on the spot, a circle of half a metre) are said to fall short as they do.
#include "motiongraph/evaluation/path_shortfalls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "motiongraph/synthesis/facing.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

bool holds(const std::vector<std::string>& said, const std::string& part) {
  for (const std::string& s : said) {
    if (s.find(part) != std::string::npos) return true;
  }
  return false;
}

FloorPath line_with(std::vector<PathSegment> segments) {
  auto path = FloorPath::create({Vec2(0.0, 0.0), Vec2(0.0, -20.0)}, std::move(segments));
  if (!path) throw std::runtime_error(path.error().to_string());
  return *path;
}

// A result the retries would keep: the end reached, not dawdling, on the path, its type carried.
PathSynthesisResult kept(const FloorPath& path) {
  PathSynthesisResult r;
  r.reached_end = true;
  r.path_length_m = path.length_m();
  r.arc_covered_m = path.length_m();
  r.mean_deviation_m = 0.05;
  r.max_deviation_m = 0.2;
  r.attempts = 1;
  r.segment_tag_matches.assign(path.segments().size(), {100, 90});
  return r;
}

TEST(PathShortfalls, NoneForAResultTheRetriesWouldKeep) {
  const auto& context = test::subject16().context();
  const FloorPath path = line_with({{0.0, 10.0, "walk"}});
  EXPECT_TRUE(path_shortfalls(context, path, {}, kept(path)).empty());
}

// A rest facing more than kRestFacingWarnDeg off the path's last direction is said, with the clip
// it stops in (CMU 29's and 135's stopping clips turn 55-60 degrees off a straight line's end).
TEST(PathShortfalls, ARestFacingAwayFromThePathsEndIsSaid) {
  const auto& context = test::subject16().context();
  const FloorPath path = line_with({});  // north, -z
  const RestEnding& ending = context.rest().endings.front();
  const std::string clip = context.db->clips[static_cast<size_t>(context.db->clip_of(ending.last_frame))].name;
  const Vec2 captured =
      facing_on_floor(context.assembler.root_rotation(ending.last_frame, {}), context.tracks.forward_axis);
  for (const double deg : {0.0, 30.0, -40.0, 60.0, -90.0, 170.0}) {
    PathSynthesisResult r = kept(path);
    r.rest = &ending;
    const double a = deg * std::numbers::pi / 180.0;
    const Vec2 want(std::sin(a), -std::cos(a));  // `deg` clockwise from north
    r.motion = context.assembler.empty_motion();
    context.assembler.append_frame(ending.last_frame, FloorTransform{yaw_between(captured, want), 0.0, 0.0}, r.motion);
    const std::vector<std::string> said = path_shortfalls(context, path, {}, r);
    const bool warned = holds(said, "degrees off the path's last direction");
    EXPECT_EQ(warned, std::abs(deg) > kRestFacingWarnDeg) << deg;
    if (warned) {
      EXPECT_TRUE(holds(said, fmt::format("stands facing {:.0f} degrees off the path's last direction: {}, the clip it "
                                          "stops in",
                                          std::abs(deg), clip)))
          << said.front();
    }
  }
}

TEST(PathShortfalls, TheEndNotReachedSaysHowFarAndWhy) {
  const auto& context = test::subject16().context();
  const FloorPath path = line_with({});
  PathSynthesisResult r = kept(path);
  r.reached_end = false;
  r.arc_covered_m = 12.34;
  r.end_distance_m = 7.891;
  r.attempts = 3;
  r.mean_deviation_m = 5.0;  // not said: the end not reached says it all
  auto said = path_shortfalls(context, path, {}, r);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(holds(said, "it went 12.3 m of 20.0 m and stops 7.89 m from the end")) << said[0];
  EXPECT_TRUE(holds(said, "the search gave up after 3 searches of the whole path")) << said[0];
  // Its way along the path at the end, but far from it: the path folds back tighter than a step.
  r.arc_covered_m = path.length_m() - 0.4;
  said = path_shortfalls(context, path, {}, r);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(holds(said, "the path turns back on itself more tightly than the motion can follow")) << said[0];
}

TEST(PathShortfalls, DawdlingNamesTheSpanAndItsTimes) {
  const auto& context = test::subject16().context();
  PathSynthesisSettings settings;
  settings.min_speed_mps = 0.7;
  const FloorPath plain = line_with({});
  PathSynthesisResult r = kept(plain);
  r.dawdled_in = 0;  // no segment: the whole path
  r.dawdled_s = 41.73;
  r.dawdle_limit_s = 29.57;
  r.attempts = 5;
  auto said = path_shortfalls(context, plain, settings, r);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(holds(said, "it takes 41.7 s over the path's 20.0 m, where 29.6 s would do")) << said[0];
  EXPECT_TRUE(holds(said, "(0.7 m/s,")) << said[0];
  EXPECT_TRUE(holds(said, "5 searches of the whole path found none quicker")) << said[0];
  const FloorPath segmented = line_with({{0.0, 10.0, "walk"}, {10.0, 20.0, "run"}});
  r = kept(segmented);
  r.dawdled_in = 1;
  r.dawdled_s = 12.0;
  r.dawdle_limit_s = 6.0;
  said = path_shortfalls(context, segmented, settings, r);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(holds(said, "over the segment run 10-20 m")) << said[0];
  r.dawdled_in = 2;  // past the last segment: where none is
  said = path_shortfalls(context, segmented, settings, r);
  EXPECT_TRUE(holds(said, "over the stretches no segment holds")) << said[0];
}

TEST(PathShortfalls, FollowingFurtherOffThanTheRetriesLookForIsSaid) {
  const auto& context = test::subject16().context();
  const FloorPath path = line_with({});
  PathSynthesisSettings settings;
  settings.retry_deviation_m = 0.25;
  PathSynthesisResult r = kept(path);
  r.mean_deviation_m = 0.25;  // at it: within
  EXPECT_TRUE(path_shortfalls(context, path, settings, r).empty());
  r.mean_deviation_m = 0.973;
  r.max_deviation_m = 1.54;
  auto said = path_shortfalls(context, path, settings, r);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(holds(said, "0.97 m off on average (at most 1.54 m), more than the 0.25 m")) << said[0];
  settings.retry_deviation_m = 0.0;  // not looked for: not said
  EXPECT_TRUE(path_shortfalls(context, path, settings, r).empty());
}

TEST(PathShortfalls, AMissedTypeIsSaidWithItsShare) {
  const auto& context = test::subject16().context();
  const FloorPath path = line_with({{0.0, 10.0, "walk"}, {10.0, 20.0, "run"}});
  PathSynthesisResult r = kept(path);
  r.segment_tag_matches[1] = {83, 10};
  r.missed_segments = {1};
  auto said = path_shortfalls(context, path, {}, r);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(holds(said, "the segment run 10-20 m misses its motion type: 12 % of its 83 frames carry run")) << said[0];
  EXPECT_TRUE(holds(said, "(the retries look for 50 %)")) << said[0];
}

// A segment too short for the retries to judge (under kTagMissMinSeconds of motion): none of its
// type is said (a jump asked for at the end of a run, none played); some of it, a modifier, a
// type the graph does not play, or one past the end (said as such) is not.
TEST(PathShortfalls, AShortSegmentGettingNoneOfItsTypeIsSaid) {
  const auto& context = test::subject16().context();
  const FloorPath path = line_with({{0.0, 12.0, "walk"}, {12.0, 16.0, "jump"}, {16.0, 18.0, "stop"}});
  PathSynthesisResult r = kept(path);
  r.segment_tag_matches[1] = {42, 0};
  r.segment_tag_matches[2] = {20, 0};  // stop: a modifier, how a motion goes
  auto said = path_shortfalls(context, path, {}, r);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the segment jump 12-16 m gets none of its motion type: none of its 42 frames (1.4 s) carry "
                     "jump (shorter than the 2 s the retries judge a segment by, it may be too short to change into "
                     "it)");
  r.segment_tag_matches[1] = {42, 1};  // one frame: some of it
  EXPECT_TRUE(path_shortfalls(context, path, {}, r).empty());
  r.segment_tag_matches[1] = {42, 0};
  r.missed_segments = {1};  // judged by the retries: said once, as missed
  said = path_shortfalls(context, path, {}, r);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(holds(said, "misses its motion type")) << said[0];
  // A segment of 2 s or more is the retries' to judge: told not to, nothing is said of it here.
  r.missed_segments = {};
  r.segment_tag_matches[1] = {120, 0};
  PathSynthesisSettings not_judged;
  not_judged.retry_tag_match = 0.0;
  EXPECT_TRUE(path_shortfalls(context, path, not_judged, r).empty());
  // Past the end: said as such alone.
  const FloorPath beyond = line_with({{0.0, 20.0, "walk"}, {20.0, 21.0, "jump"}});
  PathSynthesisResult at_end = kept(beyond);
  at_end.segment_tag_matches[1] = {1, 0};
  said = path_shortfalls(context, beyond, {}, at_end);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(holds(said, "lies past the path's end")) << said[0];
}

TEST(PathShortfalls, ASegmentPastThePathsEndIsSaid) {
  const auto& context = test::subject16().context();
  const FloorPath path = line_with({{0.0, 10.0, "walk"}, {20.0, 30.0, "run"}, {15.0, 25.0, "jump"}});
  auto said = path_shortfalls(context, path, {}, kept(path));
  ASSERT_EQ(said.size(), 1u);  // the jump from 15 m is reached, and cut at the end
  EXPECT_EQ(said[0], "the segment run 20-30 m lies past the path's end (20.0 m): no frame can carry its motion type");
}

// Synthesized on subject 16: what is said is what the result shows.
TEST(PathShortfalls, PathsAWalkCannotFollowFallShortAsTheirResultsShow) {
  const auto& context = test::subject16().context();
  const PathSynthesisSettings settings;
  auto uturn = FloorPath::create({Vec2(0.0, 0.0), Vec2(0.0, -6.0), Vec2(0.0, 0.0)});
  auto small_circle = make_shape("circle:0.5");
  auto figure8 = make_shape("figure8:4");
  ASSERT_TRUE(uturn && small_circle && figure8);
  int short_of = 0;
  for (const FloorPath* path : {&*uturn, &*small_circle, &*figure8}) {
    auto result = synthesize_path(context, *path, settings);
    ASSERT_TRUE(result) << result.error().to_string();
    const auto said = path_shortfalls(context, *path, settings, *result);
    EXPECT_EQ(holds(said, "did not reach the path's end"), !result->reached_end);
    EXPECT_EQ(holds(said, "the motion dawdles"), result->reached_end && result->dawdled_in >= 0);
    EXPECT_EQ(holds(said, "off on average"),
              result->reached_end && result->mean_deviation_m > settings.retry_deviation_m);
    if (result->dawdled_in >= 0) {
      // The seconds said are the motion's own over the span (the whole path here: no segments).
      EXPECT_EQ(result->dawdled_in, 0);
      EXPECT_DOUBLE_EQ(result->dawdled_s, result->motion.frame_count / context.db->fps);
      EXPECT_GT(result->dawdled_s, result->dawdle_limit_s);
      EXPECT_DOUBLE_EQ(result->dawdle_limit_s, slowest_seconds(context, *path, settings.min_speed_mps).back());
    }
    short_of += said.empty() ? 0 : 1;
    if (path == &*figure8) {
      EXPECT_TRUE(said.empty()) << said.front();  // subject 16 follows it within centimetres
    }
  }
  EXPECT_EQ(short_of, 2);  // the U-turn dawdles and strays, the circle strays
}

}  // namespace
}  // namespace mg
