// The build's settings, checked before any work.
#include "motiongraph/pipeline/build_settings.h"

#include <cmath>

#include "motiongraph/graph/candidates.h"
#include "motiongraph/graph/graph_from_candidates.h"

namespace mg {

const char* threshold_mode_name(ThresholdMode mode) {
  switch (mode) {
    case ThresholdMode::kAuto:
      return "auto";
    case ThresholdMode::kQuantile:
      return "quantile";
    case ThresholdMode::kDistance:
      return "distance";
    case ThresholdMode::kRmsCm:
      return "rms_cm";
  }
  return "auto";
}

Status BuildSettings::validate() const {
  TransitionSettings selection = transitions;
  if (threshold_mode == ThresholdMode::kQuantile) {
    selection.threshold = -1.0;
    selection.threshold_quantile = threshold_value;
  }
  CandidateSettings candidates;
  candidates.continuation_radius = distance_stage.continuation_radius;
  candidates.keep_matrix = exports.matrix_npy;
  for (const Status& s : {distance_stage.cloud.validate(), distance_stage.distance.validate(), selection.validate(),
                          candidates.validate(), bridges.validate(), choice.validate(), path_check_settings.validate(),
                          spacing.validate(), shared.validate(), pruned.validate()}) {
    if (!s) return s;
  }
  if ((threshold_mode == ThresholdMode::kDistance || threshold_mode == ThresholdMode::kRmsCm) &&
      !(std::isfinite(threshold_value) && threshold_value >= 0.0)) {
    return Error{"", 0, "the threshold must be a finite distance >= 0"};
  }
  if (!(std::isfinite(max_bridge_rms_cm) && max_bridge_rms_cm >= 0.0)) {
    return Error{"", 0, "the bridge cap must be a finite RMS distance >= 0 cm (0: no cap)"};
  }
  if (pruned_from_frames < 0) return Error{"", 0, "the pruned stage's smallest library must be >= 0 frames"};
  if (exports.matrix_npy && !shared.checkpoint_folder.empty()) {
    return Error{"", 0, "the matrix export (--export-matrix) is made without --checkpoint only"};
  }
  return Ok{};
}

bool BuildSettings::pruned_stage(const MotionDatabase& db, const FrameFeatures& features) const {
  if (exhaustive || exports.matrix_npy || db.frame_count() < pruned_from_frames) return false;
  if (threshold_mode == ThresholdMode::kAuto) return true;
  if (threshold_mode == ThresholdMode::kQuantile) return false;
  const double threshold =
      threshold_mode == ThresholdMode::kRmsCm ? distance_of_rms_cm(threshold_value, features) : threshold_value;
  if (!(threshold <= distance_of_rms_cm(choice.max_rms_cm, features))) return false;
  if (!transitions.per_tag_thresholds) return true;
  auto connected = connected_tags(db);
  return connected && *connected == 0;
}

Result<TagMask> BuildSettings::connected_tags(const MotionDatabase& db) const {
  TagMask connected = motion_type_tags(db);
  if (!connect_tags.empty()) {
    auto mask = tag_mask_of(db, connect_tags);
    if (!mask) return Error{"", 0, "--connect-tags: " + mask.error().message};
    connected = *mask;
  }
  return ignore_tags ? 0 : connected;
}

}  // namespace mg
