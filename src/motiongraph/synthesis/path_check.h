// Can the graph follow a path? Coverage (graph/threshold_choice.h) says how much of each motion
// type a graph keeps, not whether it can turn: CMU subject 03 (walks on uneven ground) keeps
// 94 % of its frames at 5.9 cm, yet follows a gentle S-curve 0.44 m off there and 0.04 m off
// at 6.5 cm, where a few more transitions join its turning steps to its straight ones. So the
// automatic threshold is checked by doing what a user will do: synthesize a test path (the
// probe: 2 m straight, a half circle of 4 m radius to the right, one to the left, 2 m straight,
// about 29 m, with `path`'s default search, transitions priced as below) and its mirror (left
// first) on the graph of the threshold, and raise the threshold in log-spaced steps towards the
// ceiling until both are
// followed within `tolerance_m` mean deviation. Paths turn either way: one probe alone let a
// few moved nodes flip a library's choice (subject 16 followed the probe 0.081 m off at 2.65
// cm, its mirror 0.205 m off; both within 0.053 m at 3.46 cm). Each threshold is judged by the
// worse of the two (`mirrored`; off: the probe alone). When no step passes, the threshold
// whose probes went best (reached the end; else covered the most of it; then least deviation)
// is kept and `passed` is false, and the probes are synthesized there once more as `path` does
// by default (`delivered`). A higher threshold adds rougher transitions, so it is kept only
// when its probes came near the path at all (within `lost_m`, or the tolerance when larger, on
// average): a library whose clips hold no turns (game cycles
// walking straight, dance on the spot with a few steps) wanders tens of metres off at every
// threshold, and keeps the first.
//
// A library that hardly travels (dance on the spot, sitting, gestures) has no path to follow:
// when less than `min_travel_share` of the graph's clip frames are played in pieces moving at
// `travel_speed_mps` or faster, the check is skipped and the threshold stays.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/path_synthesis.h"

namespace mg {

struct PathCheckPoint;

struct PathCheckSettings {
  double tolerance_m = 0.1;         // mean deviation the probe must be followed within
  double lost_m = 1.0;              // a probe further off on average is lost (see above)
  int steps = 6;                    // thresholds tried above the first, log-spaced in RMS to the ceiling
  double min_travel_share = 0.1;    // of clip frames; below it the check is skipped
  double travel_speed_mps = 0.5;    // a clip piece travels when its root moves this fast on average
  bool mirrored = true;             // follow the probe's mirror too; a threshold is judged by the worse
  PathSynthesisSettings synthesis;  // the search `path` uses by default, once, its motion not edited
  // ... but for the cost of a transition (m^2), when the graph's own walk is judged: the check
  // asks whether the graph can turn, and `path`'s default (0.8) trades some of the walk's
  // deviation for fewer blends, which the edit then takes back. The tolerance was set with 0.2.
  double transition_penalty_m2 = 0.2;
  // Not settings of the check (not in its JSON): told of each threshold's point as it is made
  // (the build's progress lines); the search's `synthesis.stop` stops it.
  std::function<void(const PathCheckPoint& point, int tried)> tried;
  // ... and, while a probe is searched, after each of its searches (the search's own `searched`):
  // the threshold's RMS in cm, which probe (0: the probe, 1: its mirror), and the metres of it the
  // walk has come along.
  std::function<void(double rms_cm, int probe, double arc_m)> searching;

  Status validate() const;
};

// Its JSON form, the settings part of the build report's "path_check": {"tolerance_m", "lost_m",
// "steps", "min_travel_share", "travel_speed_mps", "mirrored"} (the search is `path`'s default, not
// recorded); a key missing on reading keeps its default.
void to_json(nlohmann::json& json, const PathCheckSettings& settings);
void from_json(const nlohmann::json& json, PathCheckSettings& settings);

struct PathCheckPoint {
  double threshold = 0.0;  // D
  double rms_cm = 0.0;
  bool graph = false;      // false: pruning left nothing at this threshold
  double mean_deviation_m = 0.0;
  double max_deviation_m = 0.0;
  bool reached_end = false;
  double arc_covered_m = 0.0;  // the probe's length the walk covered (path synthesis' arc)
  int transitions = 0;     // of the probe's walk
  double seconds = 0.0;    // the probes' search time
  // The mean deviation of the probe as drawn and of its mirror (NaN when not followed); the
  // fields above are the worse one's (went_better below).
  std::array<double, 2> probe_deviations_m{std::nan(""), std::nan("")};
};

// Whether probe p went better than q: a graph, then reaching the end (or, short of it, covering
// more of the probe: a walk stuck early deviates little only because it went nowhere), then less
// mean deviation.
bool went_better(const PathCheckPoint& p, const PathCheckPoint& q);

struct PathCheck {
  double probe_length_m = 0.0;       // of path_check_probe()
  bool skipped = false;              // the library hardly travels (see travel_share)
  double travel_share = 0.0;         // of the first graph's clip frames, in travelling pieces
  double threshold = 0.0;            // D chosen (the first one when skipped)
  double rms_cm = 0.0;
  bool passed = false;               // the chosen threshold's probe is within the tolerance
  std::vector<PathCheckPoint> points;  // every threshold tried, in order (increasing)
  // When none passed: the probes at the chosen threshold as `path` runs them by default (the
  // motion bent onto the path by the edit, searched again when off), the deviations the
  // delivered motion's, the worse of the two. The points judge the graph's own walks; this says
  // what a user will get.
  std::optional<PathCheckPoint> delivered;
  const PathCheckPoint* chosen() const;
};

// The probe path (see above), starting at the origin heading north; mirrored, turning left
// first (x negated).
FloorPath path_check_probe(bool mirrored = false);

// The share of the graph's clip frames played by clip edges whose root travels at
// `speed_mps` or faster on average.
double travelling_share(const SynthesisContext& context, double speed_mps);

// The check, from `from_threshold` (D, the coverage choice) up to `ceiling` (D) under
// `settings` (its own threshold ignored). Fails when a stage fails for another reason than
// pruning leaving nothing, or when the settings are invalid. `more`: as
// select_transitions_with_bridges takes it.
Result<PathCheck> check_path_following(const MotionDatabase& db, const FrameFeatures& features,
                                       const CandidateSearch& candidates, const GraphFromCandidatesSettings& settings,
                                       double from_threshold, double ceiling, const PathCheckSettings& check,
                                       OnDemandCandidates* more = nullptr);

}  // namespace mg
