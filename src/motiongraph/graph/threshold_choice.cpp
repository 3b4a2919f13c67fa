// The transition threshold chosen from the data: lowest threshold reaching a coverage target.
#include "motiongraph/graph/threshold_choice.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace mg {

double rms_cm_of_distance(double distance, const FrameFeatures& features) {
  if (!(features.window_weight > 0.0) || !(distance > 0.0)) return 0.0;
  return 100.0 * std::sqrt(distance / features.window_weight);
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
    if (p.threshold == threshold) return p;
  }
  return curve.front();
}

std::vector<int> coverage_tags(const GraphFromCandidatesSettings& settings) {
  std::vector<int> tags;
  for (int t = 0; t < 64; ++t) {
    if (settings.connected_tags >> t & 1) tags.push_back(t);
  }
  return tags;
}

Result<CoveragePoint> coverage_at(const MotionDatabase& db, const FrameFeatures& features,
                                  const CandidateSearch& candidates, const GraphFromCandidatesSettings& settings,
                                  double threshold, OnDemandCandidates* more) {
  GraphFromCandidatesSettings at = settings;
  at.transitions.threshold = threshold;
  CoveragePoint point;
  point.threshold = threshold;
  point.rms_cm = rms_cm_of_distance(threshold, features);
  point.quantile = candidates.histogram.fraction_below(threshold);
  const std::vector<int> tags = coverage_tags(settings);
  point.tag_coverage.assign(tags.size(), 0.0);
  auto selected = select_transitions_with_bridges(db, features, candidates, at, more);
  if (!selected) return selected.error();
  // Without spacing the second pruning of build_spaced_graph keeps what the first kept (the
  // graph is rebuilt only to drop the nodes of pruned transitions), so one is enough here.
  const bool spaced = at.spacing.max_out > 0 || at.spacing.min_piece_frames > 0;
  auto pruned = spaced ? build_spaced_graph(db, *selected, features, at)
                       : build_pruned_graph(db, selected->all_transitions, features.window, at.connected_tags,
                                            selected->blend_lengths(selected->all_transitions, features.window));
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
  out.tags = coverage_tags(settings);
  // Tag thresholds never pass the ceiling either.
  GraphFromCandidatesSettings capped = settings;
  const double ceiling = distance_of_rms_cm(choice.max_rms_cm, features);
  capped.transitions.max_threshold = ceiling;
  auto evaluate = [&](double threshold) -> Result<const CoveragePoint*> {
    auto point = coverage_at(db, features, candidates, capped, threshold, more);
    if (!point) return point.error();
    out.curve.push_back(std::move(*point));
    return &out.curve.back();
  };

  // 0. The ceiling first: what each motion type can have at all. A type whose clips are short
  // (cut mid-stride at both ends) never reaches a high share at any threshold; its target is
  // then `reachable_share` of what the ceiling gives it, not a level no threshold reaches.
  auto top = coverage_at(db, features, candidates, capped, ceiling, more);
  if (!top) return top.error();
  out.targets.assign(std::max<size_t>(1, out.tags.size()), choice.coverage);
  if (top->graph) {
    if (out.tags.empty()) {
      out.targets[0] = std::min(choice.coverage, choice.reachable_share * top->coverage);
    } else {
      for (size_t i = 0; i < out.tags.size(); ++i) {
        out.targets[i] = std::min(choice.coverage, choice.reachable_share * top->tag_coverage[i]);
      }
    }
  }
  const double fps = db.fps > 0.0 ? db.fps : 30.0;
  auto rate = [&](const CoveragePoint& p) {
    return p.kept_frames > 0 ? p.transitions / (static_cast<double>(p.kept_frames) / fps) : 0.0;
  };
  out.target_rate = top->graph ? std::min(choice.min_transition_rate, rate(*top)) : choice.min_transition_rate;
  auto reaches = [&](const CoveragePoint& p) {
    if (!p.graph || rate(p) < out.target_rate) return false;
    if (out.tags.empty()) return p.coverage >= out.targets[0];
    for (size_t i = 0; i < out.tags.size(); ++i) {
      if (p.tag_coverage[i] < out.targets[i]) return false;
    }
    return true;
  };
  out.curve.push_back(std::move(*top));

  // 1. The grid, from the lowest threshold up; it stops at the first that reaches the targets.
  double below = -1.0, above = -1.0;  // the bracket: last short of the targets, first reaching them
  for (int i = 0; i + 1 < choice.grid; ++i) {
    const double rms = choice.lowest_rms_cm * std::pow(choice.max_rms_cm / choice.lowest_rms_cm,
                                                       static_cast<double>(i) / (choice.grid - 1));
    auto point = evaluate(distance_of_rms_cm(rms, features));
    if (!point) return point.error();
    if (reaches(**point)) {
      above = (*point)->threshold;
      break;
    }
    below = (*point)->threshold;
  }
  if (above < 0.0 && reaches(out.curve.front())) above = ceiling;
  // 2. Bisection in log D between the bracket's ends.
  if (above > 0.0 && below > 0.0) {
    for (int step = 0; step < choice.refine; ++step) {
      const double middle = std::sqrt(below * above);
      auto point = evaluate(middle);
      if (!point) return point.error();
      if (reaches(**point)) {
        above = middle;
      } else {
        below = middle;
      }
    }
  }
  std::sort(out.curve.begin(), out.curve.end(),
            [](const CoveragePoint& x, const CoveragePoint& y) { return x.threshold < y.threshold; });
  if (above > 0.0) {
    out.reached = true;
    out.threshold = above;
  } else {
    // No graph reaches the targets (no graph at all, or pruning keeps less at the ceiling than
    // below it): the lowest threshold with the best worst coverage.
    double best = -1.0;
    for (const CoveragePoint& p : out.curve) {
      const double c = p.graph ? p.coverage : -0.5;
      if (c > best + 1e-9) {
        best = c;
        out.threshold = p.threshold;
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
