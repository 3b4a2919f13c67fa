// The build report (`motiongraph build --report`, and GraphFile::report_json): the frames,
// rate, window, point and window weights, the clips with their tags and what the graph keeps of
// them, the feet and how often
// they are planted, the distance settings
// (DistanceStageSettings::to_json), the threshold and how it was found (the automatic choice's
// coverage curve, the path check), counts, the graph's statistics before and after pruning,
// the bridges (with their blend lengths), the motion types no bridge joins, whether the distance
// cache was used, and how the distance stage ran (processes, their peak memory and time for
// their tiles, tiles restored from a checkpoint). Thresholds are given both as D and as
// the RMS point distance in cm (graph/threshold_choice.h).
#pragma once

#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "motiongraph/database/database_loader.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/clip_coverage.h"
#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/graph/threshold_choice.h"
#include "motiongraph/metric/point_cloud.h"
#include "motiongraph/motion/clip_doubts.h"
#include "motiongraph/synthesis/path_check.h"

namespace mg {

// [{"name", "source", "first_frame", "frames", "tags", "skeleton"}, ...]; with the pruned graph's
// coverage (one per clip), each also has "kept_frames", and a clip it keeps nothing of
// "best_join_rms_cm" (ClipCoverage::best_join as RMS; null when no candidates could join it).
nlohmann::json clips_json(const MotionDatabase& db, std::span<const ClipCoverage> coverage = {},
                          const FrameFeatures* features = nullptr);

// Gives each entry of `clips` (clips_json of `db`) "doubts": the phrases of what looks wrong with
// that clip as read (loading's notes, motion/clip_doubts.h; matched by name, unique in a
// database), [] for one that looks right.
void add_clip_doubts(nlohmann::json& clips, const MotionDatabase& db, std::span<const DoubtedClip> doubts);
// Each clip's "mirror_of" (database_loader.h DatabaseSettings::mirror): the clip it mirrors, or
// null; as the build report and info --json give them.
void add_mirror_of(nlohmann::json& clips, const MotionDatabase& db, const DatabaseLoadNotes& notes);
// Loading's turning, {"travel_s", "left_deg", "right_deg", "lopsided"}, and the rigs it could not
// mirror, [{"skeleton", "reason", "clips"}]: as the build report and info --json give them.
nlohmann::json turning_json(const TurningBalance& turning);
nlohmann::json unmirrored_json(const DatabaseLoadNotes& notes);
// The report's mirroring: add_mirror_of, and "mirroring": {"mode" (auto, on or off), "turning":
// {"travel_s", "left_deg", "right_deg", "lopsided"}, "mirrored" (clips), "unmirrored":
// [{"skeleton", "reason", "clips"}]}.
void add_mirroring(nlohmann::json& report, const MotionDatabase& db, const DatabaseLoadNotes& notes);

// The feet found on each skeleton ({"feet": [{"skeleton", "left_ankle", "left_toe",
// "right_ankle", "right_toe"}]}) and the share of frames each joint is planted
// ("planted_share"); {"error": why} when the database has no contacts.
nlohmann::json foot_contacts_json(const MotionDatabase& db);

// One point of a coverage curve, per-tag coverage by tag name (`tags`: the tags measured); with
// per-type thresholds, each type's as "tag_thresholds" (D) and "tag_rms_cm".
nlohmann::json coverage_point_json(const CoveragePoint& point, const MotionDatabase& db, const std::vector<int>& tags);

// The automatic threshold: the target, the ceiling, and the curve it was chosen on; per type
// ("per_type"), the thresholds chosen by type name ("tag_thresholds", D).
nlohmann::json threshold_choice_json(const ThresholdChoice& choice, const MotionDatabase& db,
                                     const ThresholdChoiceSettings& settings);

// The path check: the tolerance, the probe and each threshold tried.
nlohmann::json path_check_json(const PathCheck& check, const PathCheckSettings& settings);

// The ordered pairs of motion types that no transition or bridge joins: [{"from", "to", "why",
// "best_distance", "best_rms_cm", "through_graph"}], the best distance null when no candidate
// would join them. "through_graph": both keep frames in the pruned graph `after` (null: none),
// which is strongly connected, so it leads from the one to the other through other frames (CMU
// 14's walking clips are all tagged jump too: no frame of walking lacks jump, so nothing can
// bridge walk to jump, yet the graph joins them).
nlohmann::json unjoined_json(const std::vector<UnjoinedPair>& pairs, const MotionDatabase& db,
                             const FrameFeatures& features, const GraphStatistics* after = nullptr);

// What the whole report is made of; pruned is null when pruning left nothing.
struct BuildReportParts {
  const MotionDatabase& db;
  const FrameFeatures& features;
  const CloudLayout& layout;
  const CandidateSearch& candidates;
  const TransitionsWithBridges& selected;
  const PrunedGraph* pruned = nullptr;
  std::span<const ClipCoverage> coverage;  // what pruned keeps of each clip (empty: no graph)
  nlohmann::json distance_settings;
  const char* threshold_mode = "auto";
  nlohmann::json threshold_choice;  // null unless automatic
  nlohmann::json path_check;        // null unless checked
  TransitionSpacing spacing;
  BridgeSettings bridge_settings;  // max_distance as D
  const char* distance_cache = "off";  // "hit", "stored" or "off"
  int processes = 1;                   // that shared the distance stage
  std::vector<double> peak_memory_mb;  // each process's peak at the end of the distance stage (empty: cache hit)
  std::vector<double> share_seconds;   // the seconds each process took for its share of the tiles
  long long restored_tiles = 0;        // tiles taken from a checkpoint
};

// The report without "timings" (and, for a failed build, without "error").
nlohmann::json build_report(const BuildReportParts& parts);

}  // namespace mg
