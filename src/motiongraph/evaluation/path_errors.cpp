// Path-following error on built-in shapes.
#include "motiongraph/evaluation/path_errors.h"

namespace mg {

std::vector<std::string> default_evaluation_shapes() { return {"line:20", "circle:5", "figure8:4", "s-curve:100"}; }

Result<std::vector<PathErrorRow>> measure_path_errors(const SynthesisContext& context, std::span<const std::string> shapes,
                                                      const PathSynthesisSettings& settings) {
  std::vector<PathErrorRow> rows;
  for (const std::string& shape : shapes) {
    auto path = make_shape(shape);
    if (!path) return path.error();
    auto result = synthesize_path(context, *path, settings);
    if (!result) return result.error();
    PathErrorRow row;
    row.shape = shape;
    row.path_length_m = result->path_length_m;
    row.arc_covered_m = result->arc_covered_m;
    row.end_distance_m = result->end_distance_m;
    row.mean_deviation_m = result->mean_deviation_m;
    row.max_deviation_m = result->max_deviation_m;
    row.graph_mean_deviation_m = result->graph_mean_deviation_m;
    row.graph_max_deviation_m = result->graph_max_deviation_m;
    row.reached_end = result->reached_end;
    row.frames = result->motion.frame_count;
    row.searches = result->searches;
    row.budget_exhausted = result->budget_exhausted;
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace mg
