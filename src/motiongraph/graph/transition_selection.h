// From candidates to transitions (Kovar et al. 2002, section 3.2): keep the local minima
// below a threshold, given in absolute units of D or as a quantile of all finite D; within a
// locality radius keep only the best (lowest D) candidate; compute each kept transition's
// floor alignment. Cheap: runs on the cached candidates, not on the distance matrix.
//
// Thresholds per motion type. Faster motion has larger distances: on subject 16 the 2 % quantile
// of D among run-run pairs is four times the quantile among all pairs, so one threshold keeps
// walking richly connected and running barely at all. With per-tag thresholds, each tag t of
// `tags` keeps the same share of its own candidates (local minima whose 2k frames all carry t)
// as the database keeps of all candidates under the global threshold: t's threshold is the D at
// that rank among its candidates, and a candidate of t is kept below it (or below the global
// threshold, whichever is larger).
//
// The automatic threshold (threshold_choice.h) gives each tag its own threshold instead, found by
// searching for the lowest at which the tag reaches its coverage target: `tag_thresholds` then
// holds them and no rank is taken. Given thresholds depend on no candidate above them, so the
// pruned stage's candidates serve them exactly, as they serve one threshold.
#pragma once

#include <span>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/metric/frame_features.h"

namespace mg {

// A motion type's own threshold, given.
struct OwnThreshold {
  int tag = 0;             // bit index into MotionDatabase::tag_names; -1: the untagged class
  double threshold = 0.0;  // D; a candidate of the tag passes at or below it
  bool operator==(const OwnThreshold&) const = default;
};

struct TransitionSettings {
  double threshold = -1.0;         // absolute D; < 0: use the quantile
  double threshold_quantile = 0.02;  // fraction of all finite D below the threshold
  int locality_radius = -1;        // frames (both a and b); -1 = half the window
  bool per_tag_thresholds = true;  // see above; needs frame tags
  double max_threshold = -1.0;     // absolute D no tag threshold passes; < 0: no ceiling
  // With per_tag_thresholds: each listed tag's own threshold, given rather than ranked (the
  // automatic choice's); a tag's threshold is never below the global one. Empty: by rank.
  std::vector<OwnThreshold> tag_thresholds;

  Status validate() const;
};

// Its JSON form, the one the graph file writes: {"threshold", "threshold_quantile",
// "max_threshold", "locality_radius", "per_tag_thresholds", "tag_thresholds": [{"tag", "threshold"}]}
// (the last only when given). Reading needs the first, second and fourth
// (nlohmann::json::exception otherwise); the others keep their defaults.
void to_json(nlohmann::json& json, const TransitionSettings& settings);
void from_json(const nlohmann::json& json, TransitionSettings& settings);

struct TagThreshold {
  int tag = 0;            // -1: the untagged class (given thresholds only)
  int candidates = 0;     // local minima belonging to the tag (under the ceiling of pruned candidates)
  double threshold = 0.0; // the tag's own threshold (never below the global one)
  bool given = false;     // from TransitionSettings::tag_thresholds, not by rank
};

struct TransitionSelection {
  double threshold = 0.0;          // the absolute threshold used
  double threshold_quantile = 0.0; // the fraction of finite D below it
  int locality_radius = 0;
  int candidates_below_threshold = 0;
  std::vector<TagThreshold> tag_thresholds;  // for the tags that have candidates
  std::vector<Transition> transitions;  // with alignment, sorted by (from_frame, to_frame)
};

// frame_tags: one mask per frame (or empty: no per-tag thresholds); tags: the tags that get
// their own threshold. On the pruned stage's candidates (ceiling >= 0) every threshold used must
// lie at or below the ceiling, and per-tag thresholds by rank are refused (given ones are not).
// aligned = false leaves the transitions' floor alignments at 0: a graph's shape does not need
// them (the automatic threshold's search builds dozens of graphs only to count what they keep).
// untagged_class: the frames whose windows tag -1's threshold governs, one entry per frame
// (window_membership.h's untagged_class_frames: the clips of no type); empty: every frame that
// carries none of `tags`.
Result<TransitionSelection> select_transitions(const FrameFeatures& features, const CandidateSearch& candidates,
                                               const TransitionSettings& settings,
                                               std::span<const TagMask> frame_tags = {}, TagMask tags = 0,
                                               bool aligned = true, std::span<const char> untagged_class = {});

}  // namespace mg
