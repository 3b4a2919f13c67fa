// Can the graph follow a path: a probe synthesized at rising thresholds.
#include "motiongraph/synthesis/path_check.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <span>

#include <nlohmann/json.hpp>

#include "motiongraph/graph/threshold_choice.h"

namespace mg {

Status PathCheckSettings::validate() const {
  if (!(tolerance_m > 0.0) || !std::isfinite(tolerance_m)) return Error{"", 0, "the path check's tolerance must be > 0 m"};
  if (!(lost_m > 0.0)) return Error{"", 0, "the path check's lost distance must be > 0 m"};
  if (steps < 0) return Error{"", 0, "the path check's steps must be >= 0"};
  if (!(min_travel_share >= 0.0 && min_travel_share <= 1.0)) {
    return Error{"", 0, "the path check's travelling share must be in [0, 1]"};
  }
  if (!(travel_speed_mps > 0.0)) return Error{"", 0, "the path check's travelling speed must be > 0"};
  if (!(transition_penalty_m2 >= 0.0) || !std::isfinite(transition_penalty_m2)) {
    return Error{"", 0, "the path check's transition penalty must be >= 0"};
  }
  return synthesis.validate();
}

const PathCheckPoint* PathCheck::chosen() const {
  for (const PathCheckPoint& p : points) {
    if (p.threshold == threshold) return &p;
  }
  return nullptr;
}

FloorPath path_check_probe(bool mirrored) {
  constexpr double kPi = std::numbers::pi;
  constexpr double kStraight = 2.0, kRadius = 4.0, kStep = 0.1;
  // Heading h is measured from north (-z) towards east (+x): direction (sin h, -cos h).
  std::vector<Vec2> points{Vec2(0.0, 0.0)};
  double h = 0.0;
  auto go = [&](double length, double curvature) {
    const int n = static_cast<int>(std::ceil(length / kStep));
    for (int i = 0; i < n; ++i) {
      const double ds = length / n;
      h += 0.5 * curvature * ds;
      points.push_back(points.back() + Vec2(std::sin(h) * ds, -std::cos(h) * ds));
      h += 0.5 * curvature * ds;
    }
  };
  go(kStraight, 0.0);
  go(kPi * kRadius, 1.0 / kRadius);   // right
  go(kPi * kRadius, -1.0 / kRadius);  // left
  go(kStraight, 0.0);
  if (mirrored) {
    for (Vec2& p : points) p.x() = -p.x();
  }
  auto path = FloorPath::create(points);
  return std::move(*path);  // a fixed, valid polyline
}

double travelling_share(const SynthesisContext& context, double speed_mps) {
  const MotionGraph& graph = *context.graph;
  const double fps = context.db->fps > 0.0 ? context.db->fps : 30.0;
  long long frames = 0, travelling = 0;
  for (int e = 0; e < graph.edge_count(); ++e) {
    if (graph.edges[e].transition) continue;
    const auto roots = context.tracks.roots_of(e);
    if (roots.size() < 2) continue;
    double length = 0.0;
    for (size_t i = 1; i < roots.size(); ++i) length += (roots[i] - roots[i - 1]).norm();
    const double seconds = static_cast<double>(roots.size() - 1) / fps;
    frames += static_cast<long long>(roots.size());
    if (length >= speed_mps * seconds) travelling += static_cast<long long>(roots.size());
  }
  return frames > 0 ? static_cast<double>(travelling) / frames : 0.0;
}

namespace {

// The probes (the probe, and its mirror when asked) on the graph of one threshold, the point
// the worse of them. travel_share is set only when asked for. With as_path_does, the search is
// `path`'s own, edit and retries included, and the deviations are its delivered motion's.
Result<PathCheckPoint> probe_at(const MotionDatabase& db, const FrameFeatures& features,
                                const CandidateSearch& candidates, const GraphFromCandidatesSettings& settings,
                                double threshold, const PathCheckSettings& check, std::span<const FloorPath> probes,
                                double* travel_share, OnDemandCandidates* more, bool as_path_does = false) {
  GraphFromCandidatesSettings at = settings;
  at.transitions.threshold = threshold;
  PathCheckPoint point;
  point.threshold = threshold;
  point.rms_cm = rms_cm_of_distance(threshold, features);
  auto selected = select_transitions_with_bridges(db, features, candidates, at, more);
  if (!selected) return selected.error();
  auto built = build_spaced_graph(db, *selected, features, at);
  if (!built) {
    if (built.error().kind == ErrorKind::kEmptyGraph) return point;
    return built.error();
  }
  point.graph = true;
  auto context = make_synthesis_context(db, built->graph);
  if (!context) return context.error();
  if (travel_share != nullptr) *travel_share = travelling_share(*context, check.travel_speed_mps);
  const auto start = std::chrono::steady_clock::now();
  PathSynthesisSettings search = check.synthesis;
  if (!as_path_does) {
    search.edit_path = false;     // the graph is judged, not the edit that bends its motion,
    search.progress_retries = 0;  // nor another search pushing harder,
    search.anchor_arc = false;    // nor one that corrects its arc as it goes: Kovar's search alone
    search.transition_penalty_m2 = check.transition_penalty_m2;
  }
  PathCheckPoint worse = point;
  std::array<double, 2> deviations = point.probe_deviations_m;
  for (size_t i = 0; i < probes.size() && i < deviations.size(); ++i) {
    if (check.searching) {
      search.searched = [&check, rms_cm = point.rms_cm, probe = static_cast<int>(i)](double arc_m, int) {
        check.searching(rms_cm, probe, arc_m);
      };
    }
    auto result = synthesize_path(*context, probes[i], search);
    if (!result) return result.error();
    PathCheckPoint one = point;
    one.mean_deviation_m = as_path_does ? result->mean_deviation_m : result->graph_mean_deviation_m;
    one.max_deviation_m = as_path_does ? result->max_deviation_m : result->graph_max_deviation_m;
    one.reached_end = result->reached_end;
    one.arc_covered_m = result->arc_covered_m;
    one.transitions = result->walk.transition_count(built->graph);
    deviations[i] = one.mean_deviation_m;
    if (i == 0 || went_better(worse, one)) worse = one;
  }
  worse.probe_deviations_m = deviations;
  worse.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return worse;
}

bool passes(const PathCheckPoint& p, double tolerance) {
  return p.graph && p.reached_end && p.mean_deviation_m <= tolerance;
}

}  // namespace

bool went_better(const PathCheckPoint& p, const PathCheckPoint& q) {
  if (p.graph != q.graph) return p.graph;
  if (p.reached_end != q.reached_end) return p.reached_end;
  if (!p.reached_end && p.arc_covered_m != q.arc_covered_m) return p.arc_covered_m > q.arc_covered_m;
  return p.mean_deviation_m < q.mean_deviation_m;
}

Result<PathCheck> check_path_following(const MotionDatabase& db, const FrameFeatures& features,
                                       const CandidateSearch& candidates, const GraphFromCandidatesSettings& settings,
                                       double from_threshold, double ceiling, const PathCheckSettings& check,
                                       OnDemandCandidates* more) {
  if (auto s = check.validate(); !s) return s.error();
  std::vector<FloorPath> probe{path_check_probe()};
  if (check.mirrored) probe.push_back(path_check_probe(true));
  PathCheck out;
  out.probe_length_m = probe.front().length_m();
  out.threshold = from_threshold;
  out.rms_cm = rms_cm_of_distance(from_threshold, features);
  auto first = probe_at(db, features, candidates, settings, from_threshold, check, probe, &out.travel_share, more);
  if (!first) return first.error();
  out.points.push_back(*first);
  if (check.tried) check.tried(out.points.back(), 1);
  if (first->graph && out.travel_share < check.min_travel_share) {
    out.skipped = true;
    return out;
  }
  if (passes(*first, check.tolerance_m)) {
    out.passed = true;
    return out;
  }
  // Upward in log-spaced RMS steps to the ceiling; the first that passes is the answer.
  const double from_rms = out.rms_cm, ceiling_rms = rms_cm_of_distance(ceiling, features);
  if (from_rms > 0.0 && ceiling_rms > from_rms) {
    for (int i = 1; i <= check.steps; ++i) {
      const double rms = from_rms * std::pow(ceiling_rms / from_rms, static_cast<double>(i) / check.steps);
      const double threshold = i == check.steps ? ceiling : distance_of_rms_cm(rms, features);
      auto point = probe_at(db, features, candidates, settings, threshold, check, probe, nullptr, more);
      if (!point) return point.error();
      out.points.push_back(*point);
      if (check.tried) check.tried(out.points.back(), static_cast<int>(out.points.size()));
      if (passes(*point, check.tolerance_m)) {
        out.passed = true;
        out.threshold = point->threshold;
        out.rms_cm = point->rms_cm;
        return out;
      }
    }
  }
  // None passed: the one that went best (the first of equals) among the first and the probes
  // not lost; when the first made no graph and every probe was lost, the best of all.
  const double lost_m = std::max(check.lost_m, check.tolerance_m);
  const PathCheckPoint* best = &out.points.front();
  for (const PathCheckPoint& p : out.points) {
    if (p.graph && p.mean_deviation_m <= lost_m && went_better(p, *best)) best = &p;
  }
  if (!best->graph) {
    for (const PathCheckPoint& p : out.points) {
      if (went_better(p, *best)) best = &p;
    }
  }
  out.threshold = best->threshold;
  out.rms_cm = best->rms_cm;
  if (best->graph) {
    auto delivered = probe_at(db, features, candidates, settings, best->threshold, check, probe, nullptr, more,
                              /*as_path_does=*/true);
    if (!delivered) return delivered.error();
    out.delivered = *delivered;
  }
  return out;
}

void to_json(nlohmann::json& json, const PathCheckSettings& settings) {
  json = {{"tolerance_m", settings.tolerance_m},
          {"lost_m", settings.lost_m},
          {"steps", settings.steps},
          {"min_travel_share", settings.min_travel_share},
          {"travel_speed_mps", settings.travel_speed_mps},
          {"mirrored", settings.mirrored}};
}

void from_json(const nlohmann::json& json, PathCheckSettings& settings) {
  const PathCheckSettings defaults;
  settings.tolerance_m = json.value("tolerance_m", defaults.tolerance_m);
  settings.lost_m = json.value("lost_m", defaults.lost_m);
  settings.steps = json.value("steps", defaults.steps);
  settings.min_travel_share = json.value("min_travel_share", defaults.min_travel_share);
  settings.travel_speed_mps = json.value("travel_speed_mps", defaults.travel_speed_mps);
  settings.mirrored = json.value("mirrored", defaults.mirrored);
}

}  // namespace mg
