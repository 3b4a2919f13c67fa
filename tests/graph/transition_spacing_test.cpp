// Spacing transitions: no out_window consecutive frames have more than max_out departures,
// with min_piece between an arrival and the next departure of its clip lie at least that many
// frames, and
// nothing was dropped that fitted (checked by brute force over random transitions on clips of
// random lengths).
#include "motiongraph/graph/transition_spacing.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace mg {
namespace {

std::vector<int> clips_of(const std::vector<int>& lengths) {
  std::vector<int> clip_of_frame;
  for (size_t c = 0; c < lengths.size(); ++c) clip_of_frame.insert(clip_of_frame.end(), lengths[c], static_cast<int>(c));
  return clip_of_frame;
}

std::vector<std::pair<int, int>> pairs_of(const std::vector<Transition>& transitions) {
  std::vector<std::pair<int, int>> pairs;
  for (const Transition& t : transitions) pairs.emplace_back(t.from_frame, t.to_frame);
  return pairs;
}

TEST(TransitionSpacing, DefaultsAndValidation) {
  TransitionSpacing spacing;
  EXPECT_TRUE(spacing.validate());
  EXPECT_EQ(spacing.out_window_for(10), 10);
  EXPECT_EQ(spacing.min_piece_frames, 0);
  spacing.out_window_frames = 7;
  EXPECT_EQ(spacing.out_window_for(10), 7);
  for (auto broken : {+[](TransitionSpacing& x) { x.out_window_frames = 0; },
                      +[](TransitionSpacing& x) { x.out_window_frames = -2; },
                      +[](TransitionSpacing& x) { x.min_piece_frames = -1; },
                      +[](TransitionSpacing& x) { x.max_out = -1; }}) {
    TransitionSpacing x;
    broken(x);
    EXPECT_FALSE(x.validate());
  }
}

TEST(TransitionSpacing, AFewDeparturesPerStretchTheBestKept) {
  const std::vector<int> clip_of_frame = clips_of({100, 100});
  TransitionSpacing spacing;  // min_piece off
  spacing.max_out = 2;
  const std::vector<Transition> in = {
      {20, 150, 3.0f}, {22, 160, 1.0f}, {27, 170, 2.0f},  // three within 10 frames: the worst goes
      {31, 180, 4.0f},                                    // 22..31 holds two already
      {32, 190, 5.0f},                                    // 23..32 holds only 27
      {95, 105, 6.0f}, {99, 110, 7.0f}, {100, 120, 8.0f},  // 100 is another clip's stretch
  };
  const std::vector<Transition> out = space_transitions(in, clip_of_frame, 10, spacing);
  const std::vector<std::pair<int, int>> expected = {{22, 160}, {27, 170}, {32, 190}, {95, 105}, {99, 110}, {100, 120}};
  EXPECT_EQ(pairs_of(out), expected);
}

TEST(TransitionSpacing, OriginalMotionBetweenArrivalAndNextDeparture) {
  const std::vector<int> clip_of_frame = clips_of({100, 100});
  TransitionSpacing spacing;
  spacing.min_piece_frames = 10;
  spacing.out_window_frames = 10;
  spacing.max_out = 2;
  const std::vector<Transition> in = {
      {20, 150, 1.0f},  // best: lands at 150
      {155, 30, 2.0f},  // leaves 5 frames after the landing at 150: dropped
      {160, 30, 3.0f},  // 10 frames after: kept; lands at 30
      {25, 170, 4.0f},  // leaves 5 frames before the landing at 30 ... and after nothing: kept
      {35, 120, 4.5f},  // leaves 5 frames after the landing at 30: dropped
      {21, 180, 5.0f},  // a third departure within 10 frames of 20 and 25: dropped
      {95, 105, 6.0f},  // clip 0's end and clip 1's start are not one stretch: kept
      {60, 55, 7.0f},   // lands 5 frames before its own departure (a tight loop): dropped
      {60, 45, 8.0f},   // 15 frames: kept
  };
  const std::vector<Transition> out = space_transitions(in, clip_of_frame, 10, spacing);
  const std::vector<std::pair<int, int>> expected = {{20, 150}, {25, 170}, {60, 45}, {95, 105}, {160, 30}};
  EXPECT_EQ(pairs_of(out), expected);
}

TEST(TransitionSpacing, ZeroMeansOff) {
  const std::vector<int> clip_of_frame = clips_of({50});
  TransitionSpacing off;
  off.min_piece_frames = 0;
  off.max_out = 0;
  const std::vector<Transition> in = {{10, 30, 2.0f}, {30, 10, 1.0f}, {10, 31, 3.0f}, {12, 12, 0.5f}};
  EXPECT_EQ(space_transitions(in, clip_of_frame, 10, off).size(), 4u);
}

// Property, against a brute-force check of the rules on the result.
TEST(TransitionSpacing, RandomSetsObeyTheRulesAndAreMaximal) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<int> lengths;
    for (int c = 0; c < 1 + static_cast<int>(random() % 4); ++c) lengths.push_back(20 + static_cast<int>(random() % 80));
    const std::vector<int> clip_of_frame = clips_of(lengths);
    const int frames = static_cast<int>(clip_of_frame.size());
    TransitionSpacing spacing;
    spacing.min_piece_frames = static_cast<int>(random() % 15);
    spacing.out_window_frames = 1 + static_cast<int>(random() % 15);
    spacing.max_out = static_cast<int>(random() % 4);
    const int piece = spacing.min_piece_frames;
    std::vector<Transition> in;
    for (int i = 0; i < 60; ++i) {
      in.push_back({static_cast<int>(random() % frames), static_cast<int>(random() % frames),
                    static_cast<float>(random() % 1000) / 10.0f});
    }
    const std::vector<Transition> out = space_transitions(in, clip_of_frame, 5, spacing);
    EXPECT_TRUE(std::is_sorted(out.begin(), out.end(), [](const Transition& x, const Transition& y) {
      return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
    }));
    // The rules, pair by pair: an arrival b and a departure d of one clip with b <= d < b + piece
    // never both kept; at most max_out departures in any piece consecutive frames of a clip.
    auto too_close = [&](int arrival, int departure) {
      return clip_of_frame[arrival] == clip_of_frame[departure] && arrival <= departure && departure < arrival + piece;
    };
    auto departures_in = [&](const std::vector<Transition>& set, int first, int count, int clip) {
      int n = 0;
      for (const Transition& t : set) {
        n += t.from_frame >= first && t.from_frame < first + count && clip_of_frame[t.from_frame] == clip ? 1 : 0;
      }
      return n;
    };
    for (const Transition& x : out) {
      for (const Transition& y : out) ASSERT_FALSE(too_close(x.to_frame, y.from_frame)) << "trial " << trial;
    }
    const int width = spacing.out_window_frames;
    if (spacing.max_out > 0) {
      for (int s = 0; s < frames; ++s) {
        ASSERT_LE(departures_in(out, s, width, clip_of_frame[s]), spacing.max_out) << "trial " << trial;
      }
    }
    // Maximal: every dropped transition, added to the kept set, breaks a rule.
    for (const Transition& t : in) {
      const bool kept = std::any_of(out.begin(), out.end(), [&](const Transition& k) {
        return k.from_frame == t.from_frame && k.to_frame == t.to_frame && k.distance == t.distance;
      });
      if (kept) continue;
      std::vector<Transition> with = out;
      with.push_back(t);
      bool breaks = false;
      for (const Transition& x : with) {
        for (const Transition& y : with) breaks = breaks || too_close(x.to_frame, y.from_frame);
      }
      if (spacing.max_out > 0) {
        for (int s = t.from_frame - width + 1; s <= t.from_frame; ++s) {
          if (s >= 0) breaks = breaks || departures_in(with, s, width, clip_of_frame[t.from_frame]) > spacing.max_out;
        }
      }
      EXPECT_TRUE(breaks) << "trial " << trial << ": " << t.from_frame << " -> " << t.to_frame
                          << " fits but was dropped";
    }
  }
}

TEST(TransitionSpacing, JsonRoundTripResolvedWindowAndOlderFiles) {
  const TransitionSpacing s{-1, 2, 8};
  EXPECT_EQ(s.resolved(10).out_window_frames, 10);
  EXPECT_EQ(TransitionSpacing({4, 2, 8}).resolved(10).out_window_frames, 4);
  const nlohmann::json json = s.resolved(10);
  const auto back = json.get<TransitionSpacing>();
  EXPECT_EQ(back.out_window_frames, 10);
  EXPECT_EQ(back.max_out, 2);
  EXPECT_EQ(back.min_piece_frames, 8);
  const auto none = nlohmann::json::object().get<TransitionSpacing>();  // unspaced files
  EXPECT_EQ(nlohmann::json(none), nlohmann::json(TransitionSpacing{}));
}

}  // namespace
}  // namespace mg
