// Everything build_graph() takes besides its inputs (Kovar et al. 2002, sections 3-3.3): how
// the clips are read and resampled, the distance stage, how the threshold is found (chosen
// from the data, a quantile of all pairs, an absolute D or an RMS point distance in cm), the
// transition, spacing, bridge and motion-type settings, and which exports to make. Defaults
// are the paper's and the CLI's; validate() names the first rule broken.
#pragma once

#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/database/database_loader.h"
#include "motiongraph/graph/bridges.h"
#include "motiongraph/graph/pruned_candidates.h"
#include "motiongraph/graph/threshold_choice.h"
#include "motiongraph/graph/transition_selection.h"
#include "motiongraph/graph/transition_spacing.h"
#include "motiongraph/parallel/shared_candidates.h"
#include "motiongraph/pipeline/distance_stage_settings.h"
#include "motiongraph/synthesis/path_check.h"

namespace mg {

enum class ThresholdMode {
  kAuto,      // the lowest threshold keeping ThresholdChoiceSettings::coverage, path-checked
  kQuantile,  // threshold_value: the fraction of all defined pairs below the threshold
  kDistance,  // threshold_value: an absolute distance D
  kRmsCm,     // threshold_value: the RMS point distance over the window, in cm
};

// "auto", "quantile", "distance", "rms_cm": the name the report and the graph file record.
const char* threshold_mode_name(ThresholdMode mode);

// What the build makes besides the graph file (bytes in GraphBuild).
struct BuildExports {
  bool matrix_npy = false;  // the N x N float32 matrix (the distance stage then runs, cache or not)
  bool matrix_png = false;  // the distance picture with clip boundaries and transitions
  bool clouds_npy = false;  // the N x P x 3 float32 point clouds, metres
};

struct BuildSettings {
  DatabaseSettings database;
  DistanceStageSettings distance_stage;
  // The distance stage: the pruned one (graph/pruned_candidates.h), with the quality ceiling
  // (choice.max_rms_cm) as its ceiling, when the matrix is not exported and the threshold is
  // chosen automatically (per motion type too: each type's threshold is searched for under the
  // ceiling) or given by hand as a distance (D or cm) at or below the ceiling with one threshold
  // for all (no motion types, --ignore-tags or --no-tag-thresholds); the exhaustive one when asked
  // for or when something needs every distance (a quantile of all pairs, a threshold above the
  // ceiling, per-tag thresholds by rank: they count every candidate of a type). Both give the
  // same graph at the same tile side.
  bool exhaustive = false;
  // Below this many frames the exhaustive stage runs whatever the threshold: on small libraries
  // it is as fast or faster than the pruned stage with its bridges found on demand (subject 16 at
  // 120 fps, 4 940 frames: 1.0 s against 1.6 s for the whole build; 17 886 frames: 5.8 s against
  // 4.7 s; docs/performance.md). 0: from any size.
  int pruned_from_frames = 10000;
  PrunedSearchSettings pruned;  // its threads are distance_stage.distance's
  ThresholdMode threshold_mode = ThresholdMode::kAuto;
  double threshold_value = 0.0;  // see ThresholdMode
  // threshold and threshold_quantile are set by threshold_mode; locality, per-tag thresholds
  // and the rest are taken as they are.
  TransitionSettings transitions;
  ThresholdChoiceSettings choice;  // kAuto
  bool path_check = true;          // kAuto: raise the threshold until a test path is followed
  PathCheckSettings path_check_settings;
  TransitionSpacing spacing;
  // bridges.max_distance is set from max_bridge_rms_cm.
  BridgeSettings bridges;
  // No bridge above this RMS point distance in cm; 0: no cap.
  double max_bridge_rms_cm = 0.0;
  // The motion types whose frames must stay connected (bridged between); empty: every tag but
  // the modifiers (graph_from_candidates.h). ignore_tags: none, one component only.
  std::vector<std::string> connect_tags;
  bool ignore_tags = false;
  BuildExports exports;
  // The distance stage's checkpoint (none by default) and chunk size; progress_bar is
  // BuildLog's. The matrix export needs one process and no checkpoint.
  SharedSearchSettings shared;

  Status validate() const;
  // The motion types kept connected on `db`: connect_tags, or every type but the modifiers; none
  // with ignore_tags. Fails on a connect_tags name no clip carries.
  Result<TagMask> connected_tags(const MotionDatabase& db) const;
  // Whether the pruned stage runs on `db` (see `exhaustive`).
  bool pruned_stage(const MotionDatabase& db, const FrameFeatures& features) const;
};

}  // namespace mg
