// Path-following error (Kovar et al. 2002, section 5): for each built-in shape (floor_path.h),
// the motion path synthesis makes and how far its root strays from the path: the mean and
// largest distance to the nearest point of the path over its frames, as edited onto the path
// (path_edit.h) and as the graph played it, and whether it reached the path's end.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "motiongraph/synthesis/path_synthesis.h"

namespace mg {

struct PathErrorRow {
  std::string shape;            // as given, e.g. "circle:5"
  double path_length_m = 0.0;
  double arc_covered_m = 0.0;   // the furthest the motion got along the path
  double end_distance_m = 0.0;  // from its last root to the path's end
  double mean_deviation_m = 0.0;
  double max_deviation_m = 0.0;
  double graph_mean_deviation_m = 0.0;  // before the edit
  double graph_max_deviation_m = 0.0;
  bool reached_end = false;
  int frames = 0;
  int searches = 0;
  int budget_exhausted = 0;
};

// The shapes used by default: line:20, circle:5, figure8:4, s-curve:100.
std::vector<std::string> default_evaluation_shapes();

// Fails on a shape make_shape rejects or a synthesis error.
Result<std::vector<PathErrorRow>> measure_path_errors(const SynthesisContext& context, std::span<const std::string> shapes,
                                                      const PathSynthesisSettings& settings = {});

}  // namespace mg
