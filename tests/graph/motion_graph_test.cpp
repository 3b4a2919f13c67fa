#include "motiongraph/graph/motion_graph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace mg {
namespace {

// A database of clips with only names and frame ranges (no motion needed by the graph).
MotionDatabase make_db(const std::vector<std::pair<std::string, int>>& clips) {
  MotionDatabase db;
  int first = 0;
  for (const auto& [name, frames] : clips) {
    DatabaseClip clip;
    clip.name = name;
    clip.first_frame = first;
    clip.frame_count = frames;
    db.clips.push_back(clip);
    first += frames;
  }
  return db;
}

void add_tag(MotionDatabase& db, const std::string& name, int first_frame, int frame_count) {
  db.tag_ranges.push_back({db.tag_index(name), first_frame, frame_count});
}

Transition transition(int from_frame, int to_frame) {
  Transition t;
  t.from_frame = from_frame;
  t.to_frame = to_frame;
  return t;
}

std::vector<int> node_frames(const MotionGraph& g) {
  std::vector<int> frames;
  for (const GraphNode& n : g.nodes) frames.push_back(n.frame);
  return frames;
}

// An edge by what it is, independent of node and transition numbering.
struct EdgeKey {
  int from_frame, to_frame;
  bool transition;
  auto operator<=>(const EdgeKey&) const = default;
};

std::set<EdgeKey> edge_keys(const MotionGraph& g) {
  std::set<EdgeKey> keys;
  for (const GraphEdge& e : g.edges) keys.insert({g.nodes[e.from_node].frame, g.nodes[e.to_node].frame, e.transition});
  return keys;
}

// --- Brute-force checks, independent of the code under test ---------------------------------

// Nodes reachable from `start` over the edges `use` accepts.
std::vector<char> reachable(const MotionGraph& g, int start, const std::function<bool(const GraphEdge&)>& use) {
  std::vector<char> seen(g.nodes.size(), 0);
  std::deque<int> queue{start};
  seen[start] = 1;
  while (!queue.empty()) {
    const int u = queue.front();
    queue.pop_front();
    for (const GraphEdge& e : g.edges) {
      if (e.from_node == u && use(e) && !seen[e.to_node]) {
        seen[e.to_node] = 1;
        queue.push_back(e.to_node);
      }
    }
  }
  return seen;
}

// Whether the edges `use` accepts, with their end nodes, form one strongly connected subgraph
// (true when there are none).
bool strongly_connected(const MotionGraph& g, const std::function<bool(const GraphEdge&)>& use) {
  std::vector<char> touched(g.nodes.size(), 0);
  for (const GraphEdge& e : g.edges) {
    if (use(e)) touched[e.from_node] = touched[e.to_node] = 1;
  }
  for (int u = 0; u < g.node_count(); ++u) {
    if (!touched[u]) continue;
    const std::vector<char> seen = reachable(g, u, use);
    for (int v = 0; v < g.node_count(); ++v) {
      if (touched[v] && !seen[v]) return false;
    }
  }
  return true;
}

bool whole_graph_strongly_connected(const MotionGraph& g) {
  if (g.nodes.empty() || g.edges.empty()) return false;
  auto all = [](const GraphEdge&) { return true; };
  for (int u = 0; u < g.node_count(); ++u) {
    const std::vector<char> seen = reachable(g, u, all);
    if (std::count(seen.begin(), seen.end(), 1) != g.node_count()) return false;
  }
  return true;
}

// Tags of an edge computed frame by frame from the documented rule.
TagMask reference_edge_tags(const MotionGraph& g, const GraphEdge& e, const std::vector<TagMask>& tags) {
  std::vector<int> frames;
  if (e.transition) {
    const Transition& t = g.transitions[e.transition_index];
    for (int p = 0; p < g.window; ++p) frames.push_back(t.from_frame + p);
    for (int p = 0; p < g.window; ++p) frames.push_back(t.to_frame - g.window + 1 + p);
  } else {
    for (int f = g.nodes[e.from_node].frame; f < g.nodes[e.to_node].frame; ++f) frames.push_back(f);
  }
  TagMask mask = ~TagMask{0};
  for (int f : frames) mask &= static_cast<size_t>(f) < tags.size() ? tags[f] : 0;
  return tags.empty() ? 0 : mask;
}

bool tag_subgraph_strongly_connected(const MotionGraph& g, const std::vector<TagMask>& tags, int tag) {
  return strongly_connected(
      g, [&](const GraphEdge& e) { return ((reference_edge_tags(g, e, tags) >> tag) & 1) != 0; });
}

// The structural invariants of any graph, built or pruned.
void expect_well_formed(const MotionGraph& g, const MotionDatabase& db) {
  ASSERT_EQ(g.edge_offsets.size(), g.nodes.size() + 1);
  EXPECT_EQ(g.edge_offsets.front(), 0);
  EXPECT_EQ(g.edge_offsets.back(), g.edge_count());
  for (int v = 0; v + 1 < g.node_count(); ++v) EXPECT_LT(g.nodes[v].frame, g.nodes[v + 1].frame);
  for (const GraphNode& n : g.nodes) EXPECT_EQ(n.clip, db.clip_of(n.frame));
  int transition_edges = 0;
  for (int v = 0; v < g.node_count(); ++v) {
    for (int e = g.edge_offsets[v]; e < g.edge_offsets[v + 1]; ++e) EXPECT_EQ(g.edges[e].from_node, v);
  }
  for (const GraphEdge& e : g.edges) {
    const GraphNode& a = g.nodes[e.from_node];
    const GraphNode& b = g.nodes[e.to_node];
    if (e.transition) {
      ++transition_edges;
      ASSERT_GE(e.transition_index, 0);
      ASSERT_LT(e.transition_index, static_cast<int>(g.transitions.size()));
      EXPECT_EQ(g.transitions[e.transition_index].from_frame, a.frame);
      EXPECT_EQ(g.transitions[e.transition_index].to_frame, b.frame);
      // A transition plays its blend length L - 1 frames (L >= k), its windows inside their clips.
      EXPECT_GE(e.frame_count, g.window - 1);
      EXPECT_EQ(blend_frames(e), e.frame_count + 1);
      EXPECT_EQ(db.clip_of(a.frame + e.frame_count), a.clip);
      EXPECT_EQ(db.clip_of(b.frame - e.frame_count), b.clip);
    } else {
      EXPECT_EQ(e.transition_index, -1);
      EXPECT_EQ(a.clip, b.clip);
      EXPECT_EQ(e.to_node, e.from_node + 1);  // consecutive nodes
      EXPECT_EQ(e.frame_count, b.frame - a.frame);
      EXPECT_GT(e.frame_count, 0);
    }
  }
  EXPECT_EQ(transition_edges, static_cast<int>(g.transitions.size()));
}

// --- Building -------------------------------------------------------------------------------

// Clip A: frames 0..99, clip B: 100..179, k = 10.
MotionDatabase two_clips() { return make_db({{"A", 100}, {"B", 80}}); }

TEST(MotionGraphBuild, NodesAndEdgesOfTwoClips) {
  const MotionDatabase db = two_clips();
  const std::vector<Transition> transitions = {transition(60, 110), transition(150, 20)};
  auto built = build_motion_graph(db, transitions, 10);
  ASSERT_TRUE(built) << built.error().to_string();
  const MotionGraph& g = *built;
  expect_well_formed(g, db);
  EXPECT_EQ(g.window, 10);
  EXPECT_EQ(node_frames(g), (std::vector<int>{0, 20, 60, 99, 100, 110, 150, 179}));
  EXPECT_EQ(g.nodes[3].clip, 0);
  EXPECT_EQ(g.nodes[4].clip, 1);
  ASSERT_EQ(g.edge_count(), 8);

  struct Expected {
    int from, to;
    bool transition;
    int transition_index, frame_count;
  };
  const std::vector<Expected> expected = {
      {0, 20, false, -1, 20},  {20, 60, false, -1, 40}, {60, 99, false, -1, 39}, {60, 110, true, 0, 9},
      {100, 110, false, -1, 10}, {110, 150, false, -1, 40}, {150, 179, false, -1, 29}, {150, 20, true, 1, 9},
  };
  for (size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE(i);
    const GraphEdge& e = g.edges[i];
    EXPECT_EQ(g.nodes[e.from_node].frame, expected[i].from);
    EXPECT_EQ(g.nodes[e.to_node].frame, expected[i].to);
    EXPECT_EQ(e.transition, expected[i].transition);
    EXPECT_EQ(e.transition_index, expected[i].transition_index);
    EXPECT_EQ(e.frame_count, expected[i].frame_count);
  }
  // No clip edge across the clip boundary 99 | 100, none out of a clip's last frame.
  EXPECT_TRUE(g.out_edges(g.node_at_frame(99)).empty());
  EXPECT_TRUE(g.out_edges(g.node_at_frame(179)).empty());
  const auto out60 = g.out_edges(g.node_at_frame(60));
  ASSERT_EQ(out60.size(), 2u);
  EXPECT_FALSE(out60[0].transition);  // clip edge first
  EXPECT_TRUE(out60[1].transition);
  EXPECT_EQ(g.node_at_frame(61), -1);
}

TEST(MotionGraphBuild, SharedFramesShareANodeAndSelfLoopsAreEdges) {
  const MotionDatabase db = two_clips();
  // 50 is where one transition leaves and another lands; 40 -> 40 is a self-loop.
  const std::vector<Transition> transitions = {transition(50, 120), transition(130, 50), transition(40, 40)};
  auto built = build_motion_graph(db, transitions, 5);
  ASSERT_TRUE(built) << built.error().to_string();
  expect_well_formed(*built, db);
  EXPECT_EQ(node_frames(*built), (std::vector<int>{0, 40, 50, 99, 100, 120, 130, 179}));
  const int n40 = built->node_at_frame(40);
  const auto out40 = built->out_edges(n40);
  ASSERT_EQ(out40.size(), 2u);
  EXPECT_EQ(out40[1].to_node, n40);
  EXPECT_EQ(out40[1].frame_count, 4);
}

TEST(MotionGraphBuild, SingleFrameClipIsOneNode) {
  const MotionDatabase db = make_db({{"A", 30}, {"one", 1}, {"B", 30}});
  auto built = build_motion_graph(db, {}, 4);
  ASSERT_TRUE(built);
  expect_well_formed(*built, db);
  EXPECT_EQ(node_frames(*built), (std::vector<int>{0, 29, 30, 31, 60}));
  EXPECT_EQ(built->edge_count(), 2);
}

TEST(MotionGraphBuild, TransitionWindowsMayTouchClipEnds) {
  const MotionDatabase db = two_clips();
  // Leave at 90 (window 90..99, A's last frame), land at 109 (window 100..109, B's first frame).
  auto built = build_motion_graph(db, std::vector<Transition>{transition(90, 109)}, 10);
  ASSERT_TRUE(built) << built.error().to_string();
  expect_well_formed(*built, db);
}

TEST(MotionGraphBuild, ATransitionBlendsOverItsOwnLengthWhenGiven) {
  const MotionDatabase db = two_clips();
  const std::vector<Transition> transitions = {transition(60, 130), transition(150, 20)};
  auto built = build_motion_graph(db, transitions, 10, std::vector<int>{25, 10});
  ASSERT_TRUE(built) << built.error().to_string();
  expect_well_formed(*built, db);
  for (const GraphEdge& e : built->edges) {
    if (e.transition) {
      EXPECT_EQ(e.frame_count, e.transition_index == 0 ? 24 : 9);
    }
  }
  // Tags are read over the whole blend: frames 60..84 and 106..130. Tag x covers the window of
  // k frames on both sides (60..69, 121..130) but not 106..107.
  MotionDatabase tagged = two_clips();
  add_tag(tagged, "walk", 0, 180);
  add_tag(tagged, "x", 50, 50);
  add_tag(tagged, "x", 108, 72);
  const std::vector<TagMask> tags = tagged.frame_tags();
  const TagMask walk = 1, x = 2;
  for (const int length : {10, 25}) {
    auto graph = build_motion_graph(tagged, std::vector<Transition>{transition(60, 130)}, 10, std::vector<int>{length});
    ASSERT_TRUE(graph);
    for (const GraphEdge& e : graph->edges) {
      if (e.transition) {
        EXPECT_EQ(edge_tags(*graph, e, tags), length == 10 ? (walk | x) : walk) << length;
      }
    }
  }
  // A blend that does not fit its clips, one shorter than the window, or lengths for other
  // transitions: errors.
  auto too_long = build_motion_graph(db, std::vector<Transition>{transition(60, 130)}, 10, std::vector<int>{41});
  ASSERT_FALSE(too_long);
  EXPECT_NE(too_long.error().message.find("runs past the end of clip 'A'"), std::string::npos);
  auto before_start = build_motion_graph(db, std::vector<Transition>{transition(20, 120)}, 10, std::vector<int>{22});
  ASSERT_FALSE(before_start);
  EXPECT_NE(before_start.error().message.find("starts before clip 'B'"), std::string::npos);
  EXPECT_FALSE(build_motion_graph(db, std::vector<Transition>{transition(60, 130)}, 10, std::vector<int>{9}));
  EXPECT_FALSE(build_motion_graph(db, transitions, 10, std::vector<int>{12}));
}

TEST(MotionGraphBuild, RejectsBadInput) {
  const MotionDatabase db = two_clips();
  struct Case {
    const char* rule;
    MotionDatabase db;
    std::vector<Transition> transitions;
    int window;
    const char* message_part;
  };
  MotionDatabase gap = two_clips();
  gap.clips[1].first_frame = 101;
  MotionDatabase empty_clip = make_db({{"A", 100}, {"E", 0}});
  const std::vector<Case> cases = {
      {"window at least 2", db, {}, 1, "at least 2 frames"},
      {"clips follow each other", gap, {}, 10, "clip 'B' starts at global frame 101 instead of 100"},
      {"clips have frames", empty_clip, {}, 10, "clip 'E' has no frames"},
      {"frames inside the database", db, {transition(60, 180)}, 10, "outside the database's 180 frames"},
      {"no negative frames", db, {transition(-1, 50)}, 10, "outside the database"},
      {"leaving window inside its clip", db, {transition(91, 150)}, 10, "window 91..100 runs past the end of clip 'A'"},
      {"arriving window inside its clip", db, {transition(20, 108)}, 10, "window 99..108 starts before clip 'B'"},
      {"arriving window inside the first clip", db, {transition(120, 5)}, 10, "starts before clip 'A'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.rule);
    auto built = build_motion_graph(c.db, c.transitions, c.window);
    ASSERT_FALSE(built);
    EXPECT_NE(built.error().message.find(c.message_part), std::string::npos) << built.error().message;
  }
}

// --- Edge tags --------------------------------------------------------------------------------

TEST(MotionGraphTags, AnEdgeCarriesATagWhenEveryFrameItReadsDoes) {
  // One clip: walk 0..59, run 60..119; a second clip all walk 120..179.
  MotionDatabase db = make_db({{"walk_run", 120}, {"walk", 60}});
  add_tag(db, "walk", 0, 60);
  add_tag(db, "run", 60, 60);
  add_tag(db, "walk", 120, 60);
  const std::vector<TagMask> tags = db.frame_tags();
  const TagMask walk = 1, run = 2;
  // Nodes of the first clip: 0, 30, 40, 50, 70, 119.
  const std::vector<Transition> transitions = {
      transition(40, 70),    // windows 40..49 walk, 61..70 run: no tag
      transition(30, 150),   // windows 30..39 walk, 141..150 walk: walk
      transition(50, 160)};  // windows 50..59 walk, 151..160 walk: walk (the window ends at 59)
  auto built = build_motion_graph(db, transitions, 10);
  ASSERT_TRUE(built) << built.error().to_string();
  const MotionGraph& g = *built;
  auto clip_edge = [&](int f1) { return g.out_edges(g.node_at_frame(f1))[0]; };
  EXPECT_EQ(edge_tags(g, clip_edge(30), tags), walk);  // 30..39
  EXPECT_EQ(edge_tags(g, clip_edge(40), tags), walk);  // 40..49
  EXPECT_EQ(edge_tags(g, clip_edge(50), tags), 0u);    // 50..69: walk then run
  EXPECT_EQ(edge_tags(g, clip_edge(70), tags), run);   // 70..118
  for (const GraphEdge& e : g.edges) EXPECT_EQ(edge_tags(g, e, tags), reference_edge_tags(g, e, tags));
  for (const GraphEdge& e : g.edges) {
    if (!e.transition) continue;
    const TagMask expected = e.transition_index == 0 ? 0 : walk;
    EXPECT_EQ(edge_tags(g, e, tags), expected) << "transition " << e.transition_index;
  }
  // A clip edge reaching into an untagged frame (or past the span) carries nothing.
  std::vector<TagMask> short_tags(tags.begin(), tags.begin() + 35);
  EXPECT_EQ(edge_tags(g, clip_edge(30), short_tags), 0u);
  EXPECT_EQ(edge_tags(g, clip_edge(0), short_tags), walk);
  EXPECT_EQ(edge_tags(g, clip_edge(0), {}), 0u);
}

// --- Pruning without tags ---------------------------------------------------------------------

TEST(MotionGraphPrune, KeepsTheLargestStronglyConnectedComponent) {
  // A 0..99, B 100..179, C 180..229. Cycle: 20 -> 30 -> 60 =t0=> 110 -> 150 =t3=> 20.
  // C is entered (30 => 200) and left (185 => 140) but cannot get from 200 back to 185.
  const MotionDatabase db = make_db({{"A", 100}, {"B", 80}, {"C", 50}});
  const std::vector<Transition> transitions = {transition(60, 110), transition(30, 200), transition(185, 140),
                                               transition(150, 20)};
  auto built = build_motion_graph(db, transitions, 10);
  ASSERT_TRUE(built) << built.error().to_string();
  const MotionGraph original = *built;
  MotionGraph g = original;
  auto report = prune_motion_graph(g, {});
  ASSERT_TRUE(report) << report.error().to_string();
  expect_well_formed(g, db);

  EXPECT_EQ(node_frames(g), (std::vector<int>{20, 30, 60, 110, 140, 150}));
  const std::set<EdgeKey> expected_edges = {{20, 30, false},  {30, 60, false},  {60, 110, true},
                                            {110, 140, false}, {140, 150, false}, {150, 20, true}};
  EXPECT_EQ(edge_keys(g), expected_edges);
  EXPECT_TRUE(whole_graph_strongly_connected(g));

  // Transitions compacted in their order, indices remapped, mappings back to the original.
  ASSERT_EQ(g.transitions.size(), 2u);
  EXPECT_EQ(g.transitions[0].from_frame, 60);
  EXPECT_EQ(g.transitions[1].from_frame, 150);
  EXPECT_EQ(report->kept_transitions, (std::vector<int>{0, 3}));
  for (size_t v = 0; v < g.nodes.size(); ++v) EXPECT_EQ(original.nodes[report->kept_nodes[v]].frame, g.nodes[v].frame);
  for (size_t e = 0; e < g.edges.size(); ++e) {
    const GraphEdge& old_edge = original.edges[report->kept_edges[e]];
    EXPECT_EQ(original.nodes[old_edge.from_node].frame, g.nodes[g.edges[e].from_node].frame);
    EXPECT_EQ(original.nodes[old_edge.to_node].frame, g.nodes[g.edges[e].to_node].frame);
  }

  // Every removed node was not mutually reachable with the kept ones in the original graph.
  auto all = [](const GraphEdge&) { return true; };
  const int kept = original.node_at_frame(20);
  const std::vector<char> from_kept = reachable(original, kept, all);
  for (int v = 0; v < original.node_count(); ++v) {
    const bool is_kept = std::count(report->kept_nodes.begin(), report->kept_nodes.end(), v) > 0;
    const bool mutual = from_kept[v] && reachable(original, v, all)[kept];
    EXPECT_EQ(is_kept, mutual) << "frame " << original.nodes[v].frame;
  }

  // Statistics before and after.
  EXPECT_EQ(report->before.nodes, original.node_count());
  EXPECT_EQ(report->before.edges, original.edge_count());
  EXPECT_EQ(report->before.transitions, 4);
  EXPECT_EQ(report->before.clip_frames, 99 + 79 + 49);  // every frame but each clip's last
  EXPECT_EQ(report->before.largest_component_nodes, 6);
  EXPECT_EQ(report->after.nodes, 6);
  EXPECT_EQ(report->after.edges, 6);
  EXPECT_EQ(report->after.transitions, 2);
  EXPECT_EQ(report->after.clip_edges, 4);
  EXPECT_EQ(report->after.clip_frames, 10 + 30 + 30 + 10);
  EXPECT_EQ(report->after.largest_component_nodes, 6);
  EXPECT_EQ(report->after.components, 1);
  EXPECT_TRUE(report->after.tags.empty());

  // Pruning again changes nothing.
  MotionGraph again = g;
  auto second = prune_motion_graph(again, {});
  ASSERT_TRUE(second);
  EXPECT_EQ(second->passes, 1);
  EXPECT_EQ(edge_keys(again), edge_keys(g));
  EXPECT_EQ(node_frames(again), node_frames(g));
}

TEST(MotionGraphPrune, NoCycleIsAnErrorAndLeavesTheGraph) {
  const MotionDatabase db = two_clips();
  auto built = build_motion_graph(db, std::vector<Transition>{transition(60, 150)}, 10);
  ASSERT_TRUE(built);
  MotionGraph g = *built;
  auto report = prune_motion_graph(g, {});
  ASSERT_FALSE(report);
  EXPECT_NE(report.error().message.find("no cycle"), std::string::npos);
  EXPECT_EQ(node_frames(g), node_frames(*built));
  EXPECT_EQ(g.edge_count(), built->edge_count());
}

TEST(MotionGraphPrune, FrameTagsMustCoverTheGraph) {
  const MotionDatabase db = two_clips();
  auto built = build_motion_graph(db, std::vector<Transition>{transition(60, 110), transition(150, 20)}, 10);
  ASSERT_TRUE(built);
  MotionGraph g = *built;
  const std::vector<TagMask> short_tags(100, 1);
  auto report = prune_motion_graph(g, short_tags);
  ASSERT_FALSE(report);
  EXPECT_NE(report.error().message.find("cover 100 frames"), std::string::npos) << report.error().message;
  EXPECT_EQ(g.edge_count(), built->edge_count());
}

TEST(MotionGraphPrune, SelfLoopAloneSurvives) {
  const MotionDatabase db = make_db({{"A", 60}});
  auto built = build_motion_graph(db, std::vector<Transition>{transition(40, 40)}, 5);
  ASSERT_TRUE(built);
  MotionGraph g = *built;
  auto report = prune_motion_graph(g, {});
  ASSERT_TRUE(report) << report.error().to_string();
  EXPECT_EQ(node_frames(g), std::vector<int>{40});
  ASSERT_EQ(g.edge_count(), 1);
  EXPECT_TRUE(g.edges[0].transition);
}

// --- Pruning with tags ------------------------------------------------------------------------

// Walk clip W 0..119 (tag walk), run clip R 120..239 (tag run), k = 10.
// Loops: W 90 => 30, R 210 => 150. Between: W 60 => R 180, R 190 => W 50.
struct WalkRun {
  MotionDatabase db;
  std::vector<Transition> transitions;
};

WalkRun walk_run() {
  WalkRun w;
  w.db = make_db({{"walk", 120}, {"run", 120}});
  add_tag(w.db, "walk", 0, 120);
  add_tag(w.db, "run", 120, 120);
  w.transitions = {transition(90, 30), transition(210, 150), transition(60, 180), transition(190, 50)};
  return w;
}

void expect_each_tag_strongly_connected(const MotionGraph& g, const std::vector<TagMask>& tags, int tag_count) {
  for (int t = 0; t < tag_count; ++t) EXPECT_TRUE(tag_subgraph_strongly_connected(g, tags, t)) << "tag " << t;
}

TEST(MotionGraphPrune, WalkAndRunEachStayStronglyConnected) {
  const WalkRun w = walk_run();
  const std::vector<TagMask> tags = w.db.frame_tags();
  auto built = build_motion_graph(w.db, w.transitions, 10);
  ASSERT_TRUE(built) << built.error().to_string();
  MotionGraph g = *built;
  auto report = prune_motion_graph(g, tags);
  ASSERT_TRUE(report) << report.error().to_string();
  expect_well_formed(g, w.db);
  EXPECT_EQ(node_frames(g), (std::vector<int>{30, 50, 60, 90, 150, 180, 190, 210}));
  EXPECT_EQ(g.edge_count(), 10);
  EXPECT_TRUE(whole_graph_strongly_connected(g));
  expect_each_tag_strongly_connected(g, tags, 2);

  // Statistics per tag, after: walk plays 30..89 through 3 clip edges, plus its loop.
  ASSERT_EQ(report->after.tags.size(), 2u);
  const TagStatistics& walk = report->after.tags[0];
  EXPECT_EQ(walk.tag, 0);
  EXPECT_EQ(walk.database_frames, 120);
  EXPECT_EQ(walk.frames, 60);
  EXPECT_EQ(walk.nodes, 4);
  EXPECT_EQ(walk.edges, 4);
  EXPECT_EQ(walk.largest_component_nodes, 4);
  const TagStatistics& run = report->after.tags[1];
  EXPECT_EQ(run.tag, 1);
  EXPECT_EQ(run.frames, 60);
  EXPECT_EQ(run.edges, 4);
  // Before: walk's clip edges 0->30->50->60->90->119 (not 119, a clip's last frame).
  EXPECT_EQ(report->before.tags[0].frames, 119);
  EXPECT_EQ(report->before.tags[0].edges, 6);

  const std::string json = to_json(report->after, w.db.tag_names);
  EXPECT_NE(json.find("\"name\": \"walk\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"largest_component_nodes\": 8"), std::string::npos) << json;
}

TEST(MotionGraphPrune, TagEdgeLeadingOnlyOutOfItsTagGoes) {
  // Add W 100 => R 200: reaching 100 takes the walk clip edge 90 -> 100, from which no walk edge
  // leads back into walk. Whole-graph pruning keeps it; the tag rule removes 90 -> 100, and then
  // (next pass) node 100 and its transition. Node 200 stays: it is on the run loop.
  WalkRun w = walk_run();
  w.transitions.push_back(transition(100, 200));
  const std::vector<TagMask> tags = w.db.frame_tags();
  auto built = build_motion_graph(w.db, w.transitions, 10);
  ASSERT_TRUE(built) << built.error().to_string();

  MotionGraph untagged = *built;
  ASSERT_TRUE(prune_motion_graph(untagged, tags, PruneSettings{.connected_tags = 0}));
  EXPECT_NE(untagged.node_at_frame(100), -1);
  EXPECT_TRUE(whole_graph_strongly_connected(untagged));
  EXPECT_FALSE(tag_subgraph_strongly_connected(untagged, tags, 0));

  MotionGraph g = *built;
  auto report = prune_motion_graph(g, tags);
  ASSERT_TRUE(report) << report.error().to_string();
  EXPECT_EQ(g.node_at_frame(100), -1);
  EXPECT_EQ(node_frames(g), (std::vector<int>{30, 50, 60, 90, 150, 180, 190, 200, 210}));
  for (const Transition& t : g.transitions) EXPECT_NE(t.from_frame, 100);
  EXPECT_TRUE(whole_graph_strongly_connected(g));
  expect_each_tag_strongly_connected(g, tags, 2);
  EXPECT_GE(report->passes, 2);
}

TEST(MotionGraphPrune, WalkRegionReachableOnlyThroughRunIsDropped) {
  // A second walk clip W2 240..359 with its own loop (330 => 270), joined to the run clip only:
  // R 200 => W2 300 and W2 270 => R 160. Walk's subgraph then has two components, W's
  // {30, 50, 60, 90} and W2's {270, 300, 330}; the larger (W's) stays, W2's walk edges go and
  // W2 is stranded. The run loop keeps nodes 160 and 200.
  WalkRun w = walk_run();
  w.db = make_db({{"walk", 120}, {"run", 120}, {"walk2", 120}});
  add_tag(w.db, "walk", 0, 120);
  add_tag(w.db, "run", 120, 120);
  add_tag(w.db, "walk", 240, 120);
  w.transitions.push_back(transition(330, 270));
  w.transitions.push_back(transition(200, 300));
  w.transitions.push_back(transition(270, 160));
  const std::vector<TagMask> tags = w.db.frame_tags();
  auto built = build_motion_graph(w.db, w.transitions, 10);
  ASSERT_TRUE(built) << built.error().to_string();

  // Without the tag rule W2 is part of the graph's strongly connected component.
  MotionGraph untagged = *built;
  ASSERT_TRUE(prune_motion_graph(untagged, tags, PruneSettings{.connected_tags = 0}));
  EXPECT_NE(untagged.node_at_frame(300), -1);
  EXPECT_FALSE(tag_subgraph_strongly_connected(untagged, tags, 0));

  // Enforcing only run keeps W2 too (run's subgraph is one loop either way).
  MotionGraph run_only = *built;
  ASSERT_TRUE(prune_motion_graph(run_only, tags, PruneSettings{.connected_tags = 2}));
  EXPECT_NE(run_only.node_at_frame(300), -1);
  EXPECT_TRUE(tag_subgraph_strongly_connected(run_only, tags, 1));

  MotionGraph g = *built;
  auto report = prune_motion_graph(g, tags);
  ASSERT_TRUE(report) << report.error().to_string();
  expect_well_formed(g, w.db);
  EXPECT_EQ(node_frames(g), (std::vector<int>{30, 50, 60, 90, 150, 160, 180, 190, 200, 210}));
  EXPECT_TRUE(whole_graph_strongly_connected(g));
  expect_each_tag_strongly_connected(g, tags, 2);
  for (const Transition& t : g.transitions) EXPECT_LT(t.from_frame, 240);
}

// --- Random databases against a reference pruning --------------------------------------------

// The documented rule, implemented with brute-force reachability instead of Tarjan. Returns the
// alive flags of the original graph's nodes and edges.
struct Alive {
  std::vector<char> nodes, edges;
};

Alive reference_prune(const MotionGraph& g, const std::vector<TagMask>& tags, TagMask connected_tags) {
  Alive a{std::vector<char>(g.nodes.size(), 1), std::vector<char>(g.edges.size(), 1)};
  std::vector<TagMask> edge_tag(g.edges.size());
  for (size_t e = 0; e < g.edges.size(); ++e) edge_tag[e] = reference_edge_tags(g, g.edges[e], tags) & connected_tags;

  // Largest non-trivial class of mutual reachability over the edges `use` accepts (alive
  // nodes only); ties to the class with the lowest node. Returns its membership, or all zero.
  auto largest_class = [&](const std::vector<char>& use_edge) {
    const int n = g.node_count();
    std::vector<std::vector<char>> reach(n);
    for (int u = 0; u < n; ++u) {
      if (!a.nodes[u]) continue;
      reach[u] = reachable(g, u, [&](const GraphEdge& e) {
        const size_t idx = static_cast<size_t>(&e - g.edges.data());
        return use_edge[idx] && a.nodes[e.from_node] && a.nodes[e.to_node];
      });
    }
    std::vector<char> best(n, 0);
    int best_size = 0;
    for (int u = 0; u < n; ++u) {
      if (!a.nodes[u]) continue;
      std::vector<char> members(n, 0);
      int size = 0;
      bool lowest = true;
      for (int v = 0; v < n; ++v) {
        if (a.nodes[v] && reach[u][v] && reach[v][u]) {
          members[v] = 1;
          ++size;
          if (v < u) lowest = false;
        }
      }
      if (!lowest) continue;
      bool has_edge = false;
      for (size_t e = 0; e < g.edges.size(); ++e) {
        has_edge = has_edge || (use_edge[e] && members[g.edges[e].from_node] && members[g.edges[e].to_node]);
      }
      if (has_edge && size > best_size) {
        best_size = size;
        best = members;
      }
    }
    return best;
  };

  while (true) {
    bool removed = false;
    const std::vector<char> keep = largest_class(a.edges);
    for (int v = 0; v < g.node_count(); ++v) {
      if (a.nodes[v] && !keep[v]) a.nodes[v] = 0, removed = true;
    }
    for (size_t e = 0; e < g.edges.size(); ++e) {
      if (a.edges[e] && (!a.nodes[g.edges[e].from_node] || !a.nodes[g.edges[e].to_node])) a.edges[e] = 0, removed = true;
    }
    for (int t = 0; t < 64; ++t) {
      std::vector<char> tag_edges(g.edges.size(), 0);
      bool any = false;
      for (size_t e = 0; e < g.edges.size(); ++e) {
        tag_edges[e] = a.edges[e] && ((edge_tag[e] >> t) & 1);
        any = any || tag_edges[e];
      }
      if (!any) continue;
      const std::vector<char> tag_keep = largest_class(tag_edges);
      for (size_t e = 0; e < g.edges.size(); ++e) {
        if (tag_edges[e] && !(tag_keep[g.edges[e].from_node] && tag_keep[g.edges[e].to_node])) {
          a.edges[e] = 0;
          removed = true;
        }
      }
    }
    if (!removed) return a;
  }
}

struct RandomCase {
  MotionDatabase db;
  std::vector<Transition> transitions;
  int window = 2;
  int tag_count = 0;
};

RandomCase random_case(std::mt19937& rng) {
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  RandomCase c;
  c.window = uniform(2, 5);
  std::vector<std::pair<std::string, int>> clips;
  const int clip_count = uniform(1, 4);
  for (int i = 0; i < clip_count; ++i) clips.push_back({"c" + std::to_string(i), uniform(c.window, 40)});
  c.db = make_db(clips);
  c.tag_count = uniform(0, 3);
  for (int t = 0; t < c.tag_count; ++t) c.db.tag_index("t" + std::to_string(t));
  for (const DatabaseClip& clip : c.db.clips) {
    for (int r = uniform(0, 3); r > 0 && c.tag_count > 0; --r) {
      const int first = clip.first_frame + uniform(0, clip.frame_count - 1);
      const int count = uniform(1, clip.first_frame + clip.frame_count - first);
      c.db.tag_ranges.push_back({uniform(0, c.tag_count - 1), first, count});
    }
  }
  const int transition_count = uniform(0, 14);
  const int k = c.window;
  for (int i = 0; i < transition_count; ++i) {
    const DatabaseClip& a = c.db.clips[uniform(0, clip_count - 1)];
    const DatabaseClip& b = c.db.clips[uniform(0, clip_count - 1)];
    const int from = a.first_frame + uniform(0, a.frame_count - k);
    const int to = b.first_frame + uniform(k - 1, b.frame_count - 1);
    c.transitions.push_back(transition(from, to));
  }
  return c;
}

TEST(MotionGraphPrune, RandomDatabasesMatchTheReferenceAndTheGuarantees) {
  int pruned_to_something = 0, tag_rule_mattered = 0;
  for (unsigned seed = 0; seed < 300; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937 rng(seed);
    const RandomCase c = random_case(rng);
    const std::vector<TagMask> tags = c.db.frame_tags();
    auto built = build_motion_graph(c.db, c.transitions, c.window);
    ASSERT_TRUE(built) << built.error().to_string();
    const MotionGraph& original = *built;
    expect_well_formed(original, c.db);
    EXPECT_EQ(original.edge_count(), static_cast<int>(c.transitions.size()) +
                                         static_cast<int>(original.nodes.size()) - static_cast<int>(c.db.clips.size()));

    const Alive expected = reference_prune(original, tags, ~TagMask{0});
    const Alive untagged = reference_prune(original, tags, 0);
    if (expected.edges != untagged.edges) ++tag_rule_mattered;
    MotionGraph g = original;
    auto report = prune_motion_graph(g, tags);
    if (std::count(expected.nodes.begin(), expected.nodes.end(), 1) == 0) {
      EXPECT_FALSE(report);
      continue;
    }
    ASSERT_TRUE(report) << report.error().to_string();
    ++pruned_to_something;
    expect_well_formed(g, c.db);
    std::vector<int> expected_nodes, expected_edges;
    for (int v = 0; v < original.node_count(); ++v) {
      if (expected.nodes[v]) expected_nodes.push_back(v);
    }
    for (int e = 0; e < original.edge_count(); ++e) {
      if (expected.edges[e]) expected_edges.push_back(e);
    }
    EXPECT_EQ(report->kept_nodes, expected_nodes);
    EXPECT_EQ(report->kept_edges, expected_edges);

    // The guarantees, checked by brute force on the result.
    EXPECT_TRUE(whole_graph_strongly_connected(g));
    expect_each_tag_strongly_connected(g, tags, c.tag_count);
    for (int v = 0; v < g.node_count(); ++v) {
      EXPECT_FALSE(g.out_edges(v).empty()) << "dead end";
      EXPECT_TRUE(std::any_of(g.edges.begin(), g.edges.end(), [&](const GraphEdge& e) { return e.to_node == v; }));
    }
    EXPECT_EQ(report->after.nodes, g.node_count());
    EXPECT_EQ(report->after.largest_component_nodes, g.node_count());
    EXPECT_EQ(report->after.components, 1);

    // Idempotent.
    MotionGraph again = g;
    auto second = prune_motion_graph(again, tags);
    ASSERT_TRUE(second);
    EXPECT_EQ(second->passes, 1);
    EXPECT_EQ(edge_keys(again), edge_keys(g));
  }
  // The property test is only worth something if it exercises both outcomes and the tag rule.
  EXPECT_GT(pruned_to_something, 50);
  EXPECT_GT(tag_rule_mattered, 10);
}

}  // namespace
}  // namespace mg
