#include "motiongraph/graph/transition_selection.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "motiongraph/metric/pair_alignment.h"

namespace mg {

Status TransitionSettings::validate() const {
  if (threshold < 0.0 && !(threshold_quantile > 0.0 && threshold_quantile <= 1.0)) {
    return Error{"", 0, "threshold quantile must be in (0, 1]"};
  }
  if (!std::isfinite(threshold)) return Error{"", 0, "threshold must be a finite number"};
  if (locality_radius < -1) return Error{"", 0, "locality radius must be >= 0 (or -1 for half the window)"};
  return Ok{};
}

Result<TransitionSelection> select_transitions(const FrameFeatures& features, const CandidateSearch& candidates,
                                               const TransitionSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  TransitionSelection selection;
  if (settings.threshold >= 0.0) {
    selection.threshold = settings.threshold;
  } else {
    selection.threshold = candidates.histogram.quantile(settings.threshold_quantile);
  }
  selection.threshold_quantile = candidates.histogram.fraction_below(selection.threshold);
  selection.locality_radius = settings.locality_radius < 0 ? features.window / 2 : settings.locality_radius;

  std::vector<Transition> below;
  for (const Transition& t : candidates.minima) {
    if (t.distance <= selection.threshold) below.push_back(t);
  }
  selection.candidates_below_threshold = static_cast<int>(below.size());
  // Best first; a candidate is kept unless a kept one lies within the radius in a and in b.
  std::stable_sort(below.begin(), below.end(), [](const Transition& x, const Transition& y) { return x.distance < y.distance; });
  const int r = selection.locality_radius;
  const long long cell = std::max(1, r);
  std::unordered_map<long long, std::vector<int>> grid;  // cell -> kept indices
  auto key = [&](long long ca, long long cb) { return ca * 1000003LL + cb; };
  for (const Transition& t : below) {
    const long long ca = t.from_frame / cell, cb = t.to_frame / cell;
    bool near = false;
    for (long long da = -1; da <= 1 && !near; ++da) {
      for (long long db = -1; db <= 1 && !near; ++db) {
        auto it = grid.find(key(ca + da, cb + db));
        if (it == grid.end()) continue;
        for (int kept : it->second) {
          const Transition& other = selection.transitions[kept];
          if (std::abs(other.from_frame - t.from_frame) <= r && std::abs(other.to_frame - t.to_frame) <= r) {
            near = true;
            break;
          }
        }
      }
    }
    if (near) continue;
    grid[key(ca, cb)].push_back(static_cast<int>(selection.transitions.size()));
    selection.transitions.push_back(t);
  }
  for (Transition& t : selection.transitions) {
    const FloorAlignment align = align_pair(features, t.from_frame, t.to_frame);
    t.yaw_rad = static_cast<float>(align.yaw_rad);
    t.x_m = static_cast<float>(align.x_m);
    t.z_m = static_cast<float>(align.z_m);
  }
  std::sort(selection.transitions.begin(), selection.transitions.end(), [](const Transition& x, const Transition& y) {
    return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
  });
  return selection;
}

}  // namespace mg
