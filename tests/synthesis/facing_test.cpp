// The forward axis: square to the hips on every frame of a rig whose hips move with its root,
// unmoved by clips that travel across the body (where the travel axis turns), its sign the
// travel's whatever the feet are called, the travel axis without feet, and the same facing
// through another converter's rig of the same capture.
#include "motiongraph/synthesis/facing.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "motiongraph/skeleton/foot_joints.h"
#include "motiongraph/skeleton/rotation.h"
#include "synthesis/subject16_graph.h"
#include "test_data.h"

namespace mg {
namespace {

double angle_deg(const Vec2& a, const Vec2& b) {
  return std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b))) * 180.0 / std::numbers::pi;
}


// A database of the clips, resampled to 30 fps, each on a skeleton of its own.
MotionDatabase database_of(std::vector<Clip> clips) {
  MotionDatabase db;
  db.fps = 30.0;
  for (Clip& clip : clips) {
    db.skeletons.push_back(clip.skeleton);
    DatabaseClip entry;
    entry.skeleton = static_cast<int>(db.skeletons.size()) - 1;
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
  EXPECT_LT(learn_travel_axes(mixed)[0].dot(learn_travel_axes(walk)[0]), std::cos(45.0 * std::numbers::pi / 180.0));
  // ... the hips face where they did.
  EXPECT_LT((learn_forward_axes(mixed)[0] - learn_forward_axes(walk)[0]).norm(), 1e-9);
}

TEST(ForwardAxis, ItsSignIsTheTravelsWhateverTheFeetAreCalled) {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  const Vec3 axis = learn_forward_axes(db)[0];
  const Vec3 travel = learn_travel_axes(db)[0];
  // What `inspect` reports: the hips it faces square to, not turned about.
  const ForwardAxisChoice as_named = choose_forward_axis(db, 0, travel);
  EXPECT_EQ(as_named.axis, axis);
  EXPECT_EQ(as_named.travel_axis, travel);
  EXPECT_EQ(db.skeletons[0].joint(as_named.left_hip).name, "lfemur");
  EXPECT_EQ(db.skeletons[0].joint(as_named.right_hip).name, "rfemur");
  EXPECT_FALSE(as_named.turned_about);
  EXPECT_TRUE(as_named.why_not_hips.empty());
  // The feet named the other way round: the hips' line reversed, the sign from the travel.
  db.foot_names = FootJointNames{"rfoot", "rtoes", "lfoot", "ltoes"};
  EXPECT_LT((learn_forward_axes(db)[0] - axis).norm(), 1e-9);
  const ForwardAxisChoice swapped = choose_forward_axis(db, 0, travel);
  EXPECT_EQ(db.skeletons[0].joint(swapped.left_hip).name, "rfemur");
  EXPECT_TRUE(swapped.turned_about);
  // A walk played backwards (its root turned about while it travels on): the hips face back,
  // so the axis is the other way round in the root's frame, and the facing is the travel's.
  db.foot_names = {};
  const Quat about = axis_rotation(Axis::kY, std::numbers::pi);
  for (int f = 0; f < db.clips[0].frame_count; ++f) db.clips[0].motion.rotations(f)[0] = about * db.clips[0].motion.rotations(f)[0];
  EXPECT_LT((learn_forward_axes(db)[0] + axis).norm(), 1e-9);
}

TEST(ForwardAxis, TheTravelAxisWhenTheFeetCannotBeFound) {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc"});
  db.foot_names = FootJointNames{"no_such_ankle", "", "", ""};
  ASSERT_FALSE(find_foot_joints(db.skeletons[0], db.foot_names));
  EXPECT_EQ(learn_forward_axes(db)[0], learn_travel_axes(db)[0]);
  const ForwardAxisChoice choice = choose_forward_axis(db, 0, learn_travel_axes(db)[0]);
  EXPECT_EQ(choice.axis, learn_travel_axes(db)[0]);
  EXPECT_EQ(choice.left_hip, -1);
  EXPECT_NE(choice.why_not_hips.find("no_such_ankle"), std::string::npos) << choice.why_not_hips;
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

// A still pose (no frame moves, so the hips' own sign) whose hip joints are turned: ASF's
// lhipjoint and rhipjoint, bones of zero length at the root, carry the hips where forward
// kinematics puts them, and the axis is square to that.
TEST(ForwardAxis, SquareToTheHipsWhereTheJointsAboveThemAreTurned) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const Skeleton& skeleton = clip.skeleton;
  const int lhip = *skeleton.find("lhipjoint"), rhip = *skeleton.find("rhipjoint");
  const Motion pose = clip.motion;
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    for (int j = 0; j < skeleton.joint_count(); ++j) clip.motion.rotations(f)[j] = pose.rotations(40)[j];
    clip.motion.translations(f)[0] = pose.translations(40)[0];
    clip.motion.rotations(f)[lhip] = axis_rotation(Axis::kY, 0.4) * axis_rotation(Axis::kX, 0.3);
    clip.motion.rotations(f)[rhip] = axis_rotation(Axis::kY, 0.4) * axis_rotation(Axis::kZ, -0.2);
  }
  const MotionDatabase db = database_of({clip});
  std::vector<Vec3> positions(static_cast<size_t>(skeleton.joint_count()));
  std::vector<Quat> rotations(positions.size());
  forward_kinematics(skeleton, db.clips[0].motion, 0, positions, rotations);
  const Vec3 across = positions[static_cast<size_t>(*skeleton.find("rfemur"))] - positions[static_cast<size_t>(*skeleton.find("lfemur"))];
  const Vec2 facing = facing_on_floor(db.clips[0].motion.rotations(0)[0], learn_forward_axes(db)[0]);
  EXPECT_LT((facing - Vec2(across.z(), -across.x()).normalized()).norm(), 1e-9);
}

// A rig of another shape: the legs hang from a pelvis below the root, turned 20 degrees about
// the vertical from where the root's +z points; it walks along the root's +z. The hips face 20
// degrees round (the pelvis' +z), the travel axis along the walk.
TEST(ForwardAxis, TheLegsHangingFromAPelvisTurnedBelowTheRoot) {
  std::string bvh =
      "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
      " JOINT Pelvis\n {\n  OFFSET 0 -0.05 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n";
  for (const char* side : {"Left", "Right"}) {
    bvh += std::string("  JOINT ") + side + "UpLeg\n  {\n   OFFSET " + (side[0] == 'L' ? "0.1" : "-0.1") +
           " 0 0\n   CHANNELS 3 Zrotation Xrotation Yrotation\n   JOINT " + side +
           "Leg\n   {\n    OFFSET 0 -0.45 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n    JOINT " + side +
           "Foot\n    {\n     OFFSET 0 -0.45 0\n     CHANNELS 3 Zrotation Xrotation Yrotation\n"
           "     End Site\n     {\n      OFFSET 0 -0.05 0.15\n     }\n    }\n   }\n  }\n";
  }
  bvh += " }\n JOINT Spine\n {\n  OFFSET 0 0.5 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n"
         "  End Site\n  {\n   OFFSET 0 0.2 0\n  }\n }\n}\nMOTION\nFrames: 90\nFrame Time: 0.0333333\n";
  for (int f = 0; f < 90; ++f) {
    char line[160];
    std::snprintf(line, sizeof line, "0 1.0 %.4f 0 0 0 0 0 20 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n", 0.04 * f);
    bvh += line;
  }
  BvhImportSettings settings;
  settings.metres_per_unit = 1.0;
  settings.up_axis = UpAxis::kY;
  const MotionDatabase db = database_of({test::import_bvh(bvh, settings)});
  const Quat root = db.clips[0].motion.rotations(0)[0];
  const double turned = 20.0 * std::numbers::pi / 180.0;
  EXPECT_LT((facing_on_floor(root, learn_forward_axes(db)[0]) - Vec2(std::sin(turned), std::cos(turned))).norm(), 1e-9);
  EXPECT_LT((facing_on_floor(root, learn_travel_axes(db)[0]) - Vec2(0.0, 1.0)).norm(), 1e-9);
}

// Each skeleton of a library its own axis, from its own clips.
TEST(ForwardAxis, EachSkeletonItsOwn) {
  const Clip amc = test::load_data_clip("cmu/16/16_15.amc"), bvh = test::load_data_clip("bvh/131_01.bvh");
  const std::vector<Vec3> both = learn_forward_axes(database_of({amc, bvh}));
  ASSERT_EQ(both.size(), 2u);
  EXPECT_LT((both[0] - learn_forward_axes(database_of({amc}))[0]).norm(), 1e-12);
  EXPECT_LT((both[1] - learn_forward_axes(database_of({bvh}))[0]).norm(), 1e-12);
  EXPECT_GT((both[0] - both[1]).norm(), 0.1);  // rigs of other root frames
}

// Synthesis faces with the hips and starts paths with the travel axis, the target skeleton's.
TEST(ForwardAxis, TheSynthesisContextHoldsBothAxesOfItsSkeleton) {
  const SynthesisContext& context = test::subject16().context();
  const int target = context.assembler.target_skeleton();
  EXPECT_EQ(context.tracks.forward_axis, learn_forward_axes(*context.db)[static_cast<size_t>(target)]);
  EXPECT_EQ(context.tracks.travel_axis, learn_travel_axes(*context.db)[static_cast<size_t>(target)]);
  EXPECT_NE(context.tracks.forward_axis, context.tracks.travel_axis);
}

}  // namespace
}  // namespace mg
