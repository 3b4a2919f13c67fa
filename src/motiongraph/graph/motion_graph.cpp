#include "motiongraph/core/json_text.h"
#include "motiongraph/graph/motion_graph.h"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/graph/scc.h"

namespace mg {

namespace {

Error graph_error(std::string message) { return Error{"", 0, std::move(message)}; }

// Targets of every edge position, so the graph can be handed to the SCC search as it is
// (its edges are already grouped by source node, edge_offsets being the CSR offsets).
std::vector<int> edge_targets(const MotionGraph& graph) {
  std::vector<int> targets(graph.edges.size());
  for (size_t e = 0; e < graph.edges.size(); ++e) targets[e] = graph.edges[e].to_node;
  return targets;
}

// One past the last frame an edge reads.
int edge_frame_end(const MotionGraph& graph, const GraphEdge& edge) {
  if (!edge.transition) return graph.nodes[edge.to_node].frame;
  const Transition& t = graph.transitions[edge.transition_index];
  return std::max(t.from_frame + blend_frames(edge), t.to_frame + 1);
}

TagMask tag_at(std::span<const TagMask> frame_tags, int frame) {
  return frame >= 0 && static_cast<size_t>(frame) < frame_tags.size() ? frame_tags[frame] : TagMask{0};
}

}  // namespace

int MotionGraph::node_at_frame(int frame) const {
  auto it = std::lower_bound(nodes.begin(), nodes.end(), frame,
                             [](const GraphNode& node, int f) { return node.frame < f; });
  return it != nodes.end() && it->frame == frame ? static_cast<int>(it - nodes.begin()) : -1;
}

Result<MotionGraph> build_motion_graph(const MotionDatabase& db, std::span<const Transition> transitions, int window,
                                       std::span<const int> blend_lengths, std::span<const char> bridges) {
  if (window < 2) {
    return graph_error(fmt::format("the window must be at least 2 frames (got {}): a transition plays its k-1 first "
                                   "blended frames, the last one being the frame it lands on",
                                   window));
  }
  int frame_count = 0;
  for (const DatabaseClip& clip : db.clips) {
    if (clip.frame_count < 1) return graph_error(fmt::format("clip '{}' has no frames", clip.name));
    if (clip.first_frame != frame_count) {
      return graph_error(fmt::format("clip '{}' starts at global frame {} instead of {}: clips must follow each other",
                                     clip.name, clip.first_frame, frame_count));
    }
    frame_count += clip.frame_count;
  }

  if (!blend_lengths.empty() && blend_lengths.size() != transitions.size()) {
    return graph_error(fmt::format("{} blend lengths for {} transitions", blend_lengths.size(), transitions.size()));
  }
  if (!bridges.empty() && bridges.size() != transitions.size()) {
    return graph_error(fmt::format("{} bridge flags for {} transitions", bridges.size(), transitions.size()));
  }
  auto blend_of = [&](size_t i) { return blend_lengths.empty() ? window : blend_lengths[i]; };
  for (size_t i = 0; i < transitions.size(); ++i) {
    const Transition& t = transitions[i];
    const int k = blend_of(i);
    if (k < window) {
      return graph_error(fmt::format("transition {} blends over {} frames, fewer than the window's {}", i, k, window));
    }
    if (t.from_frame < 0 || t.from_frame >= frame_count || t.to_frame < 0 || t.to_frame >= frame_count) {
      return graph_error(fmt::format("transition {} ({} -> {}) is outside the database's {} frames", i, t.from_frame,
                                     t.to_frame, frame_count));
    }
    const DatabaseClip& leave = db.clips[db.clip_of(t.from_frame)];
    if (t.from_frame + k > leave.first_frame + leave.frame_count) {
      return graph_error(fmt::format("transition {} leaves at frame {}, but its window {}..{} runs past the end of "
                                     "clip '{}' (last frame {})",
                                     i, t.from_frame, t.from_frame, t.from_frame + k - 1, leave.name,
                                     leave.first_frame + leave.frame_count - 1));
    }
    const DatabaseClip& arrive = db.clips[db.clip_of(t.to_frame)];
    if (t.to_frame - k + 1 < arrive.first_frame) {
      return graph_error(fmt::format("transition {} lands on frame {}, but its window {}..{} starts before clip '{}' "
                                     "(first frame {})",
                                     i, t.to_frame, t.to_frame - k + 1, t.to_frame, arrive.name, arrive.first_frame));
    }
  }

  MotionGraph graph;
  graph.window = window;
  graph.transitions.assign(transitions.begin(), transitions.end());

  std::vector<int> frames;
  frames.reserve(2 * db.clips.size() + 2 * transitions.size());
  for (const DatabaseClip& clip : db.clips) {
    frames.push_back(clip.first_frame);
    frames.push_back(clip.first_frame + clip.frame_count - 1);
  }
  for (const Transition& t : transitions) {
    frames.push_back(t.from_frame);
    frames.push_back(t.to_frame);
  }
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  graph.nodes.reserve(frames.size());
  int clip = 0;
  for (int f : frames) {
    while (f >= db.clips[clip].first_frame + db.clips[clip].frame_count) ++clip;
    graph.nodes.push_back({f, clip});
  }

  // Edges grouped by source node: count, then fill clip edges before transitions.
  const int n = graph.node_count();
  graph.edge_offsets.assign(static_cast<size_t>(n) + 1, 0);
  std::vector<int> transition_from(transitions.size()), transition_to(transitions.size());
  for (size_t i = 0; i < transitions.size(); ++i) {
    transition_from[i] = graph.node_at_frame(transitions[i].from_frame);
    transition_to[i] = graph.node_at_frame(transitions[i].to_frame);
    ++graph.edge_offsets[transition_from[i] + 1];
  }
  for (int v = 0; v + 1 < n; ++v) {
    if (graph.nodes[v].clip == graph.nodes[v + 1].clip) ++graph.edge_offsets[v + 1];
  }
  for (int v = 0; v < n; ++v) graph.edge_offsets[v + 1] += graph.edge_offsets[v];
  graph.edges.resize(static_cast<size_t>(graph.edge_offsets[n]));
  std::vector<int> next(graph.edge_offsets.begin(), graph.edge_offsets.end() - 1);
  for (int v = 0; v + 1 < n; ++v) {
    if (graph.nodes[v].clip != graph.nodes[v + 1].clip) continue;
    graph.edges[next[v]++] = {v, v + 1, false, -1, graph.nodes[v + 1].frame - graph.nodes[v].frame};
  }
  for (size_t i = 0; i < transitions.size(); ++i) {
    graph.edges[next[transition_from[i]]++] = {transition_from[i], transition_to[i], true, static_cast<int>(i),
                                                  blend_of(i) - 1, !bridges.empty() && bridges[i] != 0};
  }
  return graph;
}

TagMask edge_tags(const MotionGraph& graph, const GraphEdge& edge, std::span<const TagMask> frame_tags) {
  if (frame_tags.empty()) return 0;
  TagMask mask = ~TagMask{0};
  if (!edge.transition) {
    const int f1 = graph.nodes[edge.from_node].frame;
    const int f2 = graph.nodes[edge.to_node].frame;
    for (int f = f1; f < f2 && mask != 0; ++f) mask &= tag_at(frame_tags, f);
    return mask;
  }
  const Transition& t = graph.transitions[edge.transition_index];
  const int k = blend_frames(edge);
  for (int p = 0; p < k && mask != 0; ++p) {
    mask &= tag_at(frame_tags, t.from_frame + p) & tag_at(frame_tags, t.to_frame - k + 1 + p);
  }
  return mask;
}

Status PruneSettings::validate() const { return Ok{}; }

GraphStatistics compute_graph_statistics(const MotionGraph& graph, std::span<const TagMask> frame_tags) {
  GraphStatistics s;
  s.nodes = graph.node_count();
  s.edges = graph.edge_count();
  for (const GraphEdge& e : graph.edges) {
    if (e.transition) {
      ++s.transitions;
      s.bridges += e.bridge ? 1 : 0;
    } else {
      ++s.clip_edges;
      s.clip_frames += e.frame_count;
    }
  }
  const std::vector<int> targets = edge_targets(graph);
  const DigraphView view{graph.edge_offsets, targets};
  if (s.nodes > 0) {
    const Components all = strongly_connected_components(view);
    s.components = all.count();
    const int largest = largest_component(all);
    s.largest_component_nodes = largest < 0 ? 0 : all.node_counts[largest];
  }

  TagMask present = 0;
  for (TagMask m : frame_tags) present |= m;
  if (present == 0) return s;
  std::vector<TagMask> tags_of_edge(graph.edges.size());
  for (size_t e = 0; e < graph.edges.size(); ++e) tags_of_edge[e] = edge_tags(graph, graph.edges[e], frame_tags);
  std::vector<char> in_tag(graph.edges.size());
  std::vector<char> node_touched(graph.nodes.size());
  for (int t = 0; t < 64; ++t) {
    const TagMask bit = TagMask{1} << t;
    if ((present & bit) == 0) continue;
    TagStatistics ts;
    ts.tag = t;
    for (TagMask m : frame_tags) ts.database_frames += (m & bit) != 0;
    std::fill(node_touched.begin(), node_touched.end(), 0);
    for (size_t e = 0; e < graph.edges.size(); ++e) {
      const GraphEdge& edge = graph.edges[e];
      in_tag[e] = (tags_of_edge[e] & bit) != 0;
      if (in_tag[e]) {
        ++ts.edges;
        node_touched[edge.from_node] = node_touched[edge.to_node] = 1;
      }
      if (!edge.transition) {
        for (int f = graph.nodes[edge.from_node].frame; f < graph.nodes[edge.to_node].frame; ++f) {
          ts.frames += (tag_at(frame_tags, f) & bit) != 0;
        }
      }
    }
    ts.nodes = static_cast<int>(std::count(node_touched.begin(), node_touched.end(), 1));
    if (ts.edges > 0) {
      const Components c = strongly_connected_components(view, {{}, in_tag});
      const int largest = largest_component(c);
      ts.largest_component_nodes = largest < 0 ? 0 : c.node_counts[largest];
    }
    s.tags.push_back(ts);
  }
  return s;
}

Result<PruneReport> prune_motion_graph(MotionGraph& graph, std::span<const TagMask> frame_tags,
                                       const PruneSettings& settings) {
  if (auto status = settings.validate(); !status) return status.error();
  if (!frame_tags.empty()) {
    int frames_read = 0;
    for (const GraphEdge& e : graph.edges) frames_read = std::max(frames_read, edge_frame_end(graph, e));
    if (static_cast<int>(frame_tags.size()) < frames_read) {
      return graph_error(fmt::format("the frame tags cover {} frames but the graph reads frames up to {}: are they "
                                     "from the same database?",
                                     frame_tags.size(), frames_read - 1));
    }
  }

  PruneReport report;
  report.before = compute_graph_statistics(graph, frame_tags);

  const int n = graph.node_count();
  const int m = graph.edge_count();
  const std::vector<int> targets = edge_targets(graph);
  const DigraphView view{graph.edge_offsets, targets};
  std::vector<TagMask> tags_of_edge(m);
  TagMask tags_used = 0;
  for (int e = 0; e < m; ++e) {
    tags_of_edge[e] = edge_tags(graph, graph.edges[e], frame_tags) & settings.connected_tags;
    tags_used |= tags_of_edge[e];
  }

  std::vector<char> node_alive(n, 1), edge_alive(m, 1), tag_edge_alive(m, 0);
  while (true) {
    ++report.passes;
    bool removed = false;
    // 1. The whole graph: keep its largest strongly connected component.
    const Components all = strongly_connected_components(view, {node_alive, edge_alive});
    const int largest = largest_component(all);
    for (int v = 0; v < n; ++v) {
      if (node_alive[v] && all.component_of_node[v] != largest) {
        node_alive[v] = 0;
        removed = true;
      }
    }
    for (int e = 0; e < m; ++e) {
      if (edge_alive[e] && (!node_alive[graph.edges[e].from_node] || !node_alive[graph.edges[e].to_node])) {
        edge_alive[e] = 0;
        removed = true;
      }
    }
    if (largest < 0) break;  // nothing left
    // 2. Each tag: keep the tag's edges inside the largest component of the tag's subgraph.
    for (int t = 0; t < 64; ++t) {
      const TagMask bit = TagMask{1} << t;
      if ((tags_used & bit) == 0) continue;
      bool any = false;
      for (int e = 0; e < m; ++e) {
        tag_edge_alive[e] = edge_alive[e] && (tags_of_edge[e] & bit) != 0;
        any = any || tag_edge_alive[e];
      }
      if (!any) continue;
      const Components c = strongly_connected_components(view, {node_alive, tag_edge_alive});
      const int tag_largest = largest_component(c);
      for (int e = 0; e < m; ++e) {
        if (!tag_edge_alive[e]) continue;
        const GraphEdge& edge = graph.edges[e];
        if (tag_largest < 0 || c.component_of_node[edge.from_node] != tag_largest ||
            c.component_of_node[edge.to_node] != tag_largest) {
          edge_alive[e] = 0;
          removed = true;
        }
      }
    }
    if (!removed) break;
  }

  if (std::find(node_alive.begin(), node_alive.end(), 1) == node_alive.end()) {
    return Error{"", 0,
                 "pruning left nothing: the transitions form no cycle (with the tags' rule applied); a higher "
                 "transition threshold gives more transitions",
                 ErrorKind::kEmptyGraph};
  }

  // Compact: kept items in their previous order, indices remapped.
  std::vector<int> new_node(n, -1);
  for (int v = 0; v < n; ++v) {
    if (!node_alive[v]) continue;
    new_node[v] = static_cast<int>(report.kept_nodes.size());
    report.kept_nodes.push_back(v);
  }
  std::vector<char> transition_alive(graph.transitions.size(), 0);
  for (int e = 0; e < m; ++e) {
    if (edge_alive[e] && graph.edges[e].transition) transition_alive[graph.edges[e].transition_index] = 1;
  }
  std::vector<int> new_transition(graph.transitions.size(), -1);
  for (size_t t = 0; t < graph.transitions.size(); ++t) {
    if (!transition_alive[t]) continue;
    new_transition[t] = static_cast<int>(report.kept_transitions.size());
    report.kept_transitions.push_back(static_cast<int>(t));
  }

  MotionGraph pruned;
  pruned.window = graph.window;
  for (int v : report.kept_nodes) pruned.nodes.push_back(graph.nodes[v]);
  for (int t : report.kept_transitions) pruned.transitions.push_back(graph.transitions[t]);
  pruned.edge_offsets.assign(pruned.nodes.size() + 1, 0);
  for (int e = 0; e < m; ++e) {
    if (!edge_alive[e]) continue;
    GraphEdge edge = graph.edges[e];
    edge.from_node = new_node[edge.from_node];
    edge.to_node = new_node[edge.to_node];
    if (edge.transition) edge.transition_index = new_transition[edge.transition_index];
    pruned.edges.push_back(edge);
    ++pruned.edge_offsets[edge.from_node + 1];
    report.kept_edges.push_back(e);
  }
  for (size_t v = 0; v < pruned.nodes.size(); ++v) pruned.edge_offsets[v + 1] += pruned.edge_offsets[v];
  graph = std::move(pruned);
  report.after = compute_graph_statistics(graph, frame_tags);
  return report;
}

std::string to_json(const GraphStatistics& statistics, std::span<const std::string> tag_names) {
  using nlohmann::json;
  json tags = json::array();
  for (const TagStatistics& t : statistics.tags) {
    json entry = {{"tag", t.tag},
                  {"database_frames", t.database_frames},
                  {"frames", t.frames},
                  {"nodes", t.nodes},
                  {"edges", t.edges},
                  {"largest_component_nodes", t.largest_component_nodes}};
    if (t.tag >= 0 && static_cast<size_t>(t.tag) < tag_names.size()) {
      entry["name"] = tag_names[t.tag];
      // A modifier (turn, stop, ...) rides on the motion types' regions: no SCC of its own.
      entry["modifier"] = is_modifier_tag(tag_names[t.tag]);
    }
    tags.push_back(std::move(entry));
  }
  json out = {{"nodes", statistics.nodes},
              {"edges", statistics.edges},
              {"clip_edges", statistics.clip_edges},
              {"transitions", statistics.transitions},
              {"bridges", statistics.bridges},
              {"clip_frames", statistics.clip_frames},
              {"components", statistics.components},
              {"largest_component_nodes", statistics.largest_component_nodes},
              {"tags", std::move(tags)}};
  return json_text(out, 2);
}

}  // namespace mg
