// Walk lengths per cost function.
#include "motiongraph/evaluation/walk_lengths.h"

#include <random>

namespace mg {

Status WalkLengthSettings::validate() const {
  if (walks < 1) return Error{"", 0, "walks must be at least 1"};
  if (max_expansions < 1) return Error{"", 0, "the search budget must be at least 1"};
  return Ok{};
}

Result<std::vector<WalkLengthSample>> sample_walk_lengths(const MotionGraph& graph, std::span<const WalkCost> costs,
                                                          const WalkLengthSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  if (graph.node_count() < 2) return Error{"", 0, "walk lengths need a graph of at least two nodes"};
  std::mt19937_64 random(settings.seed);
  std::uniform_int_distribution<int> node(0, graph.node_count() - 1);
  std::vector<std::pair<int, int>> pairs;
  while (static_cast<int>(pairs.size()) < settings.walks) {
    const int from = node(random), to = node(random);
    if (from != to) pairs.emplace_back(from, to);
  }
  std::vector<WalkLengthSample> samples;
  for (const WalkCost cost : costs) {
    for (int i = 0; i < settings.walks; ++i) {
      WalkLengthSample sample;
      sample.cost = cost;
      sample.index = i;
      sample.from = pairs[i].first;
      sample.to = pairs[i].second;
      WalkSearchSettings search;
      search.cost = cost;
      search.seed = settings.seed + static_cast<std::uint64_t>(i);
      search.max_expansions = settings.max_expansions;
      auto found = find_walk(graph, sample.from, sample.to, search);
      if (found) {
        sample.found = true;
        sample.walk = found->walk;
        sample.frames = found->walk.frame_count(graph);
        for (int e : found->walk.edges) sample.transitions += graph.edges[e].transition ? 1 : 0;
        sample.cost_value = found->cost;
        sample.expansions = found->expansions;
      } else {
        sample.failure = found.error().message;
      }
      samples.push_back(std::move(sample));
    }
  }
  return samples;
}

}  // namespace mg
