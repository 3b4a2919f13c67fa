#include "motiongraph/graph/transition_selection.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "motiongraph/core/json_text.h"
#include "motiongraph/graph/window_membership.h"
#include "motiongraph/metric/pair_alignment.h"

namespace mg {

Status TransitionSettings::validate() const {
  if (threshold < 0.0 && !(threshold_quantile > 0.0 && threshold_quantile <= 1.0)) {
    return Error{"", 0, "threshold quantile must be in (0, 1]"};
  }
  if (!std::isfinite(threshold)) return Error{"", 0, "threshold must be a finite number"};
  if (locality_radius < -1) return Error{"", 0, "locality radius must be >= 0 (or -1 for half the window)"};
  if (!std::isfinite(max_threshold)) return Error{"", 0, "the maximum threshold must be a finite number"};
  for (const OwnThreshold& own : tag_thresholds) {
    if (own.tag < -1 || own.tag >= 64) return Error{"", 0, fmt::format("tag threshold for tag bit {}", own.tag)};
    if (!(std::isfinite(own.threshold) && own.threshold >= 0.0)) {
      return Error{"", 0, "a tag's own threshold must be a finite distance >= 0"};
    }
  }
  return Ok{};
}

namespace {

// Per tag of `tags` (and -1: the candidates whose 2k frames carry none of them) its own
// threshold: the one `given` lists, or else the D at the rank where the tag keeps the share
// `share` of its candidates. Never below `global`. Given for some, the others keep the global
// one; tag -1 only when given.
std::vector<TagThreshold> tag_thresholds(const CandidateSearch& candidates, const WindowMembership& windows,
                                         TagMask tags, double global, double share,
                                         std::span<const OwnThreshold> given) {
  std::vector<TagThreshold> result;
  for (int t = -1; t < 64; ++t) {
    if (t >= 0 && (tags >> t & 1) == 0) continue;
    const auto own = std::find_if(given.begin(), given.end(), [t](const OwnThreshold& g) { return g.tag == t; });
    if ((!given.empty() || t < 0) && own == given.end()) continue;
    if (own != given.end()) {
      const auto members = std::count_if(candidates.minima.begin(), candidates.minima.end(),
                                         [&](const Transition& c) { return windows.belongs(c, t); });
      result.push_back({t, static_cast<int>(members), std::max(own->threshold, global), true});
      continue;
    }
    std::vector<float> d;
    for (const Transition& c : candidates.minima) {
      if (windows.belongs(c, t)) d.push_back(c.distance);
    }
    if (d.empty()) continue;
    std::sort(d.begin(), d.end());
    const size_t keep = static_cast<size_t>(std::ceil(share * static_cast<double>(d.size())));
    const double ranked = keep == 0 ? 0.0 : d[std::min(keep, d.size()) - 1];
    result.push_back({t, static_cast<int>(d.size()), std::max(ranked, global), false});
  }
  return result;
}

}  // namespace

Result<TransitionSelection> select_transitions(const FrameFeatures& features, const CandidateSearch& candidates,
                                               const TransitionSettings& settings, std::span<const TagMask> frame_tags,
                                               TagMask tags, bool aligned, std::span<const char> untagged_class) {
  if (auto s = settings.validate(); !s) return s.error();
  TransitionSelection selection;
  if (settings.threshold >= 0.0) {
    selection.threshold = settings.threshold;
  } else {
    selection.threshold = candidates.histogram.quantile(settings.threshold_quantile);
  }
  // The pruned stage's candidates are all known up to its ceiling only; per-tag thresholds by
  // rank count every candidate of a tag, above any ceiling too.
  const double ceiling = candidates.ceiling;
  auto above_ceiling = [&](double threshold) {
    return Error{"", 0,
                 fmt::format("the threshold (D {:.6g}) lies above the pruned distance stage's ceiling (D {:.6g}); "
                             "the exhaustive stage knows every distance",
                             threshold, ceiling)};
  };
  if (ceiling >= 0.0 && !(selection.threshold <= ceiling)) return above_ceiling(selection.threshold);
  const bool tag_thresholds_on = settings.per_tag_thresholds && !frame_tags.empty() && tags != 0;
  const bool ranked = settings.tag_thresholds.empty();
  if (ceiling >= 0.0 && tag_thresholds_on && ranked) {
    return Error{"", 0, "per-tag thresholds by rank need the exhaustive distance stage's candidates (they count a "
                        "tag's candidates above any ceiling)"};
  }
  selection.threshold_quantile = candidates.histogram.fraction_below(selection.threshold);
  selection.locality_radius = settings.locality_radius < 0 ? features.window / 2 : settings.locality_radius;

  WindowMembership windows;
  if (tag_thresholds_on && (!candidates.minima.empty() || !ranked)) {
    const auto global_count = std::count_if(candidates.minima.begin(), candidates.minima.end(),
                                            [&](const Transition& t) { return t.distance <= selection.threshold; });
    const double share = candidates.minima.empty()
                             ? 0.0
                             : static_cast<double>(global_count) / static_cast<double>(candidates.minima.size());
    windows = window_membership(frame_tags, tags, features.window, untagged_class);
    selection.tag_thresholds =
        tag_thresholds(candidates, windows, tags, selection.threshold, share, settings.tag_thresholds);
    if (settings.max_threshold >= 0.0) {
      for (TagThreshold& own : selection.tag_thresholds) {
        own.threshold = std::min(own.threshold, settings.max_threshold);
      }
    }
    for (const TagThreshold& own : selection.tag_thresholds) {
      if (ceiling >= 0.0 && !(own.threshold <= ceiling)) return above_ceiling(own.threshold);
    }
  }
  std::vector<Transition> below;
  for (const Transition& t : candidates.minima) {
    bool keep = t.distance <= selection.threshold;
    for (const TagThreshold& own : selection.tag_thresholds) {
      if (!keep && t.distance <= own.threshold && windows.belongs(t, own.tag)) keep = true;
    }
    if (keep) below.push_back(t);
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
  for (Transition& t : aligned ? std::span<Transition>(selection.transitions) : std::span<Transition>{}) {
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

void to_json(nlohmann::json& json, const TransitionSettings& settings) {
  json = {{"threshold", settings.threshold},
          {"threshold_quantile", settings.threshold_quantile},
          {"max_threshold", cap_json(settings.max_threshold)},
          {"locality_radius", settings.locality_radius},
          {"per_tag_thresholds", settings.per_tag_thresholds}};
  if (!settings.tag_thresholds.empty()) {
    nlohmann::json own = nlohmann::json::array();
    for (const OwnThreshold& t : settings.tag_thresholds) own.push_back({{"tag", t.tag}, {"threshold", t.threshold}});
    json["tag_thresholds"] = own;
  }
}

void from_json(const nlohmann::json& json, TransitionSettings& settings) {
  const TransitionSettings defaults;
  settings.threshold = json.at("threshold").get<double>();
  settings.threshold_quantile = json.at("threshold_quantile").get<double>();
  settings.locality_radius = json.at("locality_radius").get<int>();
  settings.per_tag_thresholds = json.value("per_tag_thresholds", defaults.per_tag_thresholds);
  settings.max_threshold = cap_from_json(json, "max_threshold");
  settings.tag_thresholds.clear();
  if (json.contains("tag_thresholds")) {
    for (const nlohmann::json& t : json.at("tag_thresholds")) {
      settings.tag_thresholds.push_back({t.at("tag").get<int>(), t.at("threshold").get<double>()});
    }
  }
}

}  // namespace mg
