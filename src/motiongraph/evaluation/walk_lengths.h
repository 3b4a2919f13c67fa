// Walk lengths per cost function (the seed's figure 3.3): the same random (start, goal) node
// pairs, drawn from a seed, searched with each cost of walk_search.h; each walk's frames,
// edges, transitions and cost. A search that runs out of budget is reported, not an error.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "motiongraph/synthesis/walk_search.h"

namespace mg {

struct WalkLengthSettings {
  int walks = 100;                    // per cost function
  std::uint64_t seed = 1;             // node pairs; walk i's random costs use seed + i
  long long max_expansions = 2000000; // per search

  Status validate() const;
};

struct WalkLengthSample {
  WalkCost cost = WalkCost::kConstant;
  int index = 0;          // 0..walks-1: the same index has the same nodes for every cost
  int from = 0;
  int to = 0;
  bool found = false;
  std::string failure;    // why not, when not found
  Walk walk;
  long long frames = 0;   // frames played (walk.frame_count)
  int transitions = 0;
  double cost_value = 0.0;
  long long expansions = 0;
};

// Fails when the graph has fewer than two nodes or the settings are invalid.
Result<std::vector<WalkLengthSample>> sample_walk_lengths(const MotionGraph& graph, std::span<const WalkCost> costs,
                                                          const WalkLengthSettings& settings);

}  // namespace mg
