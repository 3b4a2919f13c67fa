// Which way a character faces. Skeletons do not say which of the root's axes points forward
// (CMU's ASF, BVH converters and other studios all differ), so it is learnt from the data:
// the forward axis of a skeleton is the mean, in the root's own frame, of the horizontal
// direction of travel over the frames of its clips that move (root faster than 0.3 m/s over
// the next 10 frames, as in the seed's self-consistency measure). Most capture walks forwards,
// so the mean points forwards; a skeleton with no moving frame gets the root's +z axis.
// A frame's facing is that axis turned by the root's world rotation, projected on the floor.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "motiongraph/database/motion_database.h"

namespace mg {

using Vec2 = Eigen::Vector2d;  // (x, z) on the floor, metres

// The seed's self-consistency measure looks this many frames ahead for the direction of
// travel, and a root slower than this has none.
constexpr int kTravelLookaheadFrames = 10;
constexpr double kMovingSpeedMps = 0.3;

// One axis per skeleton of db, unit length, in the root joint's frame.
std::vector<Vec3> learn_forward_axes(const MotionDatabase& db);

// The unit facing direction on the floor of a root world rotation; (0, 0) when the axis is
// vertical.
Vec2 facing_on_floor(const Quat& root_world_rotation, const Vec3& forward_axis);

// Direction of travel over the next `lookahead` frames: the unit floor direction from the
// root at frame i to the root at frame i + lookahead, or (0, 0) when it moves less than
// min_speed_mps (floor positions `roots`, frames per second `fps`).
Vec2 travel_direction(const std::vector<Vec2>& roots, int i, int lookahead, double fps, double min_speed_mps);

}  // namespace mg
