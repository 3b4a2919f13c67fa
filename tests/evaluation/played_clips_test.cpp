#include "motiongraph/evaluation/played_clips.h"

#include <gtest/gtest.h>

#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

using nlohmann::json;

MotionDatabase two_clips() {
  MotionDatabase db;
  db.fps = 10.0;
  for (const char* name : {"walk", "run"}) {
    DatabaseClip clip;
    clip.name = name;
    clip.first_frame = db.frame_count();
    clip.frame_count = 20;
    db.clips.push_back(std::move(clip));
  }
  return db;
}

// Walk's frames 5-9, a blend of three frames into run's 2-4, run's 5-8 and its 8 held twice (a
// rest), a jump back to walk's frame 3 (another piece), then the frames past the output's end.
TEST(PlayedClips, PiecesOfClipsAndTheBlendsBetweenThem) {
  const MotionDatabase db = two_clips();
  std::vector<FrameSource> sources;
  for (int f = 5; f <= 9; ++f) sources.push_back({f, f, 1.0});
  for (int i = 0; i < 3; ++i) sources.push_back({10 + i, 20 + 2 + i, 1.0 - (i + 1) / 4.0});
  for (int f = 25; f <= 28; ++f) sources.push_back({f, f, 1.0});
  sources.push_back({28, 28, 1.0});
  sources.push_back({0, 28, 0.0});  // all arrival: run's 8 again
  sources.push_back({3, 3, 1.0});
  sources.push_back({4, 4, 1.0});  // past the output's end
  const json played = played_clips_json(db, sources, 10.0, static_cast<int>(sources.size()) - 1);
  const json expected = json::array(
      {{{"at_s", 0.0}, {"seconds", 0.5}, {"clip", "walk"}, {"first_frame", 5}, {"last_frame", 9}},
       {{"at_s", 0.5}, {"seconds", 0.3}, {"blend_from", "walk"}, {"blend_to", "run"}},
       {{"at_s", 0.8}, {"seconds", 0.6}, {"clip", "run"}, {"first_frame", 5}, {"last_frame", 8}},
       {{"at_s", 1.4}, {"seconds", 0.1}, {"clip", "walk"}, {"first_frame", 3}, {"last_frame", 3}}});
  ASSERT_EQ(played.size(), expected.size()) << played.dump(1);
  for (size_t i = 0; i < played.size(); ++i) {
    for (const auto& [key, value] : expected[i].items()) {
      if (value.is_number_float()) {
        EXPECT_NEAR(played[i].at(key).get<double>(), value.get<double>(), 1e-12) << i << " " << key;
      } else {
        EXPECT_EQ(played[i].at(key), value) << i << " " << key;
      }
    }
    EXPECT_EQ(played[i].size(), expected[i].size()) << played[i];
  }
}

// A walk of the subject-16 graph: the pieces and blends follow one another to the output's end, every piece
// inside its clip.
TEST(PlayedClips, AWalkOnSubject16IsAccountedForFrameByFrame) {
  const LoadedGraph& graph = test::subject16();
  const SynthesisContext& context = graph.context();
  const MotionDatabase& db = *context.db;
  // A walk of the graph's first edges, out of node 0 each time it can.
  Walk walk{0, {}};
  int node = 0;
  for (int i = 0; i < 40; ++i) {
    const auto out = context.graph->out_edges(node);
    if (out.empty()) break;
    const int e = static_cast<int>(&out[static_cast<size_t>(i) % out.size()] - context.graph->edges.data());
    walk.edges.push_back(e);
    node = context.graph->edges[static_cast<size_t>(e)].to_node;
  }
  const std::vector<FrameSource> sources = context.walk_sources(walk);
  const json played = played_clips_json(db, sources, db.fps, static_cast<int>(sources.size()));
  double at = 0.0;
  for (const json& p : played) {
    EXPECT_NEAR(p["at_s"].get<double>(), at, 1e-9);
    at += p["seconds"].get<double>();
    if (!p.contains("clip")) continue;
    const auto clip = std::find_if(db.clips.begin(), db.clips.end(), [&](const DatabaseClip& c) {
      return c.name == p["clip"].get<std::string>();
    });
    ASSERT_NE(clip, db.clips.end());
    EXPECT_GE(p["first_frame"].get<int>(), 0);
    EXPECT_LE(p["first_frame"].get<int>(), p["last_frame"].get<int>());
    EXPECT_LT(p["last_frame"].get<int>(), clip->frame_count);
  }
  EXPECT_NEAR(at, sources.size() / db.fps, 1e-9);
}

}  // namespace
}  // namespace mg
