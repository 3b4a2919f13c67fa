// The forward axis: square to the hips on every frame of a rig whose hips move with its root,
// unmoved by clips that travel across the body (where the travel axis turns), its sign the
// travel's whatever the feet are called, the travel axis without feet, and the same facing
// through another converter's rig of the same capture.
#include "motiongraph/synthesis/facing.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "motiongraph/skeleton/foot_joints.h"
#include "motiongraph/skeleton/rotation.h"
#include "test_data.h"

namespace mg {
namespace {

double angle_deg(const Vec2& a, const Vec2& b) {
  return std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b))) * 180.0 / std::numbers::pi;
}

double angle_deg(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(a.dot(b), -1.0, 1.0)) * 180.0 / std::numbers::pi; }

// A database of the clips, resampled to 30 fps, on the first one's skeleton.
MotionDatabase database_of(std::vector<Clip> clips) {
  MotionDatabase db;
  db.fps = 30.0;
  db.skeletons.push_back(clips.front().skeleton);
  for (Clip& clip : clips) {
    DatabaseClip entry;
    entry.name = clip.name;
    entry.first_frame = db.frame_count();
    entry.motion = *resample(clip.motion, db.fps);
    entry.frame_count = entry.motion.frame_count;
    db.clips.push_back(std::move(entry));
  }
  return db;
}

// The clip's root carried across its body: its floor travel turned by `yaw` about where it
// starts, its rotations as captured (a walk becomes a sidestep at 90 degrees).
void turn_travel(DatabaseClip& clip, double yaw) {
  const Quat turn = axis_rotation(Axis::kY, yaw);
  const Vec3 start = clip.motion.translations(0)[0];
  for (int f = 0; f < clip.frame_count; ++f) {
    Vec3& p = clip.motion.translations(f)[0];
    const Vec3 floor(p.x() - start.x(), 0.0, p.z() - start.z());
    const Vec3 turned = turn * floor;
    p = Vec3(start.x() + turned.x(), p.y(), start.z() + turned.z());
  }
}

TEST(ForwardAxis, SquareToTheHipsOnEveryFrameAndAlongAWalk) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc"});
  const Vec3 axis = learn_forward_axes(db)[0];
  const Skeleton& skeleton = db.skeletons[0];
  const std::optional<int> left = skeleton.find("lfemur"), right = skeleton.find("rfemur");
  ASSERT_TRUE(left && right);
  std::vector<Vec3> positions(static_cast<size_t>(skeleton.joint_count()));
  std::vector<Quat> rotations(positions.size());
  double worst = 0.0, along = 0.0;
  int moving = 0;
  for (const DatabaseClip& clip : db.clips) {
    std::vector<Vec2> roots;
    for (int f = 0; f < clip.frame_count; ++f) roots.emplace_back(clip.motion.translations(f)[0].x(), clip.motion.translations(f)[0].z());
    for (int f = 0; f < clip.frame_count; ++f) {
      forward_kinematics(skeleton, clip.motion, f, positions, rotations);
      const Vec3 across = positions[static_cast<size_t>(*right)] - positions[static_cast<size_t>(*left)];
      const Vec2 facing = facing_on_floor(clip.motion.rotations(f)[0], axis);
      const Vec2 square = Vec2(across.z(), -across.x()).normalized();  // up x (right - left)
      worst = std::max(worst, angle_deg(facing, square));
      const Vec2 travel = travel_direction(roots, f, kTravelLookaheadFrames, db.fps, kMovingSpeedMps);
      if (travel.isZero()) continue;
      along += travel.dot(facing);
      ++moving;
    }
  }
  // The root tilts a little with each step: its floor projection turns by a fraction of a degree.
  EXPECT_LT(worst, 1.0);
  ASSERT_GT(moving, 100);
  EXPECT_GT(along / moving, 0.95);  // the walks go where they face
}

TEST(ForwardAxis, UnmovedByClipsThatTravelAcrossTheBody) {
  const MotionDatabase walk = test::small_database({"cmu/16/16_15.amc"});
  MotionDatabase mixed = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_15.amc", "cmu/16/16_15.amc"});
  turn_travel(mixed.clips[1], std::numbers::pi / 2);
  turn_travel(mixed.clips[2], std::numbers::pi / 2);
  // Two sidesteps to one walk pull the mean travel 60 degrees round ...
  EXPECT_GT(angle_deg(learn_travel_axes(mixed)[0], learn_travel_axes(walk)[0]), 45.0);
  // ... the hips face where they did.
  EXPECT_LT(angle_deg(learn_forward_axes(mixed)[0], learn_forward_axes(walk)[0]), 1e-6);
}

TEST(ForwardAxis, ItsSignIsTheTravelsWhateverTheFeetAreCalled) {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  const Vec3 axis = learn_forward_axes(db)[0];
  // The feet named the other way round: the hips' line reversed, the sign from the travel.
  db.foot_names = FootJointNames{"rfoot", "rtoes", "lfoot", "ltoes"};
  EXPECT_LT(angle_deg(learn_forward_axes(db)[0], axis), 1e-6);
  // A walk played backwards (its root turned about while it travels on): the hips face back,
  // so the axis is the other way round in the root's frame, and the facing is the travel's.
  db.foot_names = {};
  const Quat about = axis_rotation(Axis::kY, std::numbers::pi);
  for (int f = 0; f < db.clips[0].frame_count; ++f) db.clips[0].motion.rotations(f)[0] = about * db.clips[0].motion.rotations(f)[0];
  EXPECT_LT(angle_deg(learn_forward_axes(db)[0], -axis), 1e-6);
}

TEST(ForwardAxis, TheTravelAxisWhenTheFeetCannotBeFound) {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc"});
  db.foot_names = FootJointNames{"no_such_ankle", "", "", ""};
  ASSERT_FALSE(find_foot_joints(db.skeletons[0], db.foot_names));
  EXPECT_EQ(learn_forward_axes(db)[0], learn_travel_axes(db)[0]);
}

TEST(ForwardAxis, TheSameFacingThroughAnotherConvertersRig) {
  // 16_01 as CMU's ASF/AMC and as a BVH converter wrote it (its own joint frames, ASF length
  // units, 120 fps labelled 30: data/README.md).
  const MotionDatabase amc = database_of({test::load_data_clip("cmu/16/16_01.amc")});
  const MotionDatabase bvh = database_of({test::load_data_clip("bvh/16_01.bvh", std::nullopt, 120.0)});
  const Vec3 amc_axis = learn_forward_axes(amc)[0], bvh_axis = learn_forward_axes(bvh)[0];
  const int frames = std::min(amc.clips[0].frame_count, bvh.clips[0].frame_count);
  ASSERT_GT(frames, 50);
  double worst = 0.0;
  for (int f = 0; f < frames; ++f) {
    worst = std::max(worst, angle_deg(facing_on_floor(amc.clips[0].motion.rotations(f)[0], amc_axis),
                                      facing_on_floor(bvh.clips[0].motion.rotations(f)[0], bvh_axis)));
  }
  EXPECT_LT(worst, 0.01);  // the converter placed the hips where the ASF has them
}

}  // namespace
}  // namespace mg
