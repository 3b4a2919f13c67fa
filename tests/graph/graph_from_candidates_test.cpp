// From candidates to the pruned graph on a few bundled clips: the motion types, the bridges
// (aligned, only between connected tags), and the pruned graph's transitions coming from the
// selection and bridges.
#include "motiongraph/graph/graph_from_candidates.h"

#include <algorithm>

#include <gtest/gtest.h>

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
  // Each bridge is a candidate minimum whose longer blend leaves earlier and lands later on the
  // same pairing of frames (graph/bridges.h): its D and alignment are the candidate's.
  const int k = x.features.window;
  for (size_t b = 0; b < t.bridges.size(); ++b) {
    const Transition& bridge = t.bridges[b];
    const int blend = t.bridge_blends[b];
    const auto candidate = std::find_if(x.search.minima.begin(), x.search.minima.end(), [&](const Transition& c) {
      return c.to_frame - k + 1 - c.from_frame == bridge.to_frame - blend + 1 - bridge.from_frame &&
             c.from_frame >= bridge.from_frame && c.to_frame <= bridge.to_frame && c.distance == bridge.distance;
    });
    ASSERT_NE(candidate, x.search.minima.end()) << bridge.from_frame << " -> " << bridge.to_frame;
    const FloorAlignment align = align_pair(x.features, candidate->from_frame, candidate->to_frame);
    EXPECT_FLOAT_EQ(bridge.yaw_rad, static_cast<float>(align.yaw_rad));
    EXPECT_FLOAT_EQ(bridge.x_m, static_cast<float>(align.x_m));
  }
  const MotionGraph& graph = built->pruned.graph;
  ASSERT_GT(graph.node_count(), 0);
  EXPECT_EQ(built->pruned.prune.after.nodes, graph.node_count());
  EXPECT_LE(built->pruned.prune.after.nodes, built->pruned.prune.before.nodes);
  for (const Transition& kept : graph.transitions) {
    EXPECT_TRUE(std::any_of(t.all_transitions.begin(), t.all_transitions.end(),
                            [&](const Transition& c) { return same_pair(c, kept); }));
  }
  // Each transition edge is flagged a bridge exactly when its transition is one of the bridges
  // (and keeps the bridge's blend); clip edges never are.
  ASSERT_FALSE(t.bridges.empty());
  int bridge_edges = 0;
  for (const GraphEdge& edge : graph.edges) {
    if (!edge.transition) {
      EXPECT_FALSE(edge.bridge);
      continue;
    }
    const Transition& kept = graph.transitions[edge.transition_index];
    const auto bridge = std::find_if(t.bridges.begin(), t.bridges.end(),
                                     [&](const Transition& c) { return same_pair(c, kept); });
    EXPECT_EQ(edge.bridge, bridge != t.bridges.end()) << kept.from_frame << " -> " << kept.to_frame;
    if (bridge != t.bridges.end()) {
      ++bridge_edges;
      EXPECT_EQ(blend_frames(edge), t.bridge_blends[bridge - t.bridges.begin()]);
    }
  }
  EXPECT_GT(bridge_edges, 0);
  // The same through spacing (which spaces the others; the second pruning may drop bridges: at
  // one transition leaving any window it drops all three here, whose blends land a frame or two
  // later than their candidates, where little of motion type "b" is left).
  settings.spacing.max_out = 2;
  auto spaced_graph = graph_from_candidates(x.db, x.features, x.search, settings);
  ASSERT_TRUE(spaced_graph) << spaced_graph.error().to_string();
  EXPECT_LT(spaced_graph->pruned.graph.transitions.size(), graph.transitions.size()) << "nothing spaced";
  int spaced_bridges = 0;
  for (const GraphEdge& edge : spaced_graph->pruned.graph.edges) {
    if (!edge.transition) continue;
    const Transition& kept = spaced_graph->pruned.graph.transitions[edge.transition_index];
    const bool is_bridge = std::any_of(t.bridges.begin(), t.bridges.end(),
                                       [&](const Transition& c) { return same_pair(c, kept); });
    EXPECT_EQ(edge.bridge, is_bridge);
    spaced_bridges += edge.bridge ? 1 : 0;
  }
  EXPECT_GT(spaced_bridges, 0);
  EXPECT_LE(spaced_bridges, bridge_edges);
  settings.spacing.max_out = 0;

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

TEST(GraphFromCandidates, NoCycleIsAnError) {
  const Fixture x = run();
  GraphFromCandidatesSettings settings;
  settings.transitions.threshold = 0.0;  // nothing below it: three clips, no cycle
  settings.bridges.per_tag_pair = 0;
  EXPECT_FALSE(graph_from_candidates(x.db, x.features, x.search, settings));
}

}  // namespace
}  // namespace mg
