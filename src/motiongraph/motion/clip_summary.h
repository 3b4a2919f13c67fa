// What `motiongraph info` reports about a clip: sizes, timing, and where it moves on the
// floor (xz extent of all joints, metres), plus the distance the root travels.
#pragma once

#include "motiongraph/motion/motion.h"

namespace mg {

struct ClipSummary {
  int joints = 0;        // joints with rotations
  int end_sites = 0;
  int frames = 0;
  double fps = 0.0;
  double duration_s = 0.0;
  double floor_min_x_m = 0.0, floor_max_x_m = 0.0;
  double floor_min_z_m = 0.0, floor_max_z_m = 0.0;
  double min_height_m = 0.0, max_height_m = 0.0;
  double root_path_m = 0.0;  // length of the root's floor trajectory
};

ClipSummary summarize(const Skeleton& skeleton, const Motion& motion);

}  // namespace mg
