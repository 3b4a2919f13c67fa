// From candidates to the pruned graph on a few bundled clips: the motion types, the bridges
// (aligned, only between connected tags), and the pruned graph's transitions coming from the
// selection and bridges.
#include "motiongraph/graph/graph_from_candidates.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "motiongraph/graph/bridges.h"
#include "motiongraph/graph/threshold_choice.h"
#include "motiongraph/graph/window_membership.h"
#include "motiongraph/metric/pair_alignment.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(GraphFromCandidates, ModifierTagsAreNotMotionTypes) {
  MotionDatabase db;
  db.tag_names = {"walk", "turn", "run", "stop", "backward"};
  EXPECT_EQ(motion_type_tags(db), TagMask{0b00101});
  EXPECT_TRUE(is_modifier_tag("veer"));
  EXPECT_FALSE(is_modifier_tag("jump"));
  const std::vector<std::string> names = {"run", "turn"};
  EXPECT_EQ(*tag_mask_of(db, names), TagMask{0b00110});
  const std::vector<std::string> unknown = {"swim"};
  auto error = tag_mask_of(db, unknown);
  ASSERT_FALSE(error);
  EXPECT_NE(error.error().message.find("'swim'"), std::string::npos);
}

struct Fixture {
  MotionDatabase db;
  FrameFeatures features;
  CandidateSearch search;
};

Fixture run() {
  Fixture x;
  x.db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_17.amc"});
  // Two motion types: the first clip is "a", the others "b" (their own transitions are few).
  x.db.tag_names = {"a", "b"};
  x.db.tag_ranges = {TagRange{0, x.db.clips[0].first_frame, x.db.clips[0].frame_count},
                     TagRange{1, x.db.clips[1].first_frame, x.db.frame_count() - x.db.clips[1].first_frame}};
  DistanceSettings distance;
  distance.threads = 2;
  auto layout = make_cloud_layout(x.db.skeletons[0], {});
  x.features = *make_frame_features(x.db, *layout, distance);
  auto search = find_candidates(x.features, distance, {});
  EXPECT_TRUE(search) << search.error().to_string();
  x.search = std::move(*search);
  return x;
}

bool same_pair(const Transition& x, const Transition& y) {
  return x.from_frame == y.from_frame && x.to_frame == y.to_frame;
}

TEST(GraphFromCandidates, PrunedGraphUsesTheSelectionAndAlignedBridges) {
  const Fixture x = run();
  GraphFromCandidatesSettings settings;
  settings.transitions.threshold_quantile = 0.01;  // low enough that motion types need bridges
  settings.connected_tags = motion_type_tags(x.db);
  auto built = graph_from_candidates(x.db, x.features, x.search, settings);
  ASSERT_TRUE(built) << built.error().to_string();
  const TransitionsWithBridges& t = built->transitions;
  EXPECT_EQ(t.all_transitions.size(), t.selection.transitions.size() + t.bridges.size());
  EXPECT_TRUE(std::is_sorted(t.all_transitions.begin(), t.all_transitions.end(), [](const auto& p, const auto& q) {
    return p.from_frame != q.from_frame ? p.from_frame < q.from_frame : p.to_frame < q.to_frame;
  }));
  // Each bridge is a candidate minimum, aligned as its window; it asks for the blend its D gives.
  const int k = x.features.window;
  for (size_t b = 0; b < t.bridges.size(); ++b) {
    const Transition& bridge = t.bridges[b];
    EXPECT_TRUE(std::any_of(x.search.minima.begin(), x.search.minima.end(), [&](const Transition& c) {
      return same_pair(c, bridge) && c.distance == bridge.distance;
    }));
    const FloorAlignment align = align_pair(x.features, bridge.from_frame, bridge.to_frame);
    EXPECT_FLOAT_EQ(bridge.yaw_rad, static_cast<float>(align.yaw_rad));
    EXPECT_FLOAT_EQ(bridge.x_m, static_cast<float>(align.x_m));
    // Between the window and 3 windows, longer for a larger D.
    EXPECT_GE(t.bridge_blends[b], k);
    EXPECT_LE(t.bridge_blends[b], 3 * k);
    for (size_t c = 0; c < t.bridges.size(); ++c) {
      if (t.bridges[c].distance < bridge.distance) {
        EXPECT_LE(t.bridge_blends[c], t.bridge_blends[b]);
      }
    }
  }
  // The graph's transitions are the selection's and the bridges. A bridge edge's blend is centred
  // on its candidate's window: its transition leaves blend_lead frames before the candidate and
  // lands the rest of its blend's extra frames after it, on the same pairs of frames, as long as
  // the bridge asks or shorter; every other edge has no lead. Clip edges are never bridges.
  ASSERT_FALSE(t.bridges.empty());
  // The candidate a graph edge plays, and whether it is a bridge.
  auto candidate_of = [&](const MotionGraph& g, const GraphEdge& edge) {
    Transition c = g.transitions[static_cast<size_t>(edge.transition_index)];
    const int extra = blend_frames(edge) - k;
    c.from_frame += edge.blend_lead;
    c.to_frame -= extra - edge.blend_lead;
    const auto bridge = std::find_if(t.bridges.begin(), t.bridges.end(), [&](const Transition& b) {
      return same_pair(b, c);
    });
    return std::pair{c, bridge == t.bridges.end() ? -1 : static_cast<int>(bridge - t.bridges.begin())};
  };
  auto check_edges = [&](const MotionGraph& g) {
    int bridge_edges = 0;
    for (const GraphEdge& edge : g.edges) {
      if (!edge.transition) {
        EXPECT_FALSE(edge.bridge);
        EXPECT_EQ(edge.blend_lead, 0);
        continue;
      }
      const auto found = candidate_of(g, edge);
      const Transition c = found.first;
      const int b = found.second;
      EXPECT_EQ(edge.bridge, b >= 0) << c.from_frame << " -> " << c.to_frame;
      EXPECT_TRUE(std::any_of(t.all_transitions.begin(), t.all_transitions.end(),
                              [&](const Transition& a) { return same_pair(a, c); }));
      if (b < 0) {
        EXPECT_EQ(blend_frames(edge), k);
        EXPECT_EQ(edge.blend_lead, 0);
        continue;
      }
      ++bridge_edges;
      EXPECT_GE(blend_frames(edge), k);
      EXPECT_LE(blend_frames(edge), t.bridge_blends[static_cast<size_t>(b)]);
      EXPECT_GE(edge.blend_lead, 0);
      EXPECT_LE(edge.blend_lead, blend_frames(edge) - k);
    }
    return bridge_edges;
  };
  // Placed, the graph prunes to itself, and its report's before and after are of one graph.
  auto placed_and_steady = [&](const PrunedGraph& pruned) {
    EXPECT_TRUE(pruned.bridge_blends_placed);
    EXPECT_TRUE(std::any_of(pruned.graph.edges.begin(), pruned.graph.edges.end(),
                            [&](const GraphEdge& e) { return e.bridge && blend_frames(e) > k; }));
    EXPECT_EQ(pruned.prune.after.nodes, pruned.graph.node_count());
    EXPECT_LE(pruned.prune.after.nodes, pruned.prune.before.largest_component_nodes);
    EXPECT_EQ(pruned.prune.kept_transitions.size(), pruned.graph.transitions.size());
    MotionGraph again = pruned.graph;
    PruneSettings prune;
    prune.connected_tags = settings.connected_tags;
    auto report = prune_motion_graph(again, x.db.frame_tags(), prune);
    ASSERT_TRUE(report) << report.error().to_string();
    EXPECT_EQ(report->after.nodes, pruned.graph.node_count());
    EXPECT_EQ(report->after.transitions, static_cast<int>(pruned.graph.transitions.size()));
  };
  const MotionGraph& graph = built->pruned.graph;
  ASSERT_GT(graph.node_count(), 0);
  placed_and_steady(built->pruned);
  const int bridge_edges = check_edges(graph);
  EXPECT_GT(bridge_edges, 0);
  // Some bridge blends longer than the window, and some leaves before its candidate.
  EXPECT_TRUE(std::any_of(graph.edges.begin(), graph.edges.end(),
                          [&](const GraphEdge& e) { return e.bridge && e.blend_lead > 0; }));
  // The same through spacing (which spaces the others; the second pruning may drop bridges).
  settings.spacing.max_out = 2;  // at 1, the second pruning dropped every bridge of subject 16
  auto spaced_graph = graph_from_candidates(x.db, x.features, x.search, settings);
  ASSERT_TRUE(spaced_graph) << spaced_graph.error().to_string();
  EXPECT_LT(spaced_graph->pruned.graph.transitions.size(), graph.transitions.size()) << "nothing spaced";
  const int spaced_bridges = check_edges(spaced_graph->pruned.graph);
  EXPECT_GT(spaced_bridges, 0);
  EXPECT_LE(spaced_bridges, bridge_edges);
  placed_and_steady(spaced_graph->pruned);
  settings.spacing.max_out = 0;
  // A tag on single frames next to where the bridges leave and land (a manifest's range): a
  // moved end there would split a piece into pieces of other tags, which pruning may drop. The
  // bridges are still placed, on pieces of one set of tags, and pruning keeps every transition.
  {
    Fixture tagged = run();
    tagged.db.tag_names.push_back("steady");
    const int steady = static_cast<int>(tagged.db.tag_names.size()) - 1;
    for (const Transition& bridge : t.bridges) {
      tagged.db.tag_ranges.push_back(TagRange{steady, bridge.from_frame - 2, 1});
      tagged.db.tag_ranges.push_back(TagRange{steady, bridge.to_frame + 2, 1});
    }
    GraphFromCandidatesSettings steady_settings = settings;
    steady_settings.connected_tags = motion_type_tags(tagged.db);
    auto steady_graph = graph_from_candidates(tagged.db, tagged.features, tagged.search, steady_settings);
    ASSERT_TRUE(steady_graph) << steady_graph.error().to_string();
    EXPECT_TRUE(steady_graph->pruned.bridge_blends_placed);
    const std::vector<TagMask> tags = tagged.db.frame_tags();
    for (const GraphEdge& e : steady_graph->pruned.graph.edges) {
      if (!e.bridge) continue;
      const MeasuredPair pair = measured_pair(steady_graph->pruned.graph, e);
      const Transition& moved = steady_graph->pruned.graph.transitions[static_cast<size_t>(e.transition_index)];
      for (int f = moved.from_frame; f < pair.from_frame; ++f) EXPECT_EQ(tags[f] >> steady & 1, 0u) << f;
      for (int f = pair.to_frame + 1; f <= moved.to_frame; ++f) EXPECT_EQ(tags[f] >> steady & 1, 0u) << f;
    }
  }

  // Tags ignored: no bridges, no per-tag thresholds; the same steps one by one agree.
  settings.connected_tags = 0;
  settings.spacing.max_out = 1;  // one transition leaving any window: some go
  auto plain = graph_from_candidates(x.db, x.features, x.search, settings);
  ASSERT_TRUE(plain) << plain.error().to_string();
  EXPECT_TRUE(plain->transitions.bridges.empty());
  EXPECT_TRUE(plain->transitions.selection.tag_thresholds.empty());
  auto selection = select_transitions(x.features, x.search, settings.transitions);
  ASSERT_TRUE(selection);
  ASSERT_EQ(selection->transitions.size(), plain->transitions.all_transitions.size());
  // Pruned, the survivors spaced, pruned again.
  auto first = build_pruned_graph(x.db, selection->transitions, x.features.window, 0);
  ASSERT_TRUE(first);
  EXPECT_EQ(plain->pruned.survived_first_pruning, static_cast<int>(first->graph.transitions.size()));
  const std::vector<Transition> spaced =
      space_transitions(first->graph.transitions, x.features.clip_of_frame, x.features.window, settings.spacing);
  EXPECT_LT(spaced.size(), first->graph.transitions.size());
  auto pruned = build_pruned_graph(x.db, spaced, x.features.window, 0);
  ASSERT_TRUE(pruned);
  EXPECT_EQ(pruned->graph.node_count(), plain->pruned.graph.node_count());
  EXPECT_EQ(pruned->graph.edge_count(), plain->pruned.graph.edge_count());
}

// Clips of no motion type amid typed ones (the untagged class) are bridged to the types as a type
// is: three walks typed and a copy of the first raised 6 cm, of no type, which no transition under
// 3 cm joins to them. The graph plays both the walks and the copy through bridges each way; with
// no bridges it keeps one side only. The class's own pairs are not reported unjoined.
TEST(GraphFromCandidates, ClipsOfNoTypeAreBridgedAsATypeIs) {
  Fixture x;
  x.db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_17.amc"}, true, 0.0,
                              Vec3(0.0, 0.06, 0.0));
  const int copy = x.db.clips.back().first_frame;
  x.db.tag_names = {"walk"};
  x.db.tag_ranges = {TagRange{0, 0, copy}};
  DistanceSettings distance;
  distance.threads = 2;
  auto layout = make_cloud_layout(x.db.skeletons[0], {});
  x.features = *make_frame_features(x.db, *layout, distance);
  x.search = *find_candidates(x.features, distance, {});
  const std::vector<char> in_class = untagged_class_frames(x.db, 0b1);
  ASSERT_EQ(untagged_bridge_tag(x.db, in_class), 1);
  ASSERT_EQ(untagged_bridge_tag(x.db, std::vector<char>(in_class.size(), 0)), -1);
  GraphFromCandidatesSettings settings;
  settings.transitions.threshold = distance_of_rms_cm(3.0, x.features);
  settings.connected_tags = 0b1;
  // Per side, whether the pruned graph's clip edges play a frame of it.
  const auto sides = [&](const MotionGraph& graph) {
    std::pair<bool, bool> played{false, false};
    for (const GraphEdge& e : graph.edges) {
      if (e.transition) continue;
      (graph.nodes[e.from_node].frame < copy ? played.first : played.second) = true;
    }
    return played;
  };
  auto built = graph_from_candidates(x.db, x.features, x.search, settings);
  ASSERT_TRUE(built) << built.error().to_string();
  const auto& bridges = built->transitions.bridges;
  const auto leaves = [&](const Transition& t) { return t.from_frame < copy && t.to_frame >= copy; };
  const auto arrives = [&](const Transition& t) { return t.from_frame >= copy && t.to_frame < copy; };
  EXPECT_TRUE(std::any_of(bridges.begin(), bridges.end(), leaves));
  EXPECT_TRUE(std::any_of(bridges.begin(), bridges.end(), arrives));
  for (const Transition& t : bridges) EXPECT_TRUE(leaves(t) || arrives(t)) << t.from_frame << " " << t.to_frame;
  EXPECT_TRUE(built->transitions.unjoined.empty());
  EXPECT_EQ(sides(built->pruned.graph), std::make_pair(true, true));
  // Capped under every candidate between them: no bridge, and no pair reported unjoined (the
  // only pairs there are are the class's).
  GraphFromCandidatesSettings capped = settings;
  capped.bridges.max_distance = settings.transitions.threshold;
  auto unbridged = select_transitions_with_bridges(x.db, x.features, x.search, capped);
  ASSERT_TRUE(unbridged) << unbridged.error().to_string();
  EXPECT_TRUE(unbridged->bridges.empty());
  EXPECT_TRUE(unbridged->unjoined.empty());
  settings.bridges.per_tag_pair = 0;
  auto alone = graph_from_candidates(x.db, x.features, x.search, settings);
  ASSERT_TRUE(alone) << alone.error().to_string();
  const auto [walks, raised] = sides(alone->pruned.graph);
  EXPECT_NE(walks, raised);
}

TEST(GraphFromCandidates, NoCycleIsAnError) {
  const Fixture x = run();
  GraphFromCandidatesSettings settings;
  settings.transitions.threshold = 0.0;  // nothing below it: three clips, no cycle
  settings.bridges.per_tag_pair = 0;
  EXPECT_FALSE(graph_from_candidates(x.db, x.features, x.search, settings));
}

}  // namespace
}  // namespace mg
