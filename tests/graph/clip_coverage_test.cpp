#include "motiongraph/graph/clip_coverage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace mg {
namespace {

MotionDatabase make_db(const std::vector<int>& lengths) {
  MotionDatabase db;
  int first = 0;
  for (size_t c = 0; c < lengths.size(); ++c) {
    DatabaseClip clip;
    clip.name = "clip" + std::to_string(c);
    clip.first_frame = first;
    clip.frame_count = lengths[c];
    db.clips.push_back(clip);
    first += lengths[c];
  }
  return db;
}

int clip_of(const MotionDatabase& db, int frame) {
  for (size_t c = 0; c < db.clips.size(); ++c) {
    if (frame < db.clips[c].first_frame + db.clips[c].frame_count) return static_cast<int>(c);
  }
  return -1;
}

// Brute force: a frame is played when the last node at or before it in its clip has a clip
// edge out (which then runs to the clip's next node, past the frame).
bool played(const MotionGraph& g, const MotionDatabase& db, int frame) {
  const int clip = clip_of(db, frame);
  int last = -1;
  for (int n = 0; n < g.node_count(); ++n) {
    if (g.nodes[n].clip == clip && g.nodes[n].frame <= frame) last = n;
  }
  if (last < 0) return false;
  for (const GraphEdge& e : g.out_edges(last)) {
    if (!e.transition) return true;
  }
  return false;
}

Transition candidate(int from, int to, float distance) {
  Transition t;
  t.from_frame = from;
  t.to_frame = to;
  t.distance = distance;
  return t;
}

TEST(ClipCoverage, CountsThePlayedFramesOfEachClipAndTheCheapestWayThroughTheClipsItLoses) {
  std::mt19937 rng(7);
  const int window = 3;
  int checked_lost = 0, lost_that_could_join = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::uniform_int_distribution<int> clips_n(1, 5), length(window, 30);
    std::vector<int> lengths(static_cast<size_t>(clips_n(rng)));
    for (int& l : lengths) l = length(rng);
    const MotionDatabase db = make_db(lengths);
    // Random candidates whose windows lie inside one clip each.
    std::vector<Transition> candidates;
    std::uniform_int_distribution<int> pick_clip(0, static_cast<int>(lengths.size()) - 1);
    std::uniform_real_distribution<float> distance(0.0f, 10.0f);
    for (int i = 0; i < 40; ++i) {
      const DatabaseClip& a = db.clips[pick_clip(rng)];
      const DatabaseClip& b = db.clips[pick_clip(rng)];
      const int from = a.first_frame + std::uniform_int_distribution<int>(0, a.frame_count - window)(rng);
      const int to = b.first_frame + std::uniform_int_distribution<int>(window - 1, b.frame_count - 1)(rng);
      candidates.push_back(candidate(from, to, distance(rng)));
    }
    std::sort(candidates.begin(), candidates.end(), [](const Transition& x, const Transition& y) {
      return std::pair(x.from_frame, x.to_frame) < std::pair(y.from_frame, y.to_frame);
    });
    candidates.erase(std::unique(candidates.begin(), candidates.end(),
                                 [](const Transition& x, const Transition& y) {
                                   return x.from_frame == y.from_frame && x.to_frame == y.to_frame;
                                 }),
                     candidates.end());
    // The graph keeps the candidates below 5, pruned when pruning leaves something.
    std::vector<Transition> selected;
    for (const Transition& t : candidates) {
      if (t.distance < 5.0f) selected.push_back(t);
    }
    auto graph = build_motion_graph(db, selected, window);
    ASSERT_TRUE(graph) << graph.error().message;
    if (trial % 2 == 0) (void)prune_motion_graph(*graph, {});

    const std::vector<ClipCoverage> coverage = clip_coverage(*graph, db, candidates);
    ASSERT_EQ(coverage.size(), db.clips.size());
    long long total = 0;
    std::vector<char> kept(static_cast<size_t>(db.frame_count()), 0);
    for (int f = 0; f < db.frame_count(); ++f) kept[f] = played(*graph, db, f) ? 1 : 0;
    for (size_t c = 0; c < coverage.size(); ++c) {
      const DatabaseClip& clip = db.clips[c];
      int expected = 0;
      for (int f = clip.first_frame; f < clip.first_frame + clip.frame_count; ++f) expected += kept[f];
      EXPECT_EQ(coverage[c].clip, static_cast<int>(c));
      EXPECT_EQ(coverage[c].frames, clip.frame_count);
      EXPECT_EQ(coverage[c].kept_frames, expected) << "trial " << trial << " clip " << c;
      total += coverage[c].kept_frames;
      // The best pair of candidates entering a clip the graph keeps nothing of from a kept frame
      // and leaving it, later, for a kept frame.
      float best_join = -1.0f;
      if (expected == 0) {
        ++checked_lost;
        for (const Transition& in : candidates) {
          if (clip_of(db, in.to_frame) != static_cast<int>(c) || !kept[in.from_frame]) continue;
          for (const Transition& out : candidates) {
            if (clip_of(db, out.from_frame) != static_cast<int>(c) || !kept[out.to_frame]) continue;
            if (out.from_frame <= in.to_frame) continue;
            const float join = std::max(in.distance, out.distance);
            if (best_join < 0.0f || join < best_join) best_join = join;
          }
        }
      }
      lost_that_could_join += best_join >= 0.0f ? 1 : 0;
      EXPECT_EQ(coverage[c].best_join, best_join) << "trial " << trial << " clip " << c;
    }
    // The graph's own count of the frames its clip edges play.
    EXPECT_EQ(total, compute_graph_statistics(*graph, {}).clip_frames) << "trial " << trial;
  }
  EXPECT_GT(checked_lost, 100);       // the trials do lose clips
  EXPECT_GT(lost_that_could_join, 10);  // and some of them could join it
}

}  // namespace
}  // namespace mg
