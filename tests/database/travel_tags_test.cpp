#include "motiongraph/database/travel_tags.h"

#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace mg {
namespace {

// A root that goes along x at each frame's speed (m/s), y up.
std::vector<Vec3> roots_at(const std::vector<double>& speeds, double fps) {
  std::vector<Vec3> roots;
  Vec3 at(0.0, 0.9, 0.0);
  for (double v : speeds) {
    at.x() += v / fps;
    roots.push_back(at);
  }
  return roots;
}

std::vector<double> pieces(std::initializer_list<std::pair<int, double>> frames_at_speed) {
  std::vector<double> speeds;
  for (const auto& [frames, speed] : frames_at_speed) speeds.insert(speeds.end(), frames, speed);
  return speeds;
}

// A clip of 1 to 6 pieces of 5 to 84 frames, each standing or at 0.2 to 2.1 m/s.
std::vector<double> random_speeds(std::mt19937& random) {
  std::vector<double> speeds;
  const int pieces_count = 1 + static_cast<int>(random() % 6);
  for (int p = 0; p < pieces_count; ++p) {
    speeds.insert(speeds.end(), 5 + random() % 80, (random() % 2) != 0 ? 0.0 : 0.2 + 0.1 * (random() % 20));
  }
  return speeds;
}

TEST(TravelTags, WalkAndRunAreTheLocomotionTags) {
  EXPECT_TRUE(is_locomotion_tag("walk"));
  EXPECT_TRUE(is_locomotion_tag("run"));
  for (const char* other : {"jump", "stop", "turn", "sit", "dance", "sidestep", "Walk", ""}) {
    EXPECT_FALSE(is_locomotion_tag(other)) << other;
  }
}

TEST(TravelTags, AWalkThatStopsKeepsItsTagUntilAboutWhereItStops) {
  const double fps = 30.0;
  const TravelTagSettings settings;
  // 3 s at 1 m/s, then 2 s standing: the window's half (15 frames) past the stop still travels
  // at least 0.25 m/s, so the span ends between frame 90 and 90 + 15.
  const auto spans = travelling_spans(roots_at(pieces({{90, 1.0}, {60, 0.0}}), fps), fps, settings);
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_EQ(spans[0].first, 0);
  EXPECT_GE(spans[0].count, 90);
  EXPECT_LE(spans[0].count, 105);
  // Starting from standing: the span starts at most a half window before the walk.
  const auto starts = travelling_spans(roots_at(pieces({{60, 0.0}, {90, 1.0}}), fps), fps, settings);
  ASSERT_EQ(starts.size(), 1u);
  EXPECT_GE(starts[0].first, 45);
  EXPECT_LE(starts[0].first, 60);
  EXPECT_EQ(starts[0].first + starts[0].count, 150);
}

TEST(TravelTags, TheSameSecondsAtAnyFrameRate) {
  // 3 s at 1 m/s then 2 s standing: the span ends within the window's half second of the stop
  // (between 3.0 and 3.5 s) at 24, 30, 60 and 120 fps alike.
  const TravelTagSettings settings;
  for (const double fps : {24.0, 30.0, 60.0, 120.0}) {
    const int walk = static_cast<int>(3 * fps), stand = static_cast<int>(2 * fps);
    const auto spans = travelling_spans(roots_at(pieces({{walk, 1.0}, {stand, 0.0}}), fps), fps, settings);
    ASSERT_EQ(spans.size(), 1u) << fps;
    EXPECT_EQ(spans[0].first, 0) << fps;
    EXPECT_GE(spans[0].count / fps, 3.0) << fps;
    EXPECT_LE(spans[0].count / fps, 3.5) << fps;
  }
}

TEST(TravelTags, NothingThatStandsOrCreepsAndAllOfAWalk) {
  const double fps = 30.0;
  const TravelTagSettings settings;
  EXPECT_TRUE(travelling_spans(roots_at(pieces({{120, 0.0}}), fps), fps, settings).empty());
  EXPECT_TRUE(travelling_spans(roots_at(pieces({{120, 0.2}}), fps), fps, settings).empty());  // below 0.25 m/s
  EXPECT_EQ(travelling_spans(roots_at(pieces({{120, 0.3}}), fps), fps, settings), (std::vector<FrameSpan>{{0, 120}}));
  // On the spot, swaying 10 cm to and fro twice a second: 0.4 m/s of movement, but no travel.
  std::vector<Vec3> sway;
  for (int f = 0; f < 120; ++f) sway.emplace_back(0.05 * std::sin(f * 2.0 * 3.14159265 * 2.0 / fps), 0.9, 0.0);
  EXPECT_TRUE(travelling_spans(sway, fps, settings).empty());
  // The height does not count: only the floor.
  std::vector<Vec3> rising;
  for (int f = 0; f < 120; ++f) rising.emplace_back(0.0, 0.9 + f / fps, 0.0);
  EXPECT_TRUE(travelling_spans(rising, fps, settings).empty());
  // Off: every frame, even standing ones; an empty clip has none.
  TravelTagSettings off;
  off.min_speed_mps = 0.0;
  EXPECT_EQ(travelling_spans(roots_at(pieces({{40, 0.0}}), fps), fps, off), (std::vector<FrameSpan>{{0, 40}}));
  EXPECT_TRUE(travelling_spans({}, fps, settings).empty());
}

TEST(TravelTags, ShortPausesAreBridgedAndShortTravelsDropped) {
  const double fps = 30.0;
  TravelTagSettings settings;
  settings.window_s = 0.2;  // 3 frames each side: the spans follow the speeds closely
  settings.min_gap_s = 0.5;
  settings.min_run_s = 1.0;
  // A pause of 0.3 s between two walks keeps one span; one of 1.5 s splits it.
  const auto bridged = travelling_spans(roots_at(pieces({{60, 1.0}, {9, 0.0}, {60, 1.0}}), fps), fps, settings);
  ASSERT_EQ(bridged.size(), 1u);
  EXPECT_EQ(bridged[0], (FrameSpan{0, 129}));
  const auto split = travelling_spans(roots_at(pieces({{60, 1.0}, {45, 0.0}, {60, 1.0}}), fps), fps, settings);
  ASSERT_EQ(split.size(), 2u);
  EXPECT_EQ(split[0].first, 0);
  EXPECT_EQ(split[1].first + split[1].count, 165);
  // A clip shorter than min_run_s that travels throughout keeps it; one that stands part of it not.
  EXPECT_EQ(travelling_spans(roots_at(pieces({{20, 1.0}}), fps), fps, settings), (std::vector<FrameSpan>{{0, 20}}));
  EXPECT_TRUE(travelling_spans(roots_at(pieces({{14, 1.0}, {6, 0.0}}), fps), fps, settings).empty());
  // Half a second of travel among standing is dropped; two seconds stay.
  EXPECT_TRUE(travelling_spans(roots_at(pieces({{60, 0.0}, {15, 1.0}, {60, 0.0}}), fps), fps, settings).empty());
  EXPECT_EQ(travelling_spans(roots_at(pieces({{60, 0.0}, {60, 1.0}, {60, 0.0}}), fps), fps, settings).size(), 1u);
}

// Invariants on random walks and stands: spans in order, within the clip, at least min_run_s
// long, at least min_gap_s apart; a frame far (a window) from every span stands by its window.
TEST(TravelTags, SpansAreOrderedLongEnoughAndApart) {
  const double fps = 30.0;
  const TravelTagSettings settings;
  std::mt19937 random(7);
  for (int trial = 0; trial < 200; ++trial) {
    const std::vector<double> speeds = random_speeds(random);
    const auto roots = roots_at(speeds, fps);
    const auto spans = travelling_spans(roots, fps, settings);
    const int n = static_cast<int>(roots.size());
    for (size_t i = 0; i < spans.size(); ++i) {
      EXPECT_GE(spans[i].first, 0);
      EXPECT_LE(spans[i].first + spans[i].count, n);
      if (spans[i].count < n) {  // or the whole clip
        EXPECT_GE(spans[i].count, settings.min_run_s * fps);
      }
      if (i > 0) {
        EXPECT_GE(spans[i].first - (spans[i - 1].first + spans[i - 1].count), settings.min_gap_s * fps);
      }
    }
    // Not every frame in a span travels (pauses are bridged), but every frame whose whole
    // window travels fast (>= 0.5 m/s) is in one.
    for (int f = 15; f + 15 < n; ++f) {
      const bool in_span = std::any_of(spans.begin(), spans.end(),
                                       [&](const FrameSpan& s) { return f >= s.first && f < s.first + s.count; });
      bool fast = true;
      for (int g = f - 15; g <= f + 15; ++g) fast = fast && speeds[static_cast<size_t>(g)] >= 0.5;
      // 31 frames of fast travel make a span of 31 frames or more: at least min_run_s (15).
      if (fast) {
        EXPECT_TRUE(in_span) << trial << " frame " << f;
      }
    }
  }
}

// Stop stays where the root halts and over the second that slows into each halt after travel.
TEST(TravelTags, AStopIsWhereTheRootHaltsAndTheSecondBefore) {
  const double fps = 30.0;
  const TravelTagSettings settings;
  EXPECT_TRUE(is_stop_tag("stop"));
  EXPECT_TRUE(is_stop_tag("Stop"));  // as a user asks for it
  EXPECT_FALSE(is_stop_tag("walk"));
  EXPECT_FALSE(is_stop_tag("stops"));
  // Standing, walking, standing, walking: the first stand whole (the clip starts there), the
  // second with the 30 frames of walking before it.
  const auto roots = roots_at(pieces({{40, 0.0}, {90, 1.0}, {60, 0.0}, {90, 1.0}}), fps);
  const auto travel = travelling_spans(roots, fps, settings);
  ASSERT_EQ(travel.size(), 2u);
  const auto stops = stopping_spans(roots, fps, settings);
  ASSERT_EQ(stops.size(), 2u);
  EXPECT_EQ(stops[0], (FrameSpan{0, travel[0].first}));
  const int halt = travel[0].first + travel[0].count;
  EXPECT_EQ(stops[1], (FrameSpan{halt - 30, travel[1].first - (halt - 30)}));
  // A walk that never halts: its description is trusted, all of it; so with the refinement off.
  const auto walk = roots_at(pieces({{150, 1.0}}), fps);
  EXPECT_EQ(stopping_spans(walk, fps, settings), (std::vector<FrameSpan>{{0, 150}}));
  TravelTagSettings whole;
  whole.min_speed_mps = 0.0;
  EXPECT_EQ(stopping_spans(roots, fps, whole), (std::vector<FrameSpan>{{0, static_cast<int>(roots.size())}}));
  EXPECT_TRUE(stopping_spans({}, fps, settings).empty());
}

// Against the travelling spans, on random clips: the stop spans hold every frame outside them,
// and of the frames inside them only the lead before a halt, in order and apart.
TEST(TravelTags, StopSpansAreTheHaltsAndTheirLeadsOnRandomClips) {
  const double fps = 30.0;
  TravelTagSettings settings;
  settings.stop_lead_s = 0.5;
  const int lead = 15;
  std::mt19937 random(11);
  for (int trial = 0; trial < 200; ++trial) {
    const std::vector<double> speeds = random_speeds(random);
    const auto roots = roots_at(speeds, fps);
    const int n = static_cast<int>(roots.size());
    const auto travel = travelling_spans(roots, fps, settings);
    const auto stops = stopping_spans(roots, fps, settings);
    std::vector<int> travelling(static_cast<size_t>(n), 0), stopping(static_cast<size_t>(n), 0);
    for (const FrameSpan& t : travel) std::fill_n(travelling.begin() + t.first, t.count, 1);
    for (size_t i = 0; i < stops.size(); ++i) {
      ASSERT_GT(stops[i].count, 0);
      if (i > 0) {
        ASSERT_GE(stops[i].first, stops[i - 1].first + stops[i - 1].count) << trial;
      }
      std::fill_n(stopping.begin() + stops[i].first, stops[i].count, 1);
    }
    if (travel.size() == 1 && travel[0] == FrameSpan{0, n}) {
      EXPECT_EQ(stops, (std::vector<FrameSpan>{{0, n}})) << trial;
      continue;
    }
    for (int f = 0; f < n; ++f) {
      if (!travelling[static_cast<size_t>(f)]) {
        EXPECT_TRUE(stopping[static_cast<size_t>(f)]) << trial << " frame " << f;
        continue;
      }
      // A travelling frame is a stop's exactly when a halt begins within `lead` frames after it
      // with no other travel between: the frame lies in the last `lead` of its span, a halt after.
      const auto span = std::find_if(travel.begin(), travel.end(), [&](const FrameSpan& t) {
        return f >= t.first && f < t.first + t.count;
      });
      const int end = span->first + span->count;
      EXPECT_EQ(stopping[static_cast<size_t>(f)] != 0, end < n && end - f <= lead) << trial << " frame " << f;
    }
  }
}

TEST(TravelTags, SettingsAreChecked) {
  EXPECT_TRUE(TravelTagSettings{}.validate());
  TravelTagSettings s;
  s.min_speed_mps = -0.1;
  EXPECT_FALSE(s.validate());
  s = {};
  s.window_s = 0.0;
  EXPECT_FALSE(s.validate());
  s = {};
  s.min_gap_s = -1.0;
  EXPECT_FALSE(s.validate());
  s = {};
  s.min_run_s = std::nan("");
  EXPECT_FALSE(s.validate());
  s = {};
  s.stop_lead_s = -1.0;
  EXPECT_FALSE(s.validate());
}

}  // namespace
}  // namespace mg

namespace mg {
namespace {

std::vector<int> frames_of(const std::vector<FrameSpan>& spans) {
  std::vector<int> frames;
  for (const FrameSpan& s : spans) {
    for (int f = s.first; f < s.first + s.count; ++f) frames.push_back(f);
  }
  return frames;
}

// A clip called both walk and run: walking where its pace is under the run pace, running where it
// is over; a blip of pace shorter than min_run_s goes with what it interrupts; standing frames
// are neither; a clip of one pace is not split. Property: the two cover the travelling spans
// exactly, without overlap, and each stretch is min_run_s or longer unless its span is shorter.
TEST(TravelTags, AClipCalledWalkAndRunIsSplitWhereItsPaceChanges) {
  constexpr double fps = 30.0;
  EXPECT_NEAR(run_pace_mps(1.0), std::sqrt(0.3 * 9.81), 1e-12);
  const TravelTagSettings settings;
  const double run_mps = run_pace_mps(1.0);  // 1.72 m/s
  // 1 s standing, 3 s walking at 1.2 m/s with a 0.2 s burst at 3 m/s, 3 s running at 3 m/s.
  const auto roots = roots_at(pieces({{30, 0.0}, {45, 1.2}, {6, 3.0}, {39, 1.2}, {90, 3.0}}), fps);
  const PaceSpans split = pace_spans(roots, fps, settings, run_mps);
  ASSERT_EQ(split.walking.size(), 1u);
  ASSERT_EQ(split.running.size(), 1u);
  // The pace over a second crosses 1.72 m/s about (1.72 - 1.2) / (3 - 1.2) of a second after the
  // change, less half a second: frame 120 + 15 * (2 * 0.29 - 1) ~ 114.
  EXPECT_NEAR(split.running[0].first, 114, 3);
  EXPECT_EQ(split.running[0].first + split.running[0].count, static_cast<int>(roots.size()));
  EXPECT_EQ(split.walking[0].first + split.walking[0].count, split.running[0].first);
  EXPECT_LT(split.walking[0].first, 30);  // the window starts travelling half a second early
  EXPECT_TRUE(pace_spans(roots_at(pieces({{90, 1.2}}), fps), fps, settings, run_mps).running.empty());
  EXPECT_TRUE(pace_spans(roots_at(pieces({{90, 3.0}}), fps), fps, settings, run_mps).walking.empty());

  std::mt19937 random(5);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> speeds;
    for (int p = 0, n = 1 + static_cast<int>(random() % 6); p < n; ++p) {
      const size_t frames = 5 + random() % 80;
      const double speed = random() % 3 == 0 ? 0.0 : 0.5 + 0.25 * static_cast<double>(random() % 12);
      speeds.insert(speeds.end(), frames, speed);
    }
    const auto r = roots_at(speeds, fps);
    const PaceSpans p = pace_spans(r, fps, settings, run_mps);
    std::vector<int> both = frames_of(p.walking), running = frames_of(p.running);
    both.insert(both.end(), running.begin(), running.end());
    std::sort(both.begin(), both.end());
    const std::vector<FrameSpan> travel = travelling_spans(r, fps, settings);
    ASSERT_EQ(both, frames_of(travel)) << "trial " << trial;
    for (const auto* spans : {&p.walking, &p.running}) {
      for (const FrameSpan& s : *spans) {
        const bool whole_span = std::any_of(travel.begin(), travel.end(), [&](const FrameSpan& t) {
          return t.first <= s.first && s.first + s.count <= t.first + t.count && t.count < settings.min_run_s * fps;
        });
        EXPECT_TRUE(s.count >= settings.min_run_s * fps || whole_span) << "trial " << trial << " at " << s.first;
      }
    }
  }
}

}  // namespace
}  // namespace mg
