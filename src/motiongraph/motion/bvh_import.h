// BVH -> Skeleton + Motion, with BVH semantics: a joint is placed at OFFSET from its parent
// (or at its position channels, which replace OFFSET component by component, as Blender and
// MotionBuilder read them), then rotated by its rotation channels composed in the listed
// order ("Zrotation Xrotation Yrotation" = Rz * Rx * Ry). Each joint keeps its own order.
//
// Joints: the file's joints in file order, then its End Sites ("<parent>_end").
// Lengths are multiplied by `metres_per_unit` (BVH carries no unit; CMU conversions use the
// ASF unit, 0.056444 m, others centimetres, 0.01).
#pragma once

#include "motiongraph/core/error.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct BvhImportSettings {
  double metres_per_unit = 1.0;
  double fps_override = 0.0;     // > 0: use instead of 1 / Frame Time (files with a wrong one)
  bool drop_rest_frames = true;  // drop leading rest or T-pose frames a converter added
                                 // (see rest_frame.h)

  Status validate() const;
};

// 1 / frame time, snapped to a whole number of frames per second when within 1e-4 of one.
double fps_from_frame_time(double frame_time_s);

Result<Clip> clip_from_bvh(const BvhDocument& bvh, const BvhImportSettings& settings);

}  // namespace mg
