#include "motiongraph/motion/mirror.h"

#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

using Names = std::vector<std::string>;

bool has(const Names& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(Mirror, NamesOfTheOtherSide) {
  EXPECT_TRUE(has(mirrored_names("LeftUpLeg"), "RightUpLeg"));
  EXPECT_TRUE(has(mirrored_names("RightUpLeg"), "LeftUpLeg"));
  EXPECT_TRUE(has(mirrored_names("mixamorig:LeftArm"), "mixamorig:RightArm"));
  EXPECT_TRUE(has(mirrored_names("LEFT_FOOT"), "RIGHT_FOOT"));
  EXPECT_TRUE(has(mirrored_names("leftEye"), "rightEye"));
  EXPECT_TRUE(has(mirrored_names("lfemur"), "rfemur"));
  EXPECT_TRUE(has(mirrored_names("rShldr"), "lShldr"));
  EXPECT_TRUE(has(mirrored_names("LHipJoint"), "RHipJoint"));
  EXPECT_TRUE(has(mirrored_names("L_Hip"), "R_Hip"));
  EXPECT_TRUE(has(mirrored_names("Hip_L"), "Hip_R"));
  EXPECT_TRUE(has(mirrored_names("hip.R"), "hip.L"));
  EXPECT_TRUE(has(mirrored_names("Bip01 L Thigh"), "Bip01 R Thigh"));
  EXPECT_TRUE(has(mirrored_names("ThighL"), "ThighR"));
  // Letters inside a word are no side: "Hips" and "upperarm" name no "Hipr" or "upperalm".
  EXPECT_TRUE(mirrored_names("Hips").empty());
  EXPECT_FALSE(has(mirrored_names("upperarm"), "upperalm"));
  EXPECT_FALSE(has(mirrored_names("LeftUpLeg"), "LeftUpLeg"));
  // Tags and clip names: the words only, every one.
  EXPECT_EQ(mirrored_side_words("turn_left"), "turn_right");
  EXPECT_EQ(mirrored_side_words("RightStep_LeftStep"), "LeftStep_RightStep");
  EXPECT_EQ(mirrored_side_words("LEFT"), "RIGHT");
  EXPECT_EQ(mirrored_side_words("walk"), "walk");
  EXPECT_EQ(mirrored_side_words("l_turn"), "l_turn");
}

// A figure whose rest pose is its own mirror image across x = 0: a root that travels, a spine
// and head, two legs to their end sites and two arms, named as `left` and `right` say; its knees
// translating (six channels) when asked.
Skeleton symmetric_figure(const std::string& left, const std::string& right, bool knees_translate = false,
                          double body_off_root_m = 0.0) {
  std::vector<JointDef> joints;
  auto add = [&](const std::string& name, int parent, Vec3 offset, bool end = false) {
    JointDef j;
    j.name = name;
    j.parent = parent;
    j.rest_offset_m = offset;
    j.end_site = end;
    j.animated_translation = parent < 0 || (knees_translate && name.ends_with("Leg") && !name.ends_with("UpLeg"));
    joints.push_back(j);
    return static_cast<int>(joints.size()) - 1;
  };
  const int root = add("Hips", -1, Vec3(0.0, 0.95, 0.0));
  const Vec3 off(body_off_root_m, 0.0, 0.0);  // the body beside its root
  const int spine = add("Spine", root, Vec3(0.0, 0.3, 0.02) + off);
  add("Head", spine, Vec3(0.0, 0.35, 0.0));
  for (const auto& [side, x] : {std::pair{left, 1.0}, std::pair{right, -1.0}}) {
    const int hip = add(side + "UpLeg", root, Vec3(0.1 * x, -0.05, 0.0) + off);
    const int knee = add(side + "Leg", hip, Vec3(0.02 * x, -0.42, 0.01));
    const int ankle = add(side + "Foot", knee, Vec3(0.0, -0.42, -0.03));
    add(side + "Foot_end", ankle, Vec3(0.01 * x, -0.05, 0.14), true);
    const int shoulder = add(side + "Arm", spine, Vec3(0.18 * x, 0.25, 0.0));
    add(side + "Hand", shoulder, Vec3(0.55 * x, 0.0, -0.02));
  }
  return Skeleton(joints);
}

Motion random_motion(const Skeleton& skeleton, int frames, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Motion motion(skeleton, frames, 30.0);
  for (int f = 0; f < frames; ++f) {
    for (Quat& q : motion.rotations(f)) q = Quat(u(random) + 1.5, u(random), u(random), u(random)).normalized();
    for (Vec3& t : motion.translations(f)) t = Vec3(3.0 * u(random), 1.0 + 0.1 * u(random), 3.0 * u(random));
  }
  return motion;
}

// Every joint of the mirrored motion stands where its partner's mirror image does (the root
// itself aside when the body lies beside it: it stands as far off the body on the other side).
TEST(Mirror, EachJointStandsAtItsPartnersMirrorImage) {
  for (const auto& [left, right, knees, off] :
       {std::tuple{"Left", "Right", false, 0.0}, std::tuple{"l", "r", false, 0.0}, std::tuple{"L_", "R_", true, 0.0},
        std::tuple{"Left", "Right", true, 0.04}}) {
    const Skeleton skeleton = symmetric_figure(left, right, knees, off);
    auto map = mirror_map(skeleton);
    ASSERT_TRUE(map) << map.error().message;
    EXPECT_EQ(map->pairs, 6);  // six joints a side, the foot's end site too
    EXPECT_NEAR(std::abs(map->normal.x()), 1.0, 1e-12);
    EXPECT_LT(map->asymmetry_m, 1e-12);
    EXPECT_NEAR(map->plane_offset_m * map->normal.x(), off, 1e-12);
    const Motion motion = random_motion(skeleton, 7, 11);
    const Motion mirrored = mirror_motion(skeleton, *map, motion);
    const std::vector<Vec3> at = world_positions(skeleton, motion), image = world_positions(skeleton, mirrored);
    const int n = skeleton.joint_count();
    for (int f = 0; f < motion.frame_count; ++f) {
      for (int j = off == 0.0 ? 0 : 1; j < n; ++j) {
        const Vec3 p = at[static_cast<size_t>(f * n + j)];
        const Vec3 q = image[static_cast<size_t>(f * n + map->partner[static_cast<size_t>(j)])];
        EXPECT_NEAR((q - Vec3(-p.x(), p.y(), p.z())).norm(), 0.0, 1e-12) << skeleton.joint(j).name << " frame " << f;
      }
    }
    // ... and mirrored twice, it is the motion again.
    const Motion twice = mirror_motion(skeleton, *map, mirrored);
    for (size_t i = 0; i < motion.local_rotations.size(); ++i) {
      EXPECT_NEAR(twice.local_rotations[i].angularDistance(motion.local_rotations[i]), 0.0, 1e-12);
    }
    for (size_t i = 0; i < motion.local_translations_m.size(); ++i) {
      EXPECT_NEAR((twice.local_translations_m[i] - motion.local_translations_m[i]).norm(), 0.0, 1e-12);
    }
  }
}

// Real captures: CMU's ASF (lfemur, rfemur), a converter's BVH (LeftUpLeg) and another's (rThigh,
// leftEye). Their bones differ a little left to right, so the image is near, not exact; a walk
// turning left turns right mirrored.
TEST(Mirror, CapturedClipsMirrorAndAWalkTurningLeftTurnsRight) {
  struct Case {
    const char* file;
    const char* left_joint;
    const char* right_joint;
  };
  for (const Case& c : {Case{"cmu/16/16_17.amc", "lfemur", "rfemur"}, Case{"bvh/111_36.bvh", "LeftUpLeg", "RightUpLeg"},
                        Case{"bvh/07_01.bvh", "lThigh", "rThigh"}}) {
    SCOPED_TRACE(c.file);
    const Clip clip = test::load_data_clip(c.file);
    auto map = mirror_map(clip.skeleton);
    ASSERT_TRUE(map) << map.error().message;
    const int l = *clip.skeleton.find(c.left_joint), r = *clip.skeleton.find(c.right_joint);
    EXPECT_EQ(map->partner[static_cast<size_t>(l)], r);
    EXPECT_EQ(map->partner[static_cast<size_t>(r)], l);
    EXPECT_EQ(map->partner[0], 0);
    EXPECT_LT(std::abs(map->normal.y()), 1e-12);
    const Motion mirrored = mirror_motion(clip.skeleton, *map, clip.motion);
    const std::vector<Vec3> at = world_positions(clip.skeleton, clip.motion);
    const std::vector<Vec3> image = world_positions(clip.skeleton, mirrored);
    const Vec3 n = map->normal;
    const int joints = clip.skeleton.joint_count();
    double worst = 0.0;
    for (int f = 0; f < clip.motion.frame_count; ++f) {
      for (int j = 0; j < joints; ++j) {
        const Vec3 p = at[static_cast<size_t>(f * joints + j)];
        const Vec3 q = image[static_cast<size_t>(f * joints + map->partner[static_cast<size_t>(j)])];
        worst = std::max(worst, (q - (p - 2.0 * n.dot(p) * n)).norm());
      }
    }
    EXPECT_LT(worst, 0.06) << "metres";
    // The turn: the heading of travel, first second against last (16_17 turns 90 degrees left).
    auto turn = [&](const std::vector<Vec3>& positions) {
      const int last = clip.motion.frame_count - 1, second = static_cast<int>(clip.motion.fps);
      const Vec3 a = positions[static_cast<size_t>(second * joints)] - positions[0];
      const Vec3 b = positions[static_cast<size_t>(last * joints)] -
                     positions[static_cast<size_t>((last - second) * joints)];
      return std::atan2(a.z() * b.x() - a.x() * b.z(), a.x() * b.x() + a.z() * b.z());
    };
    if (std::string(c.file) == "cmu/16/16_17.amc") {
      EXPECT_GT(std::abs(turn(at)), 1.0);
      // The root stands a few millimetres beside the hips' middle, and its mirrored path is that
      // of the point as far beside it on the other side: near, not exact.
      EXPECT_NEAR(turn(image), -turn(at), 1e-3);
    }
  }
}

// Where the two sides differ a little, the mirrored motion keeps each joint's own bones: a knee
// that translates (six channels) by its rest offset alone stays there, mirrored; and the plane is
// the hips', however the arms are held.
TEST(Mirror, UnevenSidesKeepTheirOwnBones) {
  const Skeleton even = symmetric_figure("Left", "Right", true);
  std::vector<JointDef> joints(even.joints().begin(), even.joints().end());
  for (JointDef& j : joints) {
    if (j.name == "LeftLeg") j.rest_offset_m = Vec3(0.025, -0.43, 0.012);  // a thigh 1 cm longer
    if (j.name == "RightHand") j.rest_offset_m = Vec3(-0.55, 0.03, -0.02);  // a hand 3 cm higher
  }
  const Skeleton skeleton(joints);
  auto map = mirror_map(skeleton);
  ASSERT_TRUE(map) << map.error().message;
  EXPECT_NEAR(std::abs(map->normal.x()), 1.0, 1e-12);  // the hips', not tilted by the hand
  Motion motion = random_motion(skeleton, 5, 7);
  for (const std::string name : {"LeftLeg", "RightLeg"}) {
    const int j = *skeleton.find(name);
    for (int f = 0; f < motion.frame_count; ++f) {
      motion.translations(f)[static_cast<size_t>(skeleton.translation_slot(j))] = skeleton.joint(j).rest_offset_m;
    }
  }
  const Motion mirrored = mirror_motion(skeleton, *map, motion);
  for (const std::string name : {"LeftLeg", "RightLeg"}) {
    const int j = *skeleton.find(name);
    for (int f = 0; f < motion.frame_count; ++f) {
      EXPECT_NEAR((mirrored.translations(f)[static_cast<size_t>(skeleton.translation_slot(j))] -
                   skeleton.joint(j).rest_offset_m)
                      .norm(),
                  0.0, 1e-15)
          << name;
    }
  }
  const Motion twice = mirror_motion(skeleton, *map, mirrored);
  for (size_t i = 0; i < motion.local_translations_m.size(); ++i) {
    EXPECT_NEAR((twice.local_translations_m[i] - motion.local_translations_m[i]).norm(), 0.0, 1e-12);
  }
}

TEST(Mirror, SkeletonsThatCannotBeMirroredSayWhy) {
  // No joint named for a side.
  const Skeleton plain = symmetric_figure("A", "B");
  auto none = mirror_map(plain);
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("no joint"), std::string::npos) << none.error().message;
  // One arm held out further than the other.
  const Skeleton figure = symmetric_figure("Left", "Right");
  std::vector<JointDef> joints(figure.joints().begin(), figure.joints().end());
  for (JointDef& j : joints) {
    if (j.name == "LeftHand") j.rest_offset_m = Vec3(0.3, -0.4, 0.0);
  }
  auto lopsided = mirror_map(Skeleton(joints));
  // A root named for a side, its "partner" a joint below it.
  std::vector<JointDef> sided(figure.joints().begin(), figure.joints().end());
  sided[0].name = "LeftRoot";
  sided[1].name = "RightRoot";
  auto rooted = mirror_map(Skeleton(sided));
  ASSERT_FALSE(rooted);
  EXPECT_NE(rooted.error().message.find("its root LeftRoot pairs with RightRoot"), std::string::npos)
      << rooted.error().message;
  ASSERT_FALSE(lopsided);
  EXPECT_NE(lopsided.error().message.find("not its own mirror image: its LeftHand and RightHand stand 47 cm off "
                                          "each other's mirror image"),
            std::string::npos)
      << lopsided.error().message;
  // Lying on its side: left above right.
  std::vector<JointDef> lying(figure.joints().begin(), figure.joints().end());
  for (JointDef& j : lying) j.rest_offset_m = Vec3(j.rest_offset_m.y(), j.rest_offset_m.x(), j.rest_offset_m.z());
  auto on_side = mirror_map(Skeleton(lying));
  ASSERT_FALSE(on_side);
  EXPECT_NE(on_side.error().message.find("its LeftUpLeg and RightUpLeg lie one 90 degrees above the other"),
            std::string::npos)
      << on_side.error().message;
}

}  // namespace
}  // namespace mg
