#include "motiongraph/synthesis/travelling_type.h"

#include <algorithm>
#include <array>
#include <bit>

#include "motiongraph/graph/graph_from_candidates.h"

namespace mg {

TagMask travelling_type(const SynthesisContext& context) {
  const MotionGraph& graph = *context.graph;
  const TagMask types = motion_type_tags(*context.db);
  std::array<double, 64> metres{};
  std::array<long long, 64> frames{};
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (graph.edges[e].transition) continue;
    const auto roots = context.tracks.roots_of(static_cast<int>(e));
    if (roots.size() < 2) continue;
    const double metres_here = (roots.back() - roots.front()).norm();
    for (TagMask m = context.tracks.tags_of(static_cast<int>(e)).front() & types; m != 0; m &= m - 1) {
      const auto t = static_cast<size_t>(std::countr_zero(m));
      metres[t] += metres_here;
      frames[t] += static_cast<long long>(roots.size()) - 1;
    }
  }
  const double fps = context.db->fps > 0.0 ? context.db->fps : 30.0;
  int best = -1;
  double best_weight = 0.0;
  for (size_t t = 0; t < frames.size(); ++t) {
    if (frames[t] == 0) continue;
    const double speed = metres[t] * fps / static_cast<double>(frames[t]);
    if (speed < kTravellingMps) continue;
    const double pace = std::min(1.0, speed / kWalkingMps);
    const double weight = static_cast<double>(frames[t]) * pace * pace;
    if (best < 0 || weight > best_weight) best = static_cast<int>(t), best_weight = weight;
  }
  return best < 0 ? TagMask{0} : TagMask{1} << best;
}

}  // namespace mg
