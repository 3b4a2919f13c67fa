// BVH -> Skeleton + Motion, with BVH semantics: a joint is placed at OFFSET from its parent
// (or at its position channels, which replace OFFSET component by component, as Blender and
// MotionBuilder read them), then rotated by its rotation channels composed in the listed
// order ("Zrotation Xrotation Yrotation" = Rz * Rx * Ry). Each joint keeps its own order.
//
// Joints: the file's joints in file order, then its End Sites ("<parent>_end").
// Lengths are multiplied by `metres_per_unit` (BVH carries no unit; CMU conversions use the
// ASF unit, 0.056444 m, others centimetres, 0.01). Without it, the unit is chosen from the
// figure's size (length_unit.h) and reported in Clip::detected_unit.
//
// A file whose figure stands along z (3ds Max and other z-up tools) is turned y up, every world
// position turned by one rotation (up_axis.h); `up_axis` says which without looking, and
// Clip::detected_up_axis reports the choice when it was made by looking.
//
// A static root above a travelling joint (the hips) is folded away so that the hips are joint
// 0 and carry the floor position and heading (trajectory_joint.h); the skeleton keeps the
// folded joints as its static_ancestors. Tolerance: kStaticRootFraction of the figure's size.
#pragma once

#include <optional>

#include "motiongraph/core/error.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/motion/up_axis_choice.h"

namespace mg {

struct BvhImportSettings {
  std::optional<double> metres_per_unit;  // nullopt: chosen from the figure's size
  double fps_override = 0.0;     // > 0: use instead of 1 / Frame Time (files with a wrong one)
  bool drop_rest_frames = true;  // drop leading rest or T-pose frames a converter added
                                 // (see rest_frame.h)
  bool fold_static_root = true;  // the hips as joint 0 below a static root (see above)
  std::optional<UpAxis> up_axis;  // nullopt: chosen from the figure's shape (up_axis.h)

  Status validate() const;
};

// 1 / frame time, snapped to a whole number of frames per second when within 1e-4 of one.
double fps_from_frame_time(double frame_time_s);

// The rates a file of motion (two frames or more) may give by its Frame Time without
// fps_override: under 1 frame a second or over 10 000 is no capture's (a frame time written in
// milliseconds, 8.3333 for 120 fps, read 994 frames as 2.3 hours), refused naming the line.
constexpr double kMinBvhFps = 1.0;
constexpr double kMaxBvhFps = 10000.0;

Result<Clip> clip_from_bvh(const BvhDocument& bvh, const BvhImportSettings& settings);

}  // namespace mg
