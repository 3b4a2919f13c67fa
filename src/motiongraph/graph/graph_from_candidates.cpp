// From cached candidates to the pruned motion graph: selection, bridges, graph, pruning.
#include "motiongraph/graph/graph_from_candidates.h"

#include <algorithm>
#include <functional>

#include <fmt/format.h>

#include "motiongraph/graph/window_membership.h"
#include "motiongraph/metric/pair_alignment.h"

namespace mg {

bool is_modifier_tag(const std::string& name) {
  for (const char* modifier : {"turn", "stop", "start", "backward", "veer"}) {
    if (name == modifier) return true;
  }
  return false;
}

TagMask motion_type_tags(const MotionDatabase& db) {
  TagMask mask = 0;
  for (size_t t = 0; t < db.tag_names.size(); ++t) {
    if (!is_modifier_tag(db.tag_names[t])) mask |= TagMask{1} << t;
  }
  return mask;
}

std::string motion_class_name(const MotionDatabase& db, int tag) {
  if (tag >= 0 && tag < static_cast<int>(db.tag_names.size())) return db.tag_names[tag];
  return "untagged";
}

Result<TagMask> tag_mask_of(const MotionDatabase& db, std::span<const std::string> names) {
  TagMask mask = 0;
  for (const std::string& name : names) {
    auto it = std::find(db.tag_names.begin(), db.tag_names.end(), name);
    if (it == db.tag_names.end()) return Error{"", 0, fmt::format("no clip has the tag '{}'", name)};
    mask |= TagMask{1} << (it - db.tag_names.begin());
  }
  return mask;
}

bool connected_bridges(const GraphFromCandidatesSettings& settings) {
  return settings.connected_tags != 0 && settings.bridges.per_tag_pair > 0;
}

Status GraphFromCandidatesSettings::validate() const {
  if (auto s = transitions.validate(); !s) return s;
  if (auto s = spacing.validate(); !s) return s;
  return bridges.validate();
}

Result<TransitionsWithBridges> select_transitions_with_bridges(const MotionDatabase& db, const FrameFeatures& features,
                                                               const CandidateSearch& candidates,
                                                               const GraphFromCandidatesSettings& settings,
                                                               OnDemandCandidates* more) {
  if (auto s = settings.validate(); !s) return s.error();
  if (candidates.ceiling >= 0.0 && more == nullptr && connected_bridges(settings)) {
    return Error{"", 0, "bridges on the pruned distance stage's candidates need the minima above its ceiling"};
  }
  TransitionsWithBridges out;
  const std::vector<TagMask> frame_tags = db.frame_tags();
  const TagMask connected = settings.connected_tags;
  const std::vector<char> untagged_class = untagged_class_frames(db, connected);
  auto selection = select_transitions(features, candidates, settings.transitions, frame_tags, connected,
                                      settings.aligned, untagged_class);
  if (!selection) return selection.error();
  out.selection = std::move(*selection);

  // Bridges between motion types that no transition below the threshold joins, the untagged
  // class one more (the tag after the database's: untagged_bridge_tag).
  BridgeSettings bridge_settings = settings.bridges;
  bridge_settings.locality_radius = out.selection.locality_radius;
  bridge_settings.tags = connected;
  if (connected_bridges(settings)) {
    std::vector<TagMask> bridge_tags = frame_tags;
    const int untagged = untagged_bridge_tag(db, untagged_class);
    if (untagged >= 0) {
      for (size_t f = 0; f < bridge_tags.size(); ++f) {
        if (untagged_class[f] != 0) bridge_tags[f] |= TagMask{1} << untagged;
      }
      bridge_settings.tags |= TagMask{1} << untagged;
    }
    std::vector<std::vector<char>> cores(db.tag_names.size() + (untagged >= 0 ? 1 : 0));
    for (size_t t = 0; t < cores.size(); ++t) {
      if (bridge_settings.tags >> t & 1) {
        auto core = tag_core_frames(db, out.selection.transitions, bridge_tags, features.window, static_cast<int>(t));
        if (!core) return core.error();
        cores[t] = std::move(*core);
      }
    }
    // With the pruned stage's candidates: raise the levels of the pairs still short of bridges
    // until none is.
    const bool pruned = candidates.ceiling >= 0.0 && more != nullptr;
    if (pruned && untagged >= 0) more->tag_windows(untagged, untagged_class);
    BridgeSelection bridges;
    while (true) {
      const std::vector<double> levels = pruned ? more->levels(cores) : std::vector<double>{};
      bridges = select_bridges(candidates.minima, out.selection.transitions, bridge_tags, features.clip_of_frame, cores,
                               features.window,
                               bridge_settings, pruned ? more->above() : std::span<const Transition>{}, levels);
      if (bridges.incomplete.empty()) break;
      if (auto s = more->raise(bridges.incomplete, cores); !s) return s.error();
    }
    out.bridges = std::move(bridges.bridges);
    // The untagged class's pairs are not reported: it is no type the user named (the coverage
    // warnings say what the graph loses of its clips).
    for (const UnjoinedPair& pair : bridges.unjoined) {
      if (pair.from_tag != untagged && pair.to_tag != untagged) out.unjoined.push_back(pair);
    }
  }
  for (Transition& t : out.bridges) {
    if (settings.aligned) {
      const FloorAlignment align = align_pair(features, t.from_frame, t.to_frame);
      t.yaw_rad = static_cast<float>(align.yaw_rad);
      t.x_m = static_cast<float>(align.x_m);
      t.z_m = static_cast<float>(align.z_m);
    }
    out.bridge_blends.push_back(
        bridge_blend_frames(t, features.window, out.selection.threshold, bridge_settings.max_blend_factor));
  }
  out.all_transitions = out.selection.transitions;
  out.all_transitions.insert(out.all_transitions.end(), out.bridges.begin(), out.bridges.end());
  std::sort(out.all_transitions.begin(), out.all_transitions.end(), [](const Transition& x, const Transition& y) {
    return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
  });
  return out;
}

namespace {

// The index of `t` among `bridges` (sorted by (from_frame, to_frame)), or -1.
long bridge_index(std::span<const Transition> bridges, const Transition& t) {
  auto before = [](const Transition& x, const Transition& y) {
    return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
  };
  auto it = std::lower_bound(bridges.begin(), bridges.end(), t, before);
  return it != bridges.end() && !before(t, *it) ? static_cast<long>(it - bridges.begin()) : -1;
}

}  // namespace

std::vector<char> TransitionsWithBridges::bridge_flags(std::span<const Transition> transitions) const {
  std::vector<char> flags(transitions.size(), 0);
  for (size_t i = 0; i < transitions.size() && !bridges.empty(); ++i) flags[i] = bridge_index(bridges, transitions[i]) >= 0;
  return flags;
}

Result<PrunedGraph> build_pruned_graph(const MotionDatabase& db, std::span<const Transition> transitions, int window,
                                       TagMask connected_tags, std::span<const int> blend_lengths,
                                       std::span<const char> bridges) {
  auto graph = build_motion_graph(db, transitions, window, blend_lengths, bridges);
  if (!graph) return graph.error();
  PruneSettings prune;
  prune.connected_tags = connected_tags;
  auto report = prune_motion_graph(*graph, db.frame_tags(), prune);
  if (!report) return report.error();
  return PrunedGraph{std::move(*graph), std::move(*report)};
}

Result<PrunedGraph> build_spaced_graph(const MotionDatabase& db, const TransitionsWithBridges& transitions,
                                       const FrameFeatures& features, const GraphFromCandidatesSettings& settings) {
  auto first = build_pruned_graph(db, transitions.all_transitions, features.window, settings.connected_tags, {},
                                  transitions.bridge_flags(transitions.all_transitions));
  if (!first) return first.error();
  const MotionGraph& kept = first->graph;
  std::vector<char> is_bridge(kept.transitions.size(), 0);
  for (const GraphEdge& edge : kept.edges) {
    if (edge.transition) is_bridge[static_cast<size_t>(edge.transition_index)] = edge.bridge;
  }
  std::vector<Transition> survivors, bridges;
  for (size_t t = 0; t < kept.transitions.size(); ++t) (is_bridge[t] ? bridges : survivors).push_back(kept.transitions[t]);
  std::vector<Transition> spaced = space_transitions(survivors, features.clip_of_frame, features.window, settings.spacing);
  spaced.insert(spaced.end(), bridges.begin(), bridges.end());
  std::sort(spaced.begin(), spaced.end(), [](const Transition& x, const Transition& y) {
    return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
  });
  const std::vector<char> spaced_bridges = transitions.bridge_flags(spaced);
  auto second = build_pruned_graph(db, spaced, features.window, settings.connected_tags, {}, spaced_bridges);
  if (!second) return second.error();
  second->survived_first_pruning = static_cast<int>(first->graph.transitions.size());
  return place_bridge_blends(db, spaced, spaced_bridges, transitions.selection.threshold, settings,
                             std::move(*second));
}

Result<PrunedGraph> place_bridge_blends(const MotionDatabase& db, std::span<const Transition> transitions,
                                        std::span<const char> bridges, double threshold,
                                        const GraphFromCandidatesSettings& settings, PrunedGraph pruned) {
  const MotionGraph& g = pruned.graph;
  if (std::none_of(g.edges.begin(), g.edges.end(), [](const GraphEdge& e) { return e.bridge; })) return pruned;
  // The frames of the clip pieces the pruned graph plays whose frames all carry the same tags: a
  // node moved onto one splits a piece the graph keeps into pieces of the same tags, so it is
  // reached and leads on as the piece did.
  const std::vector<TagMask> frame_tags = db.frame_tags();
  std::vector<char> kept(static_cast<size_t>(db.frame_count()), 0);
  for (const GraphEdge& e : g.edges) {
    if (e.transition) continue;
    const int first = g.nodes[e.from_node].frame;
    auto tags_at = [&](int f) {
      return frame_tags.begin() + std::min<size_t>(frame_tags.size(), static_cast<size_t>(f));
    };
    const auto tags_end = tags_at(first + e.frame_count);
    if (std::adjacent_find(tags_at(first), tags_end, std::not_equal_to<>()) != tags_end) continue;
    std::fill(kept.begin() + first, kept.begin() + first + e.frame_count, 1);
  }
  // Each bridge the pruning kept, placed; the others as they were (the pruning drops them again).
  std::vector<Transition> placed(transitions.begin(), transitions.end());
  std::vector<int> frames(placed.size(), g.window);
  std::vector<int> leads(placed.size(), 0);
  for (const int t : pruned.prune.kept_transitions) {
    const size_t i = static_cast<size_t>(t);
    if (i >= bridges.size() || bridges[i] == 0) continue;
    const BridgeBlend blend =
        bridge_blend(db, placed[i], g.window, threshold, settings.bridges.max_blend_factor, kept);
    leads[i] = placed[i].from_frame - blend.from_frame;
    placed[i].from_frame = blend.from_frame;
    placed[i].to_frame = blend.to_frame;
    frames[i] = blend.frames;
  }
  auto again = build_pruned_graph(db, placed, g.window, settings.connected_tags, frames, bridges);
  if (!again) return again.error();
  // The same transitions stay (the moved ends lie on kept pieces of unchanged tags); should
  // pruning take one, the bridges keep the window's blend, and the graph says so.
  if (again->prune.kept_transitions != pruned.prune.kept_transitions) {
    pruned.bridge_blends_placed = false;
    return pruned;
  }
  for (GraphEdge& e : again->graph.edges) {
    if (e.bridge) e.blend_lead = leads[static_cast<size_t>(again->prune.kept_transitions[e.transition_index])];
  }
  again->survived_first_pruning = pruned.survived_first_pruning;
  return again;
}

Result<GraphFromCandidates> graph_from_candidates(const MotionDatabase& db, const FrameFeatures& features,
                                                  const CandidateSearch& candidates,
                                                  const GraphFromCandidatesSettings& settings,
                                                  OnDemandCandidates* more) {
  auto transitions = select_transitions_with_bridges(db, features, candidates, settings, more);
  if (!transitions) return transitions.error();
  auto pruned = build_spaced_graph(db, *transitions, features, settings);
  if (!pruned) return pruned.error();
  return GraphFromCandidates{std::move(*transitions), std::move(*pruned)};
}

}  // namespace mg
