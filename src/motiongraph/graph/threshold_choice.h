// The transition threshold chosen from the data. A fixed quantile of all pairs suits one
// library and not the next: the number of pairs grows with N^2, so a big library keeps several
// transitions per frame, and a small one of short clips keeps none that pruning lets live.
// What a user wants instead is a graph that can play most of each motion type, with the least
// visible transitions. So: the lowest threshold at which the pruned graph keeps a target share
// (`coverage`) of each motion type's frames (of all frames when there are no motion types),
// never above a quality ceiling.
//
// Thresholds are spoken of in a unit a person can judge: the RMS distance between the aligned
// point clouds of the two windows, in cm, sqrt(D / W) with W the window's total weight
// (frame_features.h): D = W * (rms_cm / 100)^2.
//
// Short clips cut mid-stride at both ends (subject 16's runs are 1.2-2 s) keep only part of
// their frames at any threshold: pruning drops the pieces that lead out of a clip's end. So a
// motion type's target is the smaller of `coverage` and `reachable_share` of what the ceiling
// gives it: a type that can have 40 % at most wants 36 %, not an unreachable 70 % that would
// drive the threshold to the ceiling for a few frames more. And the pruned graph must offer
// `min_transition_rate` transitions per second of the motion it keeps (or what the ceiling
// offers, when less): otherwise it cannot be steered.
//
// The search: the ceiling first (what each type can reach), then `grid` thresholds log-spaced
// in RMS from `lowest_rms_cm` up to the ceiling, each run through selection, spacing, bridges,
// graph and pruning (graph_from_candidates.h) on the cached candidates, stopping at the first
// that reaches every target (the types still short at the grid's end go to the ceiling; all of
// them when the graph is then short of the transition rate alone, each from its own level, so
// that the bisection lowers them together to where the rate is met); then `refine` bisection
// steps (in log D) between the last threshold short of the targets and the first that reaches
// them. Coverage is close to
// monotone in the threshold but not exactly (pruning is not), so the answer is the lowest
// threshold found that reaches them, not a proof that no lower one does. When none does (no
// graph at all under the ceiling), the answer is the lowest threshold whose worst coverage is
// the best the search saw (`reached` false). Every threshold tried is kept, as the curve the
// report carries.
//
// With per-tag thresholds (the default when clips carry motion types), each motion type gets
// its own threshold by the same search: a grid step raises only the types still short of their
// targets (all of them while the graph is short of the transition rate), and the bisection
// moves each type's threshold within its own bracket. Clips of no motion type are one more class
// (window_membership.h's untagged_class_frames), whose threshold the windows within them pass;
// frames of no type in a typed clip are its way in and out, of no class. The global threshold,
// which the mixed windows (between types, or a type and frames of none) pass, is the lowest of
// them, but for types the ceiling gives less than a tenth of their frames (kMinServedShare: a
// clip of no type too short to leave and come back to; a type on a few frames amid other
// motion): no threshold serves them, so they want nothing (in either mode: chasing one frame of
// 26 took a library's every type to the ceiling), and take the global threshold rather than pull
// it down to the grid's first level. Clips of no type are bridged to the types (bridges.h); those
// that hold at most kMinorUntaggedShare of the frames and that the types' thresholds at their
// grid levels, the short ones' at the ceiling, still leave out (too short to loop, so no bridge
// joins them) raise every type's, as the only way the graph takes them in, and
// ThresholdChoice::untagged_holds says so, for the user to give them a type. Running's larger
// distances then buy
// running what it needs, and no more: the threshold of a type depends only on the candidates at
// or below it, so the pruned distance stage gives the exhaustive stage's choice.
#pragma once

#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/graph/window_membership.h"

namespace mg {

// RMS point distance in cm of a distance D under the features' weights (or a window's total
// weight W, as a build report stores it), and back.
double rms_cm_of_distance(double distance, const FrameFeatures& features);
double rms_cm_of_distance(double distance, double window_weight);
double distance_of_rms_cm(double rms_cm, const FrameFeatures& features);

// A motion type the ceiling keeps less of than this share of its frames wants nothing (above).
inline constexpr double kMinServedShare = 0.1;
// Clips of no type that hold at most this share of the library's frames, and that the graph
// takes in only with the types' own thresholds raised (their windows into the typed clips pass
// the lower of the two classes' thresholds; too short to loop, no bridge joins them), are said
// to hold the types up, for the user to give them a type. Over a quarter, they are the library.
inline constexpr double kMinorUntaggedShare = 0.25;

struct CoveragePoint;

struct ThresholdChoiceSettings {
  double coverage = 0.7;        // share of each motion type's frames the pruned graph keeps
  double max_rms_cm = 10.0;     // quality ceiling (RMS point distance over the window)
  double reachable_share = 0.9; // a type's target is at most this share of its coverage at the ceiling
  // Coverage alone is met by a few long loops that cannot turn or stop (CMU subject 03 at
  // 3.3 cm: 79 % of its frames, 0.14 transitions per second, a path followed 1.7 m off). The
  // graph must also offer this many transitions per second of the motion it keeps.
  double min_transition_rate = 5.0;
  double lowest_rms_cm = 0.5;   // where the grid starts
  int grid = 16;                // log-spaced thresholds of the first pass (>= 2)
  int refine = 6;               // bisection steps after it
  // Not settings of the choice (not in its JSON): told of each point as it is tried (the build's
  // progress lines), and asked to stop (core/stop.h) before each, failing with stopped_error().
  std::function<void(const CoveragePoint& point, int tried)> tried;
  std::stop_token stop;

  Status validate() const;
};

// Its JSON form, the settings part of the build report's "threshold_choice":
// {"coverage_target", "max_rms_cm", "reachable_share", "min_transition_rate", "lowest_rms_cm",
// "grid", "refine"}; a key missing on reading keeps its default.
void to_json(nlohmann::json& json, const ThresholdChoiceSettings& settings);
void from_json(const nlohmann::json& json, ThresholdChoiceSettings& settings);

struct CoveragePoint {
  double threshold = 0.0;           // D (the global one, with per-tag thresholds)
  std::vector<double> tag_thresholds;  // per entry of ThresholdChoice::tags, D; empty: one threshold
  std::vector<double> tag_rms_cm;      // the same in RMS cm
  double rms_cm = 0.0;
  double quantile = 0.0;            // fraction of all finite D below the threshold
  bool graph = false;               // false: pruning left nothing
  double coverage = 0.0;            // the worst motion type's (or all frames')
  std::vector<double> tag_coverage; // per entry of ThresholdChoice::tags
  long long kept_frames = 0;        // database frames the pruned graph plays
  int transitions = 0;              // kept by pruning
};

struct ThresholdChoice {
  double threshold = 0.0;            // D chosen (the global one, with per-tag thresholds)
  double rms_cm = 0.0;
  std::vector<double> tag_thresholds;  // D chosen per entry of tags; empty: one threshold
  bool reached = false;              // the target coverage was reached under the ceiling
  // The untagged class (kMinorUntaggedShare of the frames or less) joined the graph only with
  // every type's threshold raised: it holds them up.
  bool untagged_holds = false;
  std::vector<int> tags;             // motion types measured (coverage_tags); empty: all frames
  std::vector<double> targets;       // the coverage each wanted (one per tag; one value without)
  double target_rate = 0.0;          // transitions per second of kept motion wanted
  std::vector<CoveragePoint> curve;  // every threshold tried, by threshold
  const CoveragePoint& chosen() const;
};

// The motion types coverage is measured on (bit indices of settings.connected_tags), and
// kUntaggedClass when some clips carry none of them (untagged_class_frames: they want a graph
// too); empty: the database's frames as a whole.
std::vector<int> coverage_tags(const MotionDatabase& db, const GraphFromCandidatesSettings& settings);

// The coverage of one threshold: `settings` with its threshold replaced by `threshold` (D) (its
// given tag thresholds, if any, stay, lifted to `threshold` where below it).
// `more`: as select_transitions_with_bridges takes it (the pruned stage's candidates).
Result<CoveragePoint> coverage_at(const MotionDatabase& db, const FrameFeatures& features,
                                  const CandidateSearch& candidates, const GraphFromCandidatesSettings& settings,
                                  double threshold, OnDemandCandidates* more = nullptr);

// The settings' own thresholds replaced by the choice's: the global one, and the given per-tag
// ones when the choice made them.
GraphFromCandidatesSettings with_chosen_thresholds(const GraphFromCandidatesSettings& settings,
                                                  const ThresholdChoice& choice);

// The threshold for `settings` (its own thresholds are ignored). Everything it reads lies at or
// below the ceiling but the bridges, so the pruned stage's candidates with their ceiling at
// least max_rms_cm's D, and `more` for the bridges, give the exhaustive stage's choice. Fails only when a stage fails
// for another reason than pruning leaving nothing; a library where nothing under the ceiling
// makes a graph gives a choice whose chosen point has graph == false.
Result<ThresholdChoice> choose_threshold(const MotionDatabase& db, const FrameFeatures& features,
                                         const CandidateSearch& candidates,
                                         const GraphFromCandidatesSettings& settings,
                                         const ThresholdChoiceSettings& choice, OnDemandCandidates* more = nullptr);

// The lowest threshold at or above `from` (D) that makes a graph at all, searched upward to
// the largest candidate distance and then refined; nullopt when even every candidate makes
// none. One threshold, as --threshold gives it (given tag thresholds are dropped). For the error a
// user gets when no graph can be made.
Result<std::optional<CoveragePoint>> lowest_graph_threshold(const MotionDatabase& db, const FrameFeatures& features,
                                                            const CandidateSearch& candidates,
                                                            const GraphFromCandidatesSettings& settings, double from);

}  // namespace mg
