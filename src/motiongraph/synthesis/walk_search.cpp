#include "motiongraph/synthesis/walk_search.h"

#include <algorithm>
#include <queue>
#include <random>

#include <fmt/format.h>

#include "motiongraph/core/stop.h"
#include "motiongraph/core/text.h"

namespace mg {

Result<WalkCost> parse_walk_cost(std::string_view name) {
  if (name == "constant") return WalkCost::kConstant;
  if (name == "quality") return WalkCost::kQuality;
  if (name == "random") return WalkCost::kRandom;
  if (name == "hybrid") return WalkCost::kHybrid;
  // (quoted: at most 40 characters, control bytes escaped; a studio request could hold a megabyte)
  return Error{"", 0, fmt::format("unknown cost {}: constant, quality, random or hybrid", quoted(name))};
}

const char* walk_cost_name(WalkCost cost) {
  switch (cost) {
    case WalkCost::kConstant: return "constant";
    case WalkCost::kQuality: return "quality";
    case WalkCost::kRandom: return "random";
    case WalkCost::kHybrid: return "hybrid";
  }
  return "?";
}

Status WalkSearchSettings::validate() const {
  if (min_frames < 0 || min_frames > 10'000'000) return Error{"", 0, "--min-frames must be from 0 to 10000000"};
  if (max_expansions < 1) return Error{"", 0, "the expansion budget must be >= 1"};
  return Ok{};
}

std::vector<double> walk_edge_costs(const MotionGraph& graph, const WalkSearchSettings& settings) {
  std::mt19937_64 rng(settings.seed);
  // (0, 1]: 1 - [0, 1).
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> costs;
  costs.reserve(graph.edges.size());
  for (const GraphEdge& edge : graph.edges) {
    const double quality = edge.transition ? graph.transitions[edge.transition_index].distance : 0.0;
    switch (settings.cost) {
      case WalkCost::kConstant: costs.push_back(1.0); break;
      case WalkCost::kQuality: costs.push_back(quality); break;
      case WalkCost::kRandom: costs.push_back(1.0 - uniform(rng)); break;
      case WalkCost::kHybrid: costs.push_back((1.0 - uniform(rng)) * quality); break;
    }
  }
  return costs;
}

Result<WalkSearchResult> find_walk(const MotionGraph& graph, int from, int to, const WalkSearchSettings& settings) {
  if (auto status = settings.validate(); !status) return status.error();
  for (int node : {from, to}) {
    if (node < 0 || node >= graph.node_count()) {
      return Error{"", 0, fmt::format("node {} does not exist (the graph has nodes 0..{})", node, graph.node_count() - 1)};
    }
  }
  const std::vector<double> costs = walk_edge_costs(graph, settings);
  const int levels = settings.min_frames + 1;
  auto state_of = [&](int node, int frames) { return static_cast<size_t>(node) * levels + std::min(frames, settings.min_frames); };
  // Partial walks as a tree of (parent, edge) entries; the queue holds (cost, entry).
  struct Entry {
    int parent = -1;
    int edge = -1;
    int node = 0;
    int frames = 0;
  };
  std::vector<Entry> entries{{-1, -1, from, 0}};
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  queue.emplace(0.0, 0);
  std::vector<bool> extended(static_cast<size_t>(graph.node_count()) * levels, false);
  WalkSearchResult result;
  while (!queue.empty()) {
    const auto [cost, index] = queue.top();
    queue.pop();
    const Entry entry = entries[index];
    if (entry.node == to && entry.frames >= settings.min_frames) {
      result.cost = cost;
      result.walk.start_node = from;
      for (int i = index; entries[i].parent >= 0; i = entries[i].parent) result.walk.edges.push_back(entries[i].edge);
      std::reverse(result.walk.edges.begin(), result.walk.edges.end());
      return result;
    }
    const size_t state = state_of(entry.node, entry.frames);
    if (extended[state]) continue;
    extended[state] = true;
    // (A stop is looked for every kStopCheckExpansions: an expansion takes well under a microsecond.)
    constexpr long long kStopCheckExpansions = 1 << 14;
    if (result.expansions % kStopCheckExpansions == 0) {
      if (auto s = check_stop(settings.stop); !s) return s.error();
    }
    if (++result.expansions > settings.max_expansions) {
      return Error{"", 0, fmt::format("the search budget of {} expansions ran out before reaching node {}; {}",
                                      settings.max_expansions, to, settings.budget_advice)};
    }
    for (int e = graph.edge_offsets[entry.node]; e < graph.edge_offsets[entry.node + 1]; ++e) {
      const GraphEdge& edge = graph.edges[e];
      const int frames = std::min(entry.frames + edge.frame_count, settings.min_frames);
      if (extended[state_of(edge.to_node, frames)]) continue;
      entries.push_back({index, e, edge.to_node, frames});
      queue.emplace(cost + costs[e], static_cast<int>(entries.size()) - 1);
    }
  }
  return Error{"", 0, fmt::format("no walk from node {} reaches node {}", from, to)};
}

}  // namespace mg
