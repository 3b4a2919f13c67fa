#include "motiongraph/graph/scc.h"

#include <algorithm>
#include <cassert>

namespace mg {

CompressedDigraph compress_edges(int node_count, std::span<const std::pair<int, int>> edges) {
  assert(node_count >= 0);
  CompressedDigraph g;
  g.offsets.assign(static_cast<size_t>(node_count) + 1, 0);
  for (const auto& [from, to] : edges) {
    assert(from >= 0 && from < node_count && to >= 0 && to < node_count);
    (void)to;
    ++g.offsets[static_cast<size_t>(from) + 1];
  }
  for (int v = 0; v < node_count; ++v) g.offsets[v + 1] += g.offsets[v];
  g.targets.resize(edges.size());
  g.edge_ids.resize(edges.size());
  std::vector<int> next(g.offsets.begin(), g.offsets.end() - 1);
  for (size_t i = 0; i < edges.size(); ++i) {
    const int pos = next[edges[i].first]++;
    g.targets[pos] = edges[i].second;
    g.edge_ids[pos] = static_cast<int>(i);
  }
  return g;
}

Components strongly_connected_components(const DigraphView& graph, const SccFilter& filter) {
  const int n = graph.node_count();
  assert(filter.node_alive.empty() || static_cast<int>(filter.node_alive.size()) == n);
  assert(filter.edge_alive.empty() || static_cast<int>(filter.edge_alive.size()) == graph.edge_count());
  assert(n == 0 || (graph.offsets[0] == 0 && graph.offsets[n] == graph.edge_count()));
  auto node_alive = [&](int v) { return filter.node_alive.empty() || filter.node_alive[v] != 0; };
  auto edge_alive = [&](int e) { return filter.edge_alive.empty() || filter.edge_alive[e] != 0; };

  Components c;
  c.component_of_node.assign(n, -1);
  // order[v]: discovery index, -1 while unvisited. A visited node whose component is still -1
  // is on Tarjan's stack.
  std::vector<int> order(n, -1);
  std::vector<int> low(n, 0);
  std::vector<int> tarjan_stack;
  struct Frame {
    int node;
    int next_edge;  // next edge position of `node` to look at
  };
  std::vector<Frame> call_stack;
  int counter = 0;

  auto visit = [&](int v) {
    order[v] = low[v] = counter++;
    tarjan_stack.push_back(v);
    call_stack.push_back({v, graph.offsets[v]});
  };

  for (int root = 0; root < n; ++root) {
    if (!node_alive(root) || order[root] != -1) continue;
    visit(root);
    while (!call_stack.empty()) {
      const int v = call_stack.back().node;
      const int e = call_stack.back().next_edge;
      if (e < graph.offsets[v + 1]) {
        ++call_stack.back().next_edge;
        if (!edge_alive(e)) continue;
        const int w = graph.targets[e];
        assert(w >= 0 && w < n);
        if (!node_alive(w)) continue;
        if (order[w] == -1) {
          visit(w);  // "recurse"; low[v] is updated from low[w] when w returns
        } else if (c.component_of_node[w] == -1) {
          low[v] = std::min(low[v], order[w]);  // w is on the stack: a back or cross edge in the tree
        }
        continue;
      }
      // All edges of v done: v is a root of a component when nothing below reached higher.
      if (low[v] == order[v]) {
        const int id = c.count();
        int size = 0;
        int first = v;
        int w = -1;
        do {
          w = tarjan_stack.back();
          tarjan_stack.pop_back();
          c.component_of_node[w] = id;
          first = std::min(first, w);
          ++size;
        } while (w != v);
        c.node_counts.push_back(size);
        c.first_node.push_back(first);
      }
      call_stack.pop_back();
      if (!call_stack.empty()) {
        const int parent = call_stack.back().node;
        low[parent] = std::min(low[parent], low[v]);
      }
    }
  }

  c.edge_counts.assign(c.node_counts.size(), 0);
  for (int v = 0; v < n; ++v) {
    const int cv = c.component_of_node[v];
    if (cv < 0) continue;
    for (int e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
      if (edge_alive(e) && c.component_of_node[graph.targets[e]] == cv) ++c.edge_counts[cv];
    }
  }
  return c;
}

int largest_component(const Components& components) {
  int best = -1;
  for (int id = 0; id < components.count(); ++id) {
    if (components.trivial(id)) continue;
    if (best < 0 || components.node_counts[id] > components.node_counts[best] ||
        (components.node_counts[id] == components.node_counts[best] &&
         components.first_node[id] < components.first_node[best])) {
      best = id;
    }
  }
  return best;
}

}  // namespace mg
