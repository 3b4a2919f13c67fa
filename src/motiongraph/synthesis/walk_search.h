// Walks between two nodes by branch and bound with an extended list (the seed's section 2.6):
// partial walks are extended cheapest first, and a (node, frames played) state already
// extended is never extended again, which with non-negative edge costs makes the first walk
// that reaches the goal a cheapest one. Frames played are counted up to min_frames only, so
// the states are node x (min_frames + 1). Edge costs (the seed's section 3.2):
//   constant  1 per edge
//   quality   a transition's distance D; 0 for clip pieces (playing the data as captured)
//   random    uniform in (0, 1] per edge, from the seed
//   hybrid    random x quality
#pragma once

#include <cstdint>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/synthesis/walk.h"

namespace mg {

enum class WalkCost { kConstant, kQuality, kRandom, kHybrid };

Result<WalkCost> parse_walk_cost(std::string_view name);
const char* walk_cost_name(WalkCost cost);

struct WalkSearchSettings {
  WalkCost cost = WalkCost::kQuality;
  std::uint64_t seed = 1;
  int min_frames = 0;                   // the walk plays at least this many frames
  long long max_expansions = 2000000;   // partial walks extended
  // What the error says to do when the budget runs out, in the words of the caller's options.
  std::string budget_advice = "raise --max-expansions or lower --min-frames";
  // Asks the search to stop (core/stop.h): find_walk fails with stopped_error() soon after.
  std::stop_token stop;

  Status validate() const;
};

// One cost per edge of the graph.
std::vector<double> walk_edge_costs(const MotionGraph& graph, const WalkSearchSettings& settings);

struct WalkSearchResult {
  Walk walk;
  double cost = 0.0;
  long long expansions = 0;
};

// The cheapest walk from node `from` to node `to` playing at least min_frames frames; an error
// when the budget runs out first (or no walk exists).
Result<WalkSearchResult> find_walk(const MotionGraph& graph, int from, int to, const WalkSearchSettings& settings);

}  // namespace mg
