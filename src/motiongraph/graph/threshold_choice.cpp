// The transition threshold chosen from the data: lowest threshold reaching a coverage target.
#include "motiongraph/graph/threshold_choice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "motiongraph/core/stop.h"
#include "motiongraph/core/transition_rate.h"

namespace mg {

double rms_cm_of_distance(double distance, double window_weight) {
  if (!(window_weight > 0.0) || !(distance > 0.0)) return 0.0;
  return 100.0 * std::sqrt(distance / window_weight);
}

double rms_cm_of_distance(double distance, const FrameFeatures& features) {
  return rms_cm_of_distance(distance, features.window_weight);
}

double distance_of_rms_cm(double rms_cm, const FrameFeatures& features) {
  const double rms_m = rms_cm / 100.0;
  return features.window_weight * rms_m * rms_m;
}

Status ThresholdChoiceSettings::validate() const {
  if (!(coverage > 0.0 && coverage <= 1.0)) return Error{"", 0, "the coverage must be in (0, 1]"};
  if (!(max_rms_cm > 0.0 && std::isfinite(max_rms_cm))) return Error{"", 0, "the maximum threshold must be > 0 cm"};
  if (!(lowest_rms_cm > 0.0 && lowest_rms_cm < max_rms_cm)) {
    return Error{"", 0, "the lowest threshold tried must be > 0 cm and below the maximum"};
  }
  if (!(reachable_share > 0.0 && reachable_share <= 1.0)) return Error{"", 0, "the reachable share must be in (0, 1]"};
  if (!(min_transition_rate >= 0.0)) return Error{"", 0, "the transition rate wanted must be >= 0"};
  if (grid < 2) return Error{"", 0, "the threshold grid needs at least 2 steps"};
  if (refine < 0) return Error{"", 0, "the refinement steps must be >= 0"};
  return Ok{};
}

const CoveragePoint& ThresholdChoice::chosen() const {
  for (const CoveragePoint& p : curve) {
    if (p.threshold == threshold && p.tag_thresholds == tag_thresholds) return p;
  }
  return curve.front();
}

namespace {

// levels[i] as the given threshold of tags[i].
std::vector<OwnThreshold> own_thresholds(std::span<const int> tags, std::span<const double> levels) {
  std::vector<OwnThreshold> own;
  for (size_t i = 0; i < levels.size() && i < tags.size(); ++i) own.push_back({tags[i], levels[i]});
  return own;
}

// The share of the untagged class's frames (untagged_class_frames) that the graph's clip edges
// play.
double untagged_coverage(std::span<const char> in_class, const MotionGraph& graph) {
  const long long all = std::count(in_class.begin(), in_class.end(), 1);
  long long played = 0;
  for (const GraphEdge& e : graph.edges) {
    if (e.transition) continue;
    for (int f = graph.nodes[e.from_node].frame; f < graph.nodes[e.to_node].frame; ++f) played += in_class[f];
  }
  return all > 0 ? static_cast<double>(played) / static_cast<double>(all) : 0.0;
}

}  // namespace

GraphFromCandidatesSettings with_chosen_thresholds(const GraphFromCandidatesSettings& settings,
                                                  const ThresholdChoice& choice) {
  GraphFromCandidatesSettings out = settings;
  out.transitions.threshold = choice.threshold;
  out.transitions.tag_thresholds = own_thresholds(choice.tags, choice.tag_thresholds);
  return out;
}

namespace {

// coverage_tags with the untagged class's frames known.
std::vector<int> coverage_tags(TagMask connected, std::span<const char> in_class) {
  std::vector<int> tags;
  for (int t = 0; t < 64; ++t) {
    if (connected >> t & 1) tags.push_back(t);
  }
  if (!tags.empty() && std::find(in_class.begin(), in_class.end(), 1) != in_class.end()) {
    tags.push_back(kUntaggedClass);
  }
  return tags;
}

}  // namespace

std::vector<int> coverage_tags(const MotionDatabase& db, const GraphFromCandidatesSettings& settings) {
  return coverage_tags(settings.connected_tags, untagged_class_frames(db, settings.connected_tags));
}

Result<CoveragePoint> coverage_at(const MotionDatabase& db, const FrameFeatures& features,
                                  const CandidateSearch& candidates, const GraphFromCandidatesSettings& settings,
                                  double threshold, OnDemandCandidates* more) {
  GraphFromCandidatesSettings at = settings;
  at.transitions.threshold = threshold;
  at.aligned = false;  // only the graph's shape is counted
  CoveragePoint point;
  point.threshold = threshold;
  point.rms_cm = rms_cm_of_distance(threshold, features);
  point.quantile = candidates.histogram.fraction_below(threshold);
  const std::vector<char> in_class = untagged_class_frames(db, settings.connected_tags);
  const std::vector<int> tags = coverage_tags(settings.connected_tags, in_class);
  point.tag_coverage.assign(tags.size(), 0.0);
  auto selected = select_transitions_with_bridges(db, features, candidates, at, more);
  if (!selected) return selected.error();
  // Without spacing the second pruning of build_spaced_graph keeps what the first kept (the
  // graph is rebuilt only to drop the nodes of pruned transitions), so one is enough here.
  const bool spaced = at.spacing.max_out > 0 || at.spacing.min_piece_frames > 0;
  auto pruned = spaced ? build_spaced_graph(db, *selected, features, at)
                       : build_pruned_graph(db, selected->all_transitions, features.window, at.connected_tags, {},
                                            selected->bridge_flags(selected->all_transitions));
  if (!pruned) {
    if (pruned.error().kind == ErrorKind::kEmptyGraph) return point;
    return pruned.error();
  }
  const GraphStatistics& after = pruned->prune.after;
  point.graph = true;
  point.kept_frames = after.clip_frames;
  point.transitions = after.transitions;
  if (tags.empty()) {
    point.coverage = db.frame_count() > 0 ? static_cast<double>(after.clip_frames) / db.frame_count() : 0.0;
    return point;
  }
  point.coverage = 1.0;
  for (size_t i = 0; i < tags.size(); ++i) {
    if (tags[i] == kUntaggedClass) {
      point.tag_coverage[i] = untagged_coverage(in_class, pruned->graph);
    }
    for (const TagStatistics& s : after.tags) {
      if (s.tag == tags[i] && s.database_frames > 0) {
        point.tag_coverage[i] = static_cast<double>(s.frames) / s.database_frames;
      }
    }
    point.coverage = std::min(point.coverage, point.tag_coverage[i]);
  }
  return point;
}

Result<ThresholdChoice> choose_threshold(const MotionDatabase& db, const FrameFeatures& features,
                                         const CandidateSearch& candidates,
                                         const GraphFromCandidatesSettings& settings,
                                         const ThresholdChoiceSettings& choice, OnDemandCandidates* more) {
  if (auto s = choice.validate(); !s) return s.error();
  ThresholdChoice out;
  const std::vector<char> in_class = untagged_class_frames(db, settings.connected_tags);
  out.tags = coverage_tags(settings.connected_tags, in_class);
  // Tag thresholds never pass the ceiling either.
  GraphFromCandidatesSettings capped = settings;
  const double ceiling = distance_of_rms_cm(choice.max_rms_cm, features);
  capped.transitions.max_threshold = ceiling;
  capped.transitions.tag_thresholds.clear();
  // Per-type: one threshold per motion type (levels[i] for out.tags[i]); else one for all.
  const bool per_type = settings.transitions.per_tag_thresholds && !out.tags.empty();
  const size_t n = per_type ? out.tags.size() : 1;
  // Per type, whether a type takes part: one the ceiling gives less than kMinServedShare of its
  // frames (a clip of no type too short to leave and come back to; a type on a few frames amid
  // other motion) wants nothing: no threshold serves it, and chasing its last frames
  // would take every type to the ceiling. It reaches its target at any threshold and would pull
  // the global threshold, the lowest, down to the grid's first level; it follows the global one
  // instead.
  std::vector<bool> takes_part(n, true);
  auto applied = [&](std::vector<double> levels) {
    double global = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < n; ++i) {
      if (takes_part[i]) global = std::min(global, levels[i]);
    }
    if (!std::isfinite(global)) global = *std::min_element(levels.begin(), levels.end());
    for (size_t i = 0; i < n; ++i) {
      if (!takes_part[i]) levels[i] = global;
    }
    return levels;
  };
  auto evaluate = [&](const std::vector<double>& asked) -> Result<CoveragePoint> {
    if (auto s = check_stop(choice.stop); !s) return s.error();
    GraphFromCandidatesSettings at = capped;
    const std::vector<double> levels = applied(asked);
    const double global = *std::min_element(levels.begin(), levels.end());
    if (per_type) at.transitions.tag_thresholds = own_thresholds(out.tags, levels);
    auto point = coverage_at(db, features, candidates, at, global, more);
    if (!point) return point.error();
    if (per_type) {
      point->tag_thresholds = levels;
      for (const double level : levels) point->tag_rms_cm.push_back(rms_cm_of_distance(level, features));
    }
    out.curve.push_back(*point);
    if (choice.tried) choice.tried(*point, static_cast<int>(out.curve.size()));
    return point;
  };

  // 0. The ceiling first: what each motion type can have at all. A type whose clips are short
  // (cut mid-stride at both ends) never reaches a high share at any threshold; its target is
  // then `reachable_share` of what the ceiling gives it, not a level no threshold reaches.
  auto top = evaluate(std::vector<double>(n, ceiling));
  if (!top) return top.error();
  out.targets.assign(std::max<size_t>(1, out.tags.size()), choice.coverage);
  if (top->graph) {
    if (out.tags.empty()) {
      out.targets[0] = std::min(choice.coverage, choice.reachable_share * top->coverage);
    } else {
      for (size_t i = 0; i < out.tags.size(); ++i) {
        out.targets[i] = top->tag_coverage[i] < kMinServedShare
                             ? 0.0
                             : std::min(choice.coverage, choice.reachable_share * top->tag_coverage[i]);
        if (per_type) takes_part[i] = out.targets[i] > 0.0;
      }
    }
  }
  const double fps = db.fps > 0.0 ? db.fps : 30.0;
  auto rate = [&](const CoveragePoint& p) { return transitions_per_second(p.transitions, p.kept_frames, fps); };
  out.target_rate = top->graph ? std::min(choice.min_transition_rate, rate(*top)) : choice.min_transition_rate;
  auto tag_short = [&](const CoveragePoint& p, size_t i) { return !p.graph || p.tag_coverage[i] < out.targets[i]; };
  auto reaches = [&](const CoveragePoint& p) {
    if (!p.graph || rate(p) < out.target_rate) return false;
    if (out.tags.empty()) return p.coverage >= out.targets[0];
    for (size_t i = 0; i < out.tags.size(); ++i) {
      if (tag_short(p, i)) return false;
    }
    return true;
  };
  // Whether p reaches every target but i's.
  auto reaches_but = [&](const CoveragePoint& p, size_t i) {
    if (!p.graph || rate(p) < out.target_rate) return false;
    for (size_t j = 0; j < out.tags.size(); ++j) {
      if (j != i && tag_short(p, j)) return false;
    }
    return true;
  };
  // The untagged class, when it takes part and holds at most kMinorUntaggedShare of the frames
  // (ThresholdChoice::untagged_holds).
  int minor_untagged = -1;
  if (per_type && out.tags.back() == kUntaggedClass && takes_part[n - 1]) {
    const auto frames = std::count(in_class.begin(), in_class.end(), 1);
    if (static_cast<double>(frames) <= kMinorUntaggedShare * static_cast<double>(db.frame_count())) {
      minor_untagged = static_cast<int>(n - 1);
    }
  }
  // Whether threshold i is short at p: its own type's coverage, per type; the whole target else.
  auto short_at = [&](const CoveragePoint& p, size_t i) { return per_type ? tag_short(p, i) : !reaches(p); };

  // 1. The grid, from the lowest threshold up; each step raises the thresholds short at the last
  // point (all of them when only the transition rate is short). It stops at the first point that
  // reaches the targets.
  std::vector<double> levels(n), below(n, -1.0);  // below: each one's last level short of its target
  std::optional<std::vector<double>> reaching;     // the lowest levels known to reach the targets
  CoveragePoint last;
  for (int g = 0; g + 1 < choice.grid; ++g) {
    const double level = distance_of_rms_cm(
        choice.lowest_rms_cm * std::pow(choice.max_rms_cm / choice.lowest_rms_cm,
                                        static_cast<double>(g) / (choice.grid - 1)),
        features);
    if (g == 0) {
      levels.assign(n, level);
    } else {
      bool raised = false;
      for (size_t i = 0; i < n; ++i) {
        if (short_at(last, i)) {
          below[i] = levels[i];
          levels[i] = level;
          raised = true;
        }
      }
      for (size_t i = 0; i < n && !raised; ++i) {
        if (levels[i] < level) below[i] = levels[i], levels[i] = level;
      }
    }
    auto point = evaluate(levels);
    if (!point) return point.error();
    last = std::move(*point);
    if (reaches(last)) {
      reaching = levels;
      break;
    }
  }
  if (!reaching && reaches(*top)) {
    // The thresholds short at the grid's last point go to the ceiling; all of them when that
    // is not enough (the graph short of the transition rate), each bracketed from its level
    // there, so that the bisection brings them down together to where the rate is met: a
    // library of two short walks and two runs meets the rate with walking at 1.85 cm, and kept
    // 10 cm, the ceiling, without the bracket.
    for (size_t i = 0; i < n; ++i) {
      if (short_at(last, i)) below[i] = levels[i], levels[i] = ceiling;
    }
    if (n > 1) {
      auto point = evaluate(levels);
      if (!point) return point.error();
      if (!reaches(*point)) {
        // Clips of no type, a minor share of the library, that join it only with the types' own
        // thresholds raised: said, for the user to give them a type.
        out.untagged_holds = minor_untagged >= 0 && reaches_but(*point, static_cast<size_t>(minor_untagged));
        for (size_t i = 0; i < n; ++i) {
          if (levels[i] < ceiling) below[i] = levels[i], levels[i] = ceiling;
        }
      }
    }
    reaching = levels;
  }
  // 2. Bisection in log D between each threshold's bracket: its last level short of its target
  // and its first reaching it. A point that reaches every target moves every bracket down; one
  // that misses only some types moves theirs up and the others down; one short of the rate
  // moves them all up.
  if (reaching) {
    std::vector<double> above = *reaching;
    for (int step = 0; step < choice.refine; ++step) {
      std::vector<double> middle = above;
      bool any = false;
      for (size_t i = 0; i < n; ++i) {
        if (below[i] > 0.0) middle[i] = std::sqrt(below[i] * above[i]), any = true;
      }
      if (!any) break;
      auto point = evaluate(middle);
      if (!point) return point.error();
      const bool all = reaches(*point);
      if (all) reaching = middle;
      const bool rate_short = !point->graph || rate(*point) < out.target_rate;
      for (size_t i = 0; i < n; ++i) {
        if (below[i] <= 0.0) continue;
        if (all || (!rate_short && !short_at(*point, i))) {
          above[i] = middle[i];
        } else {
          below[i] = middle[i];
        }
      }
    }
    // Types that reached their targets in different points: their thresholds together.
    if (above != *reaching) {
      auto point = evaluate(above);
      if (!point) return point.error();
      if (reaches(*point)) reaching = above;
    }
  }
  std::stable_sort(out.curve.begin(), out.curve.end(),
                   [](const CoveragePoint& x, const CoveragePoint& y) { return x.threshold < y.threshold; });
  auto choose = [&](const std::vector<double>& asked) {
    const std::vector<double> chosen = applied(asked);
    out.threshold = *std::min_element(chosen.begin(), chosen.end());
    if (per_type) out.tag_thresholds = chosen;
  };
  if (reaching) {
    out.reached = true;
    choose(*reaching);
  } else {
    // No graph reaches the targets (no graph at all, or pruning keeps less at the ceiling than
    // below it): the lowest threshold with the best worst coverage.
    double best = -1.0;
    for (const CoveragePoint& p : out.curve) {
      const double c = p.graph ? p.coverage : -0.5;
      if (c > best + 1e-9) {
        best = c;
        choose(per_type ? p.tag_thresholds : std::vector<double>{p.threshold});
      }
    }
  }
  out.rms_cm = rms_cm_of_distance(out.threshold, features);
  return out;
}

Result<std::optional<CoveragePoint>> lowest_graph_threshold(const MotionDatabase& db, const FrameFeatures& features,
                                                            const CandidateSearch& candidates,
                                                            const GraphFromCandidatesSettings& settings, double from) {
  double largest = 0.0;
  for (const Transition& t : candidates.minima) largest = std::max(largest, static_cast<double>(t.distance));
  if (largest <= 0.0) return std::optional<CoveragePoint>{};
  GraphFromCandidatesSettings unbounded = settings;
  unbounded.transitions.max_threshold = -1.0;
  unbounded.transitions.tag_thresholds.clear();
  // Upward by doubling D until a graph is made (or every candidate is in), then bisection.
  double low = std::max(from, 0.0), high = std::max(2.0 * low, largest * 1e-6);
  std::optional<CoveragePoint> found;
  while (true) {
    auto point = coverage_at(db, features, candidates, unbounded, std::min(high, largest));
    if (!point) return point.error();
    if (point->graph) {
      found = std::move(*point);
      break;
    }
    if (high >= largest) return std::optional<CoveragePoint>{};
    low = high;
    high *= 2.0;
  }
  high = found->threshold;
  for (int step = 0; step < 8; ++step) {
    const double middle = 0.5 * (low + high);
    auto point = coverage_at(db, features, candidates, unbounded, middle);
    if (!point) return point.error();
    if (point->graph) {
      high = middle;
      found = std::move(*point);
    } else {
      low = middle;
    }
  }
  return found;
}

void to_json(nlohmann::json& json, const ThresholdChoiceSettings& settings) {
  json = {{"coverage_target", settings.coverage},         {"max_rms_cm", settings.max_rms_cm},
          {"reachable_share", settings.reachable_share}, {"min_transition_rate", settings.min_transition_rate},
          {"lowest_rms_cm", settings.lowest_rms_cm},     {"grid", settings.grid},
          {"refine", settings.refine}};
}

void from_json(const nlohmann::json& json, ThresholdChoiceSettings& settings) {
  const ThresholdChoiceSettings defaults;
  settings.coverage = json.value("coverage_target", defaults.coverage);
  settings.max_rms_cm = json.value("max_rms_cm", defaults.max_rms_cm);
  settings.reachable_share = json.value("reachable_share", defaults.reachable_share);
  settings.min_transition_rate = json.value("min_transition_rate", defaults.min_transition_rate);
  settings.lowest_rms_cm = json.value("lowest_rms_cm", defaults.lowest_rms_cm);
  settings.grid = json.value("grid", defaults.grid);
  settings.refine = json.value("refine", defaults.refine);
}

}  // namespace mg
