// The build's options as a user gives them, text where the user writes text (the CLI's
// `motiongraph build` options and the Python package's build() keywords), and the
// BuildSettings they make: the one place that reads a cloud or taper name, NAME=WEIGHT joint
// weights and a threshold given as 'auto', D or '4cm', so that both front ends accept the same
// values and fail with the same messages (which name the CLI's options).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/pipeline/build_settings.h"

namespace mg {

struct BuildOptions {
  double fps = 30.0;
  bool fps_given = false;  // else a manifest's fps wins
  std::string asf;
  std::optional<double> scale;
  std::string up_axis;  // "y" or "z" for every clip; empty: chosen per file (motion/up_axis.h)
  std::string travel = "auto";  // "auto", "root" or "feet" (motion/in_place.h)
  double input_fps = 0.0;
  bool keep_rest_frames = false;  // keep a BVH converter's leading rest/T-pose frames (motion/rest_frame.h) and
                                  // the frames a capture glitch cuts off clips' ends (motion/glitched_ends.h), and
                                  // clips whole where glitches within cut them (motion/capture_glitches.h)
  std::string cmu_index;
  bool no_cmu_tags = false;
  bool no_name_tags = false;  // no tags from clip names (cmu_tags.h clip_name_tags)
  bool whole_clip_tags = false;  // walk and run from descriptions on whole clips (travel_tags.h)
  bool no_loops = false;  // clips that loop are not played on past their end (motion/loop.h)
  std::string mirror = "auto";  // "auto", "on" or "off": each clip mirrored left to right too (motion/mirror.h)
  std::string feet;  // LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,RIGHT_TOE (skeleton/foot_joints.h)
  std::string cloud = "rings";
  PointCloudSettings cloud_settings;
  std::vector<std::string> joint_weights;  // NAME=WEIGHT
  DistanceSettings distance;  // its tile_frames is set from tile_frames
  int tile_frames = 0;        // 0: 1024 for the exhaustive stage, from the window for the pruned one
  bool exhaustive = false;
  int pruned_from = BuildSettings{}.pruned_from_frames;
  std::string taper = "uniform";
  TransitionSettings transitions;
  std::string threshold = "auto";  // auto, D, or an RMS distance with "cm"
  std::optional<double> quantile;  // given: the threshold is this quantile of all pairs
  ThresholdChoiceSettings choice;
  PathCheckSettings path_check;
  bool no_path_check = false;
  bool no_path_check_mirror = false;  // the probe alone (PathCheckSettings::mirrored off)
  TransitionSpacing spacing;
  int continuation_radius = -1;
  bool ignore_tags = false;
  BridgeSettings bridges;
  double max_bridge_cm = 0.0;  // RMS point distance above which no bridge is made; 0: no cap
  std::vector<std::string> connect_tags;
  BuildExports exports;
  SharedSearchSettings shared;  // --checkpoint, --checkpoint-pairs
};

// The settings the options give (validated), or the first option that is not understood.
Result<BuildSettings> build_settings_from(const BuildOptions& options);

// Fails unless `path` names a graph file (ends in .mgraph).
Status check_graph_output(const std::string& path);

}  // namespace mg
