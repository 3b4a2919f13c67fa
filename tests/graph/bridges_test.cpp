#include "motiongraph/graph/bridges.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

namespace mg {
namespace {

// Frames 0..99 walk (tag 0), 100..199 run (tag 1); window 4.
struct WalkRun {
  std::vector<TagMask> tags = std::vector<TagMask>(200, 0);
  std::vector<std::vector<char>> cores = {std::vector<char>(200, 0), std::vector<char>(200, 0)};
  WalkRun() {
    for (int f = 0; f < 200; ++f) tags[f] = f < 100 ? 1 : 2;
    for (int f = 20; f < 80; ++f) cores[0][f] = 1;
    for (int f = 120; f < 180; ++f) cores[1][f] = 1;
  }
};

Transition t(int from, int to, float d) { return Transition{from, to, d, 0, 0, 0}; }

TEST(Bridges, BestCandidatesBetweenCoresInEachDirection) {
  WalkRun s;
  BridgeSettings settings;
  settings.per_tag_pair = 2;
  settings.locality_radius = 3;
  const std::vector<Transition> candidates = {
      t(30, 150, 9.0f), t(31, 151, 5.0f),   // walk -> run, near each other: only the better one
      t(50, 170, 7.0f),                      // walk -> run, the second bridge
      t(60, 160, 7.5f),                      // walk -> run, third best: over the limit of 2
      t(10, 150, 1.0f),                      // leaves outside the walk core
      t(40, 190, 1.0f),                      // lands outside the run core
      t(140, 40, 8.0f),                      // run -> walk
      t(98, 104, 0.5f),                      // windows mixing walk and run frames: no bridge
      t(30, 60, 0.1f),                       // walk -> walk: no bridge
  };
  auto bridges = select_bridges(candidates, {}, s.tags, {}, s.cores, 4, settings).bridges;
  ASSERT_EQ(bridges.size(), 3u);
  EXPECT_EQ(bridges[0].from_frame, 31);
  EXPECT_EQ(bridges[1].from_frame, 50);
  EXPECT_EQ(bridges[2].from_frame, 140);
}

// The run frames in two clips (100..149, 150..199): the two best walk -> run candidates land in
// the first, the third best in the second. Two bridges: the best into each clip. Without clips
// given (all one clip), the two best.
TEST(Bridges, TheBestIntoEachClipFirst) {
  WalkRun s;
  BridgeSettings settings;
  settings.per_tag_pair = 2;
  settings.locality_radius = 3;
  const std::vector<Transition> candidates = {t(30, 125, 2.0f), t(50, 140, 3.0f), t(60, 170, 4.0f),
                                              t(70, 175, 5.0f)};
  std::vector<int> clips(200, 0);
  std::fill(clips.begin() + 100, clips.begin() + 150, 1);
  std::fill(clips.begin() + 150, clips.end(), 2);
  auto spread = select_bridges(candidates, {}, s.tags, clips, s.cores, 4, settings).bridges;
  ASSERT_EQ(spread.size(), 2u);
  EXPECT_EQ(spread[0].to_frame, 125);
  EXPECT_EQ(spread[1].to_frame, 170);
  auto one_clip = select_bridges(candidates, {}, s.tags, {}, s.cores, 4, settings).bridges;
  ASSERT_EQ(one_clip.size(), 2u);
  EXPECT_EQ(one_clip[0].to_frame, 125);
  EXPECT_EQ(one_clip[1].to_frame, 140);
  // Three bridges: one into each clip, then the best of the rest.
  settings.per_tag_pair = 3;
  auto three = select_bridges(candidates, {}, s.tags, clips, s.cores, 4, settings).bridges;
  ASSERT_EQ(three.size(), 3u);
  EXPECT_EQ(three[1].to_frame, 140);
  // With the candidates known only up to D 3 (levels), the pair is short of clips: incomplete.
  std::vector<double> levels(kBridgeTags * kBridgeTags, std::numeric_limits<double>::infinity());
  levels[0 * kBridgeTags + 1] = 3.0;
  settings.per_tag_pair = 2;
  const std::vector<Transition> known(candidates.begin(), candidates.begin() + 2);
  auto partial = select_bridges(known, {}, s.tags, clips, s.cores, 4, settings, {}, levels);
  ASSERT_EQ(partial.incomplete.size(), 1u);
  EXPECT_EQ(partial.incomplete[0], (TagPair{0, 1}));
  // Known up to D 4: one bridge into each clip, nothing above it can change that.
  levels[0 * kBridgeTags + 1] = 4.0;
  const std::vector<Transition> more(candidates.begin(), candidates.begin() + 3);
  auto done = select_bridges(more, {}, s.tags, clips, s.cores, 4, settings, {}, levels);
  EXPECT_TRUE(done.incomplete.empty());
  EXPECT_EQ(done.bridges.size(), 2u);
}

// Run frames 150..199 also carry turn (a run that turns): the two best walk -> run candidates
// land on plain run, the third on the turning run. Two bridges: the best onto each set of tags,
// before any second clip.
TEST(Bridges, TheBestOntoEachSetOfTagsFirst) {
  WalkRun s;
  for (int f = 150; f < 200; ++f) s.tags[f] |= 0b100;
  BridgeSettings settings;
  settings.per_tag_pair = 2;
  settings.locality_radius = 3;
  settings.tags = 0b011;
  const std::vector<Transition> candidates = {t(30, 125, 2.0f), t(50, 140, 3.0f), t(60, 170, 4.0f)};
  std::vector<int> clips(200, 0);
  std::fill(clips.begin() + 100, clips.begin() + 130, 1);  // 125 and 140 in two clips
  std::fill(clips.begin() + 130, clips.end(), 2);
  auto got = select_bridges(candidates, {}, s.tags, clips, s.cores, 4, settings).bridges;
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].to_frame, 125);
  EXPECT_EQ(got[1].to_frame, 170);
  // Known only up to D 3, the pair has not landed on the turning run its core holds: incomplete.
  std::vector<double> levels(kBridgeTags * kBridgeTags, std::numeric_limits<double>::infinity());
  levels[0 * kBridgeTags + 1] = 3.0;
  const std::vector<Transition> known(candidates.begin(), candidates.begin() + 2);
  auto partial = select_bridges(known, {}, s.tags, clips, s.cores, 4, settings, {}, levels);
  ASSERT_EQ(partial.incomplete.size(), 1u);
  EXPECT_EQ(partial.incomplete[0], (TagPair{0, 1}));
}

// Clip 2 (150..199) carries walk and run: no bridge from walk lands there, so clip 1 is all a
// walk -> run bridge can land in: one bridge there and the pair is complete whatever lies above
// its level.
TEST(Bridges, OnlyTheClipsABridgeCanLandInCount) {
  WalkRun s;
  for (int f = 150; f < 200; ++f) s.tags[f] = 3;
  BridgeSettings settings;
  settings.per_tag_pair = 1;
  const std::vector<Transition> candidates = {t(30, 125, 2.0f), t(60, 170, 1.0f)};
  std::vector<int> clips(200, 0);
  std::fill(clips.begin() + 100, clips.begin() + 150, 1);
  std::fill(clips.begin() + 150, clips.end(), 2);
  std::vector<double> levels(kBridgeTags * kBridgeTags, std::numeric_limits<double>::infinity());
  levels[0 * kBridgeTags + 1] = 2.0;
  auto got = select_bridges(candidates, {}, s.tags, clips, s.cores, 4, settings, {}, levels);
  EXPECT_TRUE(got.incomplete.empty());
  ASSERT_EQ(got.bridges.size(), 1u);
  EXPECT_EQ(got.bridges[0].to_frame, 125);
  // Two bridges a pair, the run frames one clip (no clips given): the best and the next, both in
  // it, complete; one known, short of bridges: incomplete.
  WalkRun plain;
  settings.per_tag_pair = 2;
  settings.locality_radius = 3;
  const std::vector<Transition> two = {t(30, 125, 2.0f), t(50, 140, 3.0f)};
  levels[0 * kBridgeTags + 1] = 3.0;
  EXPECT_TRUE(select_bridges(two, {}, plain.tags, {}, plain.cores, 4, settings, {}, levels).incomplete.empty());
  levels[0 * kBridgeTags + 1] = 2.0;
  const std::vector<Transition> one(two.begin(), two.begin() + 1);
  EXPECT_EQ(select_bridges(one, {}, plain.tags, {}, plain.cores, 4, settings, {}, levels).incomplete.size(), 1u);
}

TEST(Bridges, NoneBetweenCoresThatShareFrames) {
  // Frames 90..109 carry both tags (a clip tagged walk and run): with both cores through them,
  // the graph passes from one to the other there, and no pair is bridged or unjoined.
  WalkRun s;
  for (int f = 90; f < 110; ++f) s.tags[f] = 3;
  const std::vector<Transition> candidates = {t(31, 151, 5.0f), t(140, 40, 8.0f)};
  auto apart = select_bridges(candidates, {}, s.tags, {}, s.cores, 4, {});
  EXPECT_EQ(apart.bridges.size(), 2u);
  for (int f = 90; f < 110; ++f) s.cores[0][f] = s.cores[1][f] = 1;
  auto shared = select_bridges(candidates, {}, s.tags, {}, s.cores, 4, {});
  EXPECT_TRUE(shared.bridges.empty());
  EXPECT_TRUE(shared.unjoined.empty());
  // Not for a tag outside settings.tags (a modifier).
  BridgeSettings walk_only;
  walk_only.tags = 0b01;
  EXPECT_TRUE(select_bridges(candidates, {}, s.tags, {}, s.cores, 4, walk_only).unjoined.empty());
}

TEST(Bridges, NoneWhereSelectedTransitionsAlreadyJoinTheCores) {
  WalkRun s;
  const std::vector<Transition> candidates = {t(31, 151, 5.0f), t(140, 40, 8.0f)};
  const std::vector<Transition> selected = {t(45, 165, 2.0f)};  // walk core -> run core
  auto bridges = select_bridges(candidates, selected, s.tags, {}, s.cores, 4, {});
  ASSERT_EQ(bridges.bridges.size(), 1u);
  EXPECT_EQ(bridges.bridges[0].from_frame, 140);
  EXPECT_TRUE(bridges.unjoined.empty());
  // A tag without a core gets none, and both directions are reported unjoined for that reason;
  // nor do bridges come when switched off.
  s.cores[1].clear();
  auto coreless = select_bridges(candidates, {}, s.tags, {}, s.cores, 4, {});
  EXPECT_TRUE(coreless.bridges.empty());
  ASSERT_EQ(coreless.unjoined.size(), 2u);
  EXPECT_EQ(coreless.unjoined[0].reason, UnjoinedReason::kNoCore);
  EXPECT_EQ(coreless.unjoined[1].from_tag, 1);
  EXPECT_LT(coreless.unjoined[1].best_distance, 0.0f);
  BridgeSettings off;
  off.per_tag_pair = 0;
  EXPECT_TRUE(select_bridges(candidates, {}, WalkRun().tags, {}, WalkRun().cores, 4, off).bridges.empty());
}

TEST(Bridges, NoneAboveTheCapAndThePairReportedWithItsBestDistance) {
  WalkRun s;
  const std::vector<Transition> candidates = {t(31, 151, 5.0f), t(50, 170, 7.0f), t(140, 40, 8.0f)};
  BridgeSettings settings;
  settings.max_distance = 6.0;
  auto got = select_bridges(candidates, {}, s.tags, {}, s.cores, 4, settings);
  ASSERT_EQ(got.bridges.size(), 1u);  // walk -> run at 5; run -> walk's only candidate is 8
  EXPECT_EQ(got.bridges[0].from_frame, 31);
  ASSERT_EQ(got.unjoined.size(), 1u);
  EXPECT_EQ(got.unjoined[0].from_tag, 1);
  EXPECT_EQ(got.unjoined[0].to_tag, 0);
  EXPECT_EQ(got.unjoined[0].reason, UnjoinedReason::kAboveCap);
  EXPECT_FLOAT_EQ(got.unjoined[0].best_distance, 8.0f);
  // Without any candidate from run to walk the reason says so.
  got = select_bridges(std::vector<Transition>{t(31, 151, 5.0f)}, {}, s.tags, {}, s.cores, 4, settings);
  ASSERT_EQ(got.unjoined.size(), 1u);
  EXPECT_EQ(got.unjoined[0].reason, UnjoinedReason::kNoCandidate);
  EXPECT_LT(got.unjoined[0].best_distance, 0.0f);
}

// Two clips of 100 frames (no motion needed to build a graph): walk, then run; window 4.
MotionDatabase two_clips() {
  MotionDatabase db;
  db.fps = 30.0;
  for (int c = 0; c < 2; ++c) {
    DatabaseClip clip;
    clip.name = c == 0 ? "walk" : "run";
    clip.first_frame = 100 * c;
    clip.frame_count = 100;
    db.clips.push_back(clip);
  }
  return db;
}

// Where a bridge's blend leaves and lands, checked against what every blend must keep: it lies
// inside its two clips, is at least the window long, and pairs the frames D was measured on
// (frame from + p of the clip it leaves with to - k + 1 + p of the one it arrives in).
BridgeBlend checked_blend(const MotionDatabase& db, const Transition& bridge, int k, double factor,
                          std::span<const char> core = {}) {
  const BridgeBlend b = bridge_blend(db, bridge, k, 1.0, factor, core);
  EXPECT_GE(b.frames, k);
  EXPECT_EQ((b.to_frame - b.frames + 1) - b.from_frame, (bridge.to_frame - k + 1) - bridge.from_frame)
      << "pairs other frames than the measured window";
  EXPECT_LE(b.from_frame, bridge.from_frame);
  EXPECT_GE(b.to_frame, bridge.to_frame);
  EXPECT_EQ(db.clip_of(b.from_frame), db.clip_of(bridge.from_frame));
  EXPECT_EQ(db.clip_of(b.from_frame + b.frames - 1), db.clip_of(bridge.from_frame));
  EXPECT_EQ(db.clip_of(b.to_frame - b.frames + 1), db.clip_of(bridge.to_frame));
  EXPECT_EQ(db.clip_of(b.to_frame), db.clip_of(bridge.to_frame));
  for (int f = b.from_frame; f <= bridge.from_frame && !core.empty(); ++f) EXPECT_TRUE(core[f]) << f;
  for (int f = bridge.to_frame; f <= b.to_frame && !core.empty(); ++f) EXPECT_TRUE(core[f]) << f;
  return b;
}

TEST(Bridges, BlendLengthGrowsWithTheSquareRootOfDistanceWithinItsBoundsAndClips) {
  const MotionDatabase db = two_clips();
  const int k = 10;
  auto frames = [&](const Transition& bridge, double factor) { return checked_blend(db, bridge, k, factor).frames; };
  // Interior: k sqrt(D / threshold), between k and 3k.
  EXPECT_EQ(frames(t(20, 150, 4.0f), 3.0), 20);
  EXPECT_EQ(frames(t(20, 150, 2.25f), 3.0), 15);
  EXPECT_EQ(frames(t(20, 150, 100.0f), 3.0), 30);
  EXPECT_EQ(frames(t(20, 150, 0.5f), 3.0), k);
  EXPECT_EQ(frames(t(20, 150, 100.0f), 1.0), k);
  // Near the end of the clip it leaves (frames 80..99) the blend starts earlier to keep its
  // length; with frames 88..99 left and the arrival window at 103..112 (3 frames before it in
  // its clip), it grows by those 3 and the 2 after; with neither, it is the window.
  EXPECT_EQ(frames(t(80, 150, 100.0f), 3.0), 30);
  EXPECT_EQ(frames(t(88, 112, 100.0f), 3.0), 15);
  EXPECT_EQ(frames(t(90, 109, 100.0f), 3.0), k);
}

TEST(Bridges, ALongerBlendIsCentredOnTheMeasuredWindowAndKeepsItsPairs) {
  const MotionDatabase db = two_clips();
  const int k = 10;
  // 20 frames for a window of 10: 5 before the window's first pair (20 <-> 141) and 5 after its
  // last (29 <-> 150). Reading 20 frames from 20 and 20 up to 150 would pair 20 with 131.
  BridgeBlend b = checked_blend(db, t(20, 150, 4.0f), k, 3.0);
  EXPECT_EQ(b.from_frame, 15);
  EXPECT_EQ(b.to_frame, 155);
  // 15 frames: 2 before, 3 after.
  b = checked_blend(db, t(20, 150, 2.25f), k, 3.0);
  EXPECT_EQ(b.from_frame, 18);
  EXPECT_EQ(b.to_frame, 153);
  // No frames after the window in the clip it leaves (90..99): all 20 extra before it.
  b = checked_blend(db, t(90, 140, 100.0f), k, 3.0);
  EXPECT_EQ(b.from_frame, 70);
  EXPECT_EQ(b.to_frame, 140);
  // Its ends stay in the core: frames from 17 and up to 157 only.
  std::vector<char> core(200, 0);
  std::fill(core.begin() + 17, core.begin() + 158, 1);
  b = checked_blend(db, t(20, 150, 100.0f), k, 3.0, core);
  EXPECT_EQ(b.from_frame, 17);
  EXPECT_EQ(b.to_frame, 157);
  EXPECT_EQ(b.frames, 20);
  // A frame outside the core between the candidate and a longer blend's end stops it there.
  core[147 + 5] = 0;
  b = checked_blend(db, t(20, 150, 100.0f), k, 3.0, core);
  EXPECT_EQ(b.to_frame, 151);
}

TEST(TagCoreFrames, TheCycleOfATagsOwnTransitionsOrNothing) {
  const WalkRun s;
  const MotionDatabase db = two_clips();
  // Walk's transitions loop 70 -> 30 within the walk clip: its core is frames 30..70.
  const std::vector<Transition> selected = {t(70, 30, 1.0f), t(150, 190, 1.0f)};
  auto walk = tag_core_frames(db, selected, s.tags, 4, 0);
  ASSERT_TRUE(walk) << walk.error().to_string();
  ASSERT_EQ(walk->size(), 200u);
  EXPECT_TRUE((*walk)[30] && (*walk)[60]);
  EXPECT_FALSE((*walk)[10] || (*walk)[90] || (*walk)[150]);
  // Run's only transition goes forward: no cycle, no core, and no error.
  auto run = tag_core_frames(db, selected, s.tags, 4, 1);
  ASSERT_TRUE(run) << run.error().to_string();
  EXPECT_TRUE(run->empty());
}

TEST(TagCoreFrames, AGraphThatCannotBeBuiltIsAnError) {
  const WalkRun s;
  MotionDatabase db = two_clips();
  db.clips.pop_back();  // frame tags for 200 frames, a database of 100
  auto core = tag_core_frames(db, std::vector<Transition>{t(170, 130, 1.0f)}, s.tags, 4, 1);
  ASSERT_FALSE(core);
  EXPECT_NE(core.error().kind, ErrorKind::kEmptyGraph);
}

// The rule written pair by pair, over every candidate in order of distance (ties in input
// order): for each ordered pair of tags (s, u) not already joined, the best candidates leaving
// frames of s (not u) in s's core and landing on frames of u (not s) in u's core, at most
// per_tag_pair of them, none within the locality radius of one taken before it: first one onto
// each set of tags (the frame's), then one into each clip (of `clips`, per frame), then the best
// of the rest.
// Candidates above `cap` (when >= 0) bridge nothing; a pair not joined and left without a
// bridge is listed in `unjoined` with the best D of the candidates that would bridge it.
std::vector<Transition> reference_bridges(const std::vector<Transition>& candidates, const std::vector<TagMask>& tags,
                                          const std::vector<int>& clips,
                                          const std::vector<std::vector<char>>& cores, int window, int per_pair,
                                          int radius, const std::vector<std::pair<int, int>>& joined, double cap,
                                          std::vector<UnjoinedPair>& unjoined) {
  auto window_tags = [&](int first) {
    TagMask m = ~TagMask{0};
    for (int f = first; f < first + window; ++f) m &= f >= 0 && f < static_cast<int>(tags.size()) ? tags[f] : 0;
    return m;
  };
  std::vector<Transition> sorted = candidates;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Transition& x, const Transition& y) { return x.distance < y.distance; });
  std::vector<Transition> out;
  const int n = static_cast<int>(cores.size());
  for (int s = 0; s < n; ++s) {
    for (int u = 0; u < n; ++u) {
      if (s == u || std::count(joined.begin(), joined.end(), std::make_pair(s, u)) > 0) continue;
      std::vector<Transition> pair;
      float best = -1.0f;
      for (const int round : {0, 1, 2}) {
        for (const Transition& c : sorted) {
          const TagMask from = window_tags(c.from_frame), to = window_tags(c.to_frame - window + 1);
          if (!(from >> s & 1) || (from >> u & 1) || !(to >> u & 1) || (to >> s & 1)) continue;
          if (!cores[s][c.from_frame] || !cores[u][c.to_frame]) continue;
          if (round == 0 && (best < 0.0f || c.distance < best)) best = c.distance;
          if (cap >= 0.0 && c.distance > cap) continue;
          if (static_cast<int>(pair.size()) >= per_pair) continue;
          const bool taken = std::any_of(pair.begin(), pair.end(), [&](const Transition& o) {
            return o.from_frame == c.from_frame && o.to_frame == c.to_frame;
          });
          const bool tags_taken =
              std::any_of(pair.begin(), pair.end(), [&](const Transition& o) { return tags[o.to_frame] == tags[c.to_frame]; });
          const bool clip_taken = std::any_of(pair.begin(), pair.end(),
                                              [&](const Transition& o) { return clips[o.to_frame] == clips[c.to_frame]; });
          if (taken || (round == 0 && tags_taken) || (round == 1 && clip_taken)) continue;
          if (std::none_of(pair.begin(), pair.end(), [&](const Transition& o) {
                return std::abs(o.from_frame - c.from_frame) <= radius || std::abs(o.to_frame - c.to_frame) <= radius;
              })) {
            pair.push_back(c);
          }
        }
      }
      if (pair.empty()) {
        unjoined.push_back({s, u, best < 0.0f ? UnjoinedReason::kNoCandidate : UnjoinedReason::kAboveCap, best});
      }
      for (const Transition& c : pair) {
        if (std::none_of(out.begin(), out.end(), [&](const Transition& b) {
              return b.from_frame == c.from_frame && b.to_frame == c.to_frame;
            })) {
          out.push_back(c);
        }
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const Transition& x, const Transition& y) {
    return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
  });
  return out;
}

// A random library of kRandomFrames frames (window kRandomWindow): runs of one or two of three
// tags (walk, run, jump and mixes such as walk+turn: bit 3), clips of 10-80 frames (their tags
// changing within them or not), a core per tag on random stretches of its frames (two share
// frames where clips carry both), and `count` candidates with D from 0 to distances - 1 (many
// tied).
constexpr int kRandomFrames = 300, kRandomWindow = 4;
struct RandomLibrary {
  std::vector<TagMask> tags;
  std::vector<int> clips;
  std::vector<std::vector<char>> cores;
  std::vector<Transition> candidates;
};
RandomLibrary random_library(std::mt19937& rng, int count, int distances) {
  const int frames = kRandomFrames, window = kRandomWindow;
  RandomLibrary l;
  l.tags.assign(frames, 0);
  for (int f = 0; f < frames;) {
    const int length = 5 + static_cast<int>(rng() % 40);
    TagMask m = TagMask{1} << (rng() % 3);
    if (rng() % 3 == 0) m |= TagMask{1} << 3;
    if (rng() % 5 == 0) m |= TagMask{1} << (rng() % 3);
    for (int i = f; i < std::min(frames, f + length); ++i) l.tags[i] = m;
    f += length;
  }
  l.clips.assign(frames, 0);
  for (int f = 0, clip = 0; f < frames; ++clip) {
    const int length = 10 + static_cast<int>(rng() % 71);
    for (int i = f; i < std::min(frames, f + length); ++i) l.clips[i] = clip;
    f += length;
  }
  l.cores.assign(4, std::vector<char>(frames, 0));
  for (int c = 0; c < 4; ++c) {
    for (int f = 0; f < frames; ++f) l.cores[c][f] = (l.tags[f] >> c & 1) && rng() % 4 != 0;
  }
  for (int i = 0; i < count; ++i) {
    const int from = static_cast<int>(rng() % (frames - window)), to = window - 1 + static_cast<int>(rng() % (frames - window));
    l.candidates.push_back(t(from, to, static_cast<float>(rng() % static_cast<unsigned>(distances))));
  }
  return l;
}

TEST(Bridges, SameAsTheRuleWrittenPairByPairOnRandomLibraries) {
  std::mt19937 rng(7);
  size_t total = 0, with_joined = 0, unjoined = 0, sharing = 0;
  long above_cap = 0;
  for (int round = 0; round < 80; ++round) {
    const int frames = kRandomFrames, window = kRandomWindow;
    const RandomLibrary library = random_library(rng, 400, 20);
    const auto& tags = library.tags;
    const auto& clips = library.clips;
    const auto& cores = library.cores;
    const auto& candidates = library.candidates;
    std::vector<Transition> selected;
    for (int i = 0; i < 3; ++i) selected.push_back(candidates[rng() % candidates.size()]);
    BridgeSettings settings;
    settings.per_tag_pair = 1 + static_cast<int>(rng() % 3);
    settings.locality_radius = static_cast<int>(rng() % 6);
    settings.tags = 0b0111;  // bit 3 is a modifier: never bridged
    settings.max_distance = round % 3 == 0 ? -1.0 : static_cast<double>(rng() % 20);
    // The pairs the selected transitions already join, core to core: leaving frames of s,
    // landing on frames of u that the leaving ones lack.
    std::vector<std::pair<int, int>> joined;
    auto window_tags = [&](int first) {
      TagMask m = ~TagMask{0};
      for (int f = first; f < first + window; ++f) m &= tags[f];
      return m;
    };
    for (const Transition& c : selected) {
      const TagMask from = window_tags(c.from_frame), to = window_tags(c.to_frame - window + 1);
      for (int s = 0; s < 3; ++s) {
        for (int u = 0; u < 3; ++u) {
          if (s != u && (from >> s & 1) && (to >> u & 1) && !(from >> u & 1) && cores[s][c.from_frame] &&
              cores[u][c.to_frame]) {
            joined.emplace_back(s, u);
          }
        }
      }
    }
    // And the pairs whose cores share a frame.
    for (int s = 0; s < 3; ++s) {
      for (int u = 0; u < 3; ++u) {
        for (int f = 0; f < frames && s != u; ++f) {
          if (cores[s][f] && cores[u][f]) {
            joined.emplace_back(s, u);
            ++sharing;
            break;
          }
        }
      }
    }
    std::vector<UnjoinedPair> expected_unjoined;
    const auto expected =
        reference_bridges(candidates, tags, clips, {cores[0], cores[1], cores[2]}, window, settings.per_tag_pair,
                          settings.locality_radius, joined, settings.max_distance, expected_unjoined);
    const auto selection = select_bridges(candidates, selected, tags, clips, cores, window, settings);
    const auto& got = selection.bridges;
    ASSERT_EQ(got.size(), expected.size()) << "round " << round;
    total += got.size();
    with_joined += joined.empty() ? 0 : 1;
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].from_frame, expected[i].from_frame) << "round " << round;
      EXPECT_EQ(got[i].to_frame, expected[i].to_frame) << "round " << round;
    }
    ASSERT_EQ(selection.unjoined.size(), expected_unjoined.size()) << "round " << round;
    for (size_t i = 0; i < expected_unjoined.size(); ++i) {
      EXPECT_EQ(selection.unjoined[i].from_tag, expected_unjoined[i].from_tag) << "round " << round;
      EXPECT_EQ(selection.unjoined[i].to_tag, expected_unjoined[i].to_tag) << "round " << round;
      EXPECT_EQ(selection.unjoined[i].reason, expected_unjoined[i].reason) << "round " << round;
      EXPECT_EQ(selection.unjoined[i].best_distance, expected_unjoined[i].best_distance) << "round " << round;
    }
    unjoined += expected_unjoined.size();
    above_cap += std::count_if(expected_unjoined.begin(), expected_unjoined.end(),
                               [](const UnjoinedPair& p) { return p.reason == UnjoinedReason::kAboveCap; });
  }
  // The rounds exercise the rule: many bridges, pairs already joined in some rounds (by cores
  // sharing frames in some), and pairs left unjoined because of the cap.
  EXPECT_GT(total, 100u);
  EXPECT_GT(with_joined, 5u);
  EXPECT_GT(sharing, 5u);
  EXPECT_GT(above_cap, 3);
  EXPECT_GT(unjoined, static_cast<size_t>(above_cap));
}

// Known only up to a level (the pruned stage's candidates), a pair not listed incomplete has the
// bridges all its candidates give: on random libraries (tags, clips, cores), each pair at a
// random level, candidates above it left out; and raising the levels of the pairs listed until
// none is gives all the candidates' bridges and unjoined pairs.
TEST(Bridges, APairNotIncompleteHasTheBridgesAllCandidatesGive) {
  std::mt19937 rng(11);
  long complete = 0, incomplete = 0;
  auto same = [](const std::vector<Transition>& a, const std::vector<Transition>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const Transition& x, const Transition& y) {
      return x.from_frame == y.from_frame && x.to_frame == y.to_frame;
    });
  };
  for (int round = 0; round < 300; ++round) {
    const int window = kRandomWindow;
    const RandomLibrary library = random_library(rng, 150, 40);
    const auto& tags = library.tags;
    const auto& clips = library.clips;
    const auto& cores = library.cores;
    const auto& candidates = library.candidates;
    BridgeSettings settings;
    settings.per_tag_pair = 1 + static_cast<int>(rng() % 4);
    settings.locality_radius = static_cast<int>(rng() % 6);
    settings.tags = 0b0111;
    settings.max_distance = round % 3 == 0 ? -1.0 : static_cast<double>(rng() % 40);
    const auto all = select_bridges(candidates, {}, tags, clips, cores, window, settings);
    for (int s = 0; s < 3; ++s) {
      for (int u = 0; u < 3; ++u) {
        if (s == u) continue;
        std::vector<double> levels(kBridgeTags * kBridgeTags, std::numeric_limits<double>::infinity());
        levels[s * kBridgeTags + u] = static_cast<double>(rng() % 40);
        const auto part = select_bridges(candidates, {}, tags, clips, cores, window, settings, {}, levels);
        const bool listed = std::any_of(part.incomplete.begin(), part.incomplete.end(),
                                        [&](const TagPair& p) { return p.from_tag == s && p.to_tag == u; });
        if (listed) {
          ++incomplete;
          continue;
        }
        ++complete;
        EXPECT_TRUE(same(part.bridges, all.bridges)) << "round " << round << ", pair " << s << " -> " << u;
      }
    }
    // As the build does it: every pair at a random level, the incomplete ones raised (4x and 1
    // more, past the highest D to all) until none is; the bridges and the pairs left unjoined
    // are those all the candidates give.
    std::vector<double> levels(kBridgeTags * kBridgeTags, std::numeric_limits<double>::infinity());
    for (int s = 0; s < 3; ++s) {
      for (int u = 0; u < 3; ++u) levels[s * kBridgeTags + u] = static_cast<double>(rng() % 40);
    }
    BridgeSelection raised;
    for (int step = 0;; ++step) {
      ASSERT_LT(step, 100) << "round " << round;
      raised = select_bridges(candidates, {}, tags, clips, cores, window, settings, {}, levels);
      if (raised.incomplete.empty()) break;
      for (const TagPair& p : raised.incomplete) {
        double& level = levels[p.from_tag * kBridgeTags + p.to_tag];
        level = 4.0 * level + 1.0 > 40.0 ? std::numeric_limits<double>::infinity() : 4.0 * level + 1.0;
      }
    }
    EXPECT_TRUE(same(raised.bridges, all.bridges)) << "round " << round;
    ASSERT_EQ(raised.unjoined.size(), all.unjoined.size()) << "round " << round;
    for (size_t i = 0; i < all.unjoined.size(); ++i) {
      EXPECT_EQ(raised.unjoined[i].from_tag, all.unjoined[i].from_tag) << "round " << round;
      EXPECT_EQ(raised.unjoined[i].to_tag, all.unjoined[i].to_tag) << "round " << round;
      EXPECT_EQ(raised.unjoined[i].reason, all.unjoined[i].reason) << "round " << round;
      EXPECT_EQ(raised.unjoined[i].best_distance, all.unjoined[i].best_distance) << "round " << round;
    }
  }
  // Both answers are common.
  EXPECT_GT(complete, 300);
  EXPECT_GT(incomplete, 300);
}

}  // namespace
}  // namespace mg
