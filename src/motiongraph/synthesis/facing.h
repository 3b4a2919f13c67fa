// Which way a character faces. Skeletons do not say which of the root's axes points forward
// (CMU's ASF, BVH converters and other studios all differ), so it is learnt from the data.
//
// The forward axis of a skeleton is where its hips face: square to the line from the left hip to
// the right one, on the floor, averaged over every frame of its clips and expressed in the root
// joint's frame. The hips are where the legs start: on the chain from the joint where the two
// legs part down to each ankle (skeleton/foot_joints.h finds the ankles), the first joint set off
// from it (ASF's hipjoint, a bone that starts at the root, is passed over); each frame weighs
// as far as its hips lie apart on the floor. Its sign is up x (right - left), turned about when
// the skeleton's moving frames travel against it (a mean cosine below -0.2: a mirrored rig or
// swapped feet still face forwards; a library of sidesteps keeps the hips' sign). A walk's
// direction of travel swings with its steps, and sidesteps, dance and pivots travel across the
// body: a library's mean travel direction in the root's frame can be 12 degrees off its walking
// (CMU 05), its hips are not.
//
// A skeleton whose feet cannot be found, or whose hips lie one above the other, gets its
// travel axis instead: the mean, in the root's frame, of the horizontal direction of travel
// over the frames of its clips that move (root faster than 0.3 m/s over the next 10 frames, as
// in the seed's self-consistency measure), or the root's +z axis with no moving frame. The
// self-consistency measure (evaluation/self_consistency.h) uses the travel axis itself, and a
// path's start lines it up with the path (SynthesisContext::placement_heading): the root goes
// the path's way.
//
// A frame's facing is that axis turned by the root's world rotation, projected on the floor.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "motiongraph/database/motion_database.h"

namespace mg {

using Vec2 = Eigen::Vector2d;  // (x, z) on the floor, metres

// The seed's self-consistency measure looks this many frames ahead for the direction of
// travel, and a root slower than this has none.
constexpr int kTravelLookaheadFrames = 10;
constexpr double kMovingSpeedMps = 0.3;

// One axis per skeleton of db, unit length, in the root joint's frame: where its hips face.
std::vector<Vec3> learn_forward_axes(const MotionDatabase& db);

// How a skeleton's forward axis was found, for a user to check a rig by (`inspect`).
struct ForwardAxisChoice {
  Vec3 axis = Vec3::UnitZ();         // learn_forward_axis's
  Vec3 travel_axis = Vec3::UnitZ();  // the one given: its mean travel, in the root's frame
  int left_hip = -1, right_hip = -1; // the joints it faces square to; -1: none (the travel axis)
  bool turned_about = false;         // the hips' up x (right - left) turned: the moving frames went against it
  std::string why_not_hips;          // when the travel axis stands in
};
ForwardAxisChoice choose_forward_axis(const MotionDatabase& db, int skeleton, const Vec3& travel_axis);
// The same for skeleton `skeleton` alone, given its travel axis (the answer without hips).
Vec3 learn_forward_axis(const MotionDatabase& db, int skeleton, const Vec3& travel_axis);

// One axis per skeleton of db, unit length, in the root joint's frame: its mean direction of
// travel.
std::vector<Vec3> learn_travel_axes(const MotionDatabase& db);

// Where a clip's skeleton faces, learnt from that clip alone: square to its hips as above, but
// signed by its toes (the mean of ankle -> toe in the root's frame points forward), since one
// clip's travel may well go backwards (a backwards walk, or a jump whose few moving frames
// settle the sign); the travel axis without hips, as above; +z when its root has no translation
// (it has no travel). Its feet found by name unless `feet` names them.
Vec3 learn_clip_forward_axis(const Skeleton& skeleton, const Motion& motion, const FootJointNames& feet = {});

// The unit facing direction on the floor of a root world rotation; (0, 0) when the axis is
// vertical.
Vec2 facing_on_floor(const Quat& root_world_rotation, const Vec3& forward_axis);
// Degrees (0 to 180) between that facing and a unit floor `direction`: how far off it a character
// stands.
double facing_off_deg(const Quat& root_world_rotation, const Vec3& forward_axis, const Vec2& direction);

// Direction of travel over the next `lookahead` frames: the unit floor direction from the
// root at frame i to the root at frame i + lookahead, or (0, 0) when it moves less than
// min_speed_mps (floor positions `roots`, frames per second `fps`).
Vec2 travel_direction(const std::vector<Vec2>& roots, int i, int lookahead, double fps, double min_speed_mps);

}  // namespace mg
