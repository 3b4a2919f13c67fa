#include "motiongraph/motion/up_axis.h"

#include <gtest/gtest.h>

#include "motion/static_root_bvh.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

// Clips of every kind the project has: walks, turns, runs, jumps, a stop; AMC and the BVH of
// three converters (one of them, 07_12, a broken conversion whose hips sink below the floor).
const char* const kClips[] = {"cmu/16/16_01.amc", "cmu/16/16_11.amc", "cmu/16/16_17.amc", "cmu/16/16_33.amc",
                              "cmu/16/16_35.amc", "cmu/16/16_57.amc", "bvh/07_01.bvh",    "bvh/07_12.bvh",
                              "bvh/111_36.bvh",   "bvh/131_01.bvh",   "bvh/16_01.bvh"};

// The clip as a z-up tool would hold it: every world position turned so that +y goes to +z.
Clip z_up(const Clip& clip) {
  Clip turned = clip;
  turn_clip(turned, up_axis_to_y(UpAxis::kZ).conjugate());
  return turned;
}

using test::import_bvh;

std::string bvh_text(const Clip& clip, double units_per_metre = 1.0) {
  BvhWriteSettings settings;
  settings.units_per_metre = units_per_metre;
  return write_bvh(clip.skeleton, clip.motion, settings);
}

TEST(UpAxis, NamesParse) {
  EXPECT_EQ(parse_up_axis("y"), UpAxis::kY);
  EXPECT_EQ(parse_up_axis("Z"), UpAxis::kZ);
  for (const char* bad : {"", "x", "yz", "up", "-z"}) EXPECT_FALSE(parse_up_axis(bad)) << bad;
  EXPECT_EQ(up_axis_name(UpAxis::kZ), "z");
  EXPECT_EQ(up_axis_name(UpAxis::kY), "y");
}

TEST(UpAxis, TheRotationTakesZUpToYUp) {
  const Quat r = up_axis_to_y(UpAxis::kZ);
  EXPECT_LT((r * Vec3::UnitZ() - Vec3::UnitY()).norm(), 1e-12);
  EXPECT_LT((r * Vec3::UnitY() + Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_LT((r * Vec3::UnitX() - Vec3::UnitX()).norm(), 1e-12);
  EXPECT_TRUE(up_axis_to_y(UpAxis::kY).isApprox(Quat::Identity()));
}

TEST(UpAxis, EveryClipStandsInYAndItsZUpTwinInZ) {
  for (const char* file : kClips) {
    const Clip clip = test::load_data_clip(file);
    const UpAxisChoice y = choose_up_axis(clip.skeleton, clip.motion);
    EXPECT_EQ(y.axis, UpAxis::kY) << file << " ratios " << y.animation_ratio << " " << y.rest_ratio;
    EXPECT_TRUE(up_axis_settled(y)) << file;
    const Clip turned = z_up(clip);
    const UpAxisChoice z = choose_up_axis(turned.skeleton, turned.motion);
    EXPECT_EQ(z.axis, UpAxis::kZ) << file << " ratios " << z.animation_ratio << " " << z.rest_ratio;
    EXPECT_TRUE(up_axis_settled(z)) << file;
  }
}

TEST(UpAxis, TurningMovesEveryWorldPositionByTheRotation) {
  const Clip clip = test::load_data_clip("cmu/16/16_17.amc");
  const Quat r(Eigen::AngleAxisd(0.9, Vec3(0.3, -1.0, 0.4).normalized()));
  Clip turned = clip;
  turn_clip(turned, r);
  // Every joint of every frame where the rotation puts it; turned back, the clip itself.
  const std::vector<Vec3> before = world_positions(clip.skeleton, clip.motion);
  const std::vector<Vec3> after = world_positions(turned.skeleton, turned.motion);
  ASSERT_EQ(before.size(), after.size());
  double worst = 0.0;
  for (size_t i = 0; i < before.size(); ++i) worst = std::max(worst, (r * before[i] - after[i]).norm());
  EXPECT_LT(worst, 1e-9);
  Clip back = turned;
  turn_clip(back, r.conjugate());
  EXPECT_LT(test::max_position_error_by_name(clip, back), 1e-9);
  EXPECT_GT(test::max_position_error_by_name(clip, turned), 0.5);
}

TEST(UpAxis, AZUpBvhReadsBackToTheSameFigureStandingInY) {
  for (const char* file : {"cmu/16/16_15.amc", "cmu/16/16_35.amc", "bvh/111_36.bvh"}) {
    const Clip clip = test::load_data_clip(file);
    // In metres and in centimetres, plain and below a static root (a Bandai-like rig, z up).
    for (const std::string& text :
         {bvh_text(z_up(clip)), bvh_text(z_up(clip), 100.0), test::static_root_bvh(z_up(clip))}) {
      const Clip read = import_bvh(text);
      ASSERT_TRUE(read.detected_up_axis) << file;
      EXPECT_EQ(read.detected_up_axis->axis, UpAxis::kZ) << file;
      EXPECT_GE(read.detected_up_axis->animation_ratio, kUpAxisRatio) << file;
      ASSERT_TRUE(read.detected_unit);
      EXPECT_TRUE(read.detected_unit->plausible);
      // Written with 6 decimals (of a metre or a centimetre) and degrees: micrometres.
      EXPECT_LT(test::max_position_error_by_name(clip, read), 2e-5) << file;
      // Its rest pose stands too: the legs hang down from the root.
      EXPECT_GT(read.skeleton.leg_length_m(), 0.6) << file;
      // Written again, the file is y up and reads back the same, told or not.
      const std::string again = bvh_text(read);
      BvhImportSettings y;
      y.up_axis = UpAxis::kY;
      EXPECT_LT(test::max_position_error_by_name(clip, import_bvh(again, y)), 4e-5) << file;
      const Clip detected = import_bvh(again);
      ASSERT_TRUE(detected.detected_up_axis);
      EXPECT_EQ(detected.detected_up_axis->axis, UpAxis::kY);
    }
  }
}

TEST(UpAxis, AnAxisGivenIsTakenWithoutLooking) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const std::string text = bvh_text(z_up(clip));
  BvhImportSettings y;
  y.up_axis = UpAxis::kY;
  const Clip lying = import_bvh(text, y);
  EXPECT_FALSE(lying.detected_up_axis);
  EXPECT_LT(test::max_position_error_by_name(z_up(clip), lying), 2e-5);
  BvhImportSettings z;
  z.up_axis = UpAxis::kZ;
  const Clip standing = import_bvh(text, z);
  EXPECT_FALSE(standing.detected_up_axis);
  EXPECT_LT(test::max_position_error_by_name(clip, standing), 2e-5);
}

TEST(UpAxis, AFigureLyingAlongZWithAStandingRestPoseStaysY) {
  // A y-up clip of someone on the floor: the root turned to lie the figure along z (its
  // animation says z), the rest pose still standing (it says y). BVH's own convention wins.
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  Clip lying = clip;
  const Quat lie = up_axis_to_y(UpAxis::kZ).conjugate();
  const int slot = lying.skeleton.translation_slot(0);
  for (int f = 0; f < lying.motion.frame_count; ++f) {
    lying.motion.rotations(f)[0] = lie * lying.motion.rotations(f)[0];
    lying.motion.translations(f)[slot] = lie * lying.motion.translations(f)[slot];
  }
  const UpAxisChoice choice = choose_up_axis(lying.skeleton, lying.motion);
  EXPECT_GE(choice.animation_ratio, kUpAxisRatio);
  EXPECT_LE(choice.rest_ratio, 1.0 / kUpAxisRatio);
  EXPECT_EQ(choice.axis, UpAxis::kY);
  EXPECT_FALSE(up_axis_settled(choice));  // chosen against the animation
}

TEST(UpAxis, AZUpRestPoseThatTheRootTurnsUprightStaysY) {
  // A converter's fix-up: offsets and joints z up, the root's channels turning the whole figure
  // y up. The rest pose says z, the animation y: the figure as played wins.
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  Clip fixed = z_up(clip);
  const Quat up = up_axis_to_y(UpAxis::kZ);
  const int slot = fixed.skeleton.translation_slot(0);
  for (int f = 0; f < fixed.motion.frame_count; ++f) {
    fixed.motion.rotations(f)[0] = up * fixed.motion.rotations(f)[0];
    fixed.motion.translations(f)[slot] = up * fixed.motion.translations(f)[slot];
  }
  EXPECT_LT(test::max_position_error_by_name(clip, fixed),
            1e-9);  // it plays standing
  const UpAxisChoice choice = choose_up_axis(fixed.skeleton, fixed.motion);
  EXPECT_GE(choice.rest_ratio, kUpAxisRatio);
  EXPECT_EQ(choice.axis, UpAxis::kY);
  EXPECT_FALSE(up_axis_settled(choice));  // chosen against the rest pose
  const Clip read = import_bvh(bvh_text(fixed));
  EXPECT_LT(test::max_position_error_by_name(clip, read), 2e-5);
}

TEST(UpAxis, AChoiceIsSettledWhenNeitherVoiceSpeaksAgainstIt) {
  const double z = 2.0 * kUpAxisRatio, y = 0.5 / kUpAxisRatio, silent = 1.0;
  struct Case {
    UpAxisChoice choice;
    bool settled;
  };
  const Case cases[] = {
      {{UpAxis::kY, y, y}, true},          {{UpAxis::kZ, z, z}, true},
      {{UpAxis::kY, y, silent}, true},     {{UpAxis::kY, silent, y}, true},
      {{UpAxis::kZ, z, silent}, true},     {{UpAxis::kZ, silent, z}, true},
      {{UpAxis::kY, silent, silent}, false},  // y by default
      {{UpAxis::kY, z, y}, false},         {{UpAxis::kY, y, z}, false},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(up_axis_settled(c.choice), c.settled)
        << up_axis_name(c.choice.axis) << " " << c.choice.animation_ratio << " " << c.choice.rest_ratio;
  }
}

TEST(UpAxis, TheLibrarysAxisIsItsSettledMajorityWhenTheFilesItWouldTurnAreFewer) {
  const double z = 2.0 * kUpAxisRatio, y = 0.5 / kUpAxisRatio;
  const UpAxisChoice settled_z{UpAxis::kZ, z, z}, settled_y{UpAxis::kY, y, y};
  const UpAxisChoice lying{UpAxis::kY, y, z};  // a z-up rig's clip along y, or a converter's fix-up
  using Choices = std::vector<UpAxisChoice>;
  EXPECT_EQ(library_up_axis(Choices{settled_z, settled_z, settled_z, lying}), UpAxis::kZ);
  EXPECT_EQ(library_up_axis(Choices{settled_z, settled_z, lying}), UpAxis::kZ);
  EXPECT_EQ(library_up_axis(Choices{settled_y, settled_y, settled_z, lying}), UpAxis::kY);
  // Too few to overrule: a library of fix-ups with one crawling clip that settles z.
  EXPECT_EQ(library_up_axis(Choices{settled_z, lying, lying, lying}), std::nullopt);
  EXPECT_EQ(library_up_axis(Choices{settled_z, settled_z, lying, lying}), std::nullopt);
  EXPECT_EQ(library_up_axis(Choices{settled_z, lying}), std::nullopt);
  EXPECT_EQ(library_up_axis(Choices{settled_z, settled_y}), std::nullopt);  // split evenly
  EXPECT_EQ(library_up_axis(Choices{lying, lying}), std::nullopt);           // none settled
  EXPECT_EQ(library_up_axis(Choices{}), std::nullopt);
}

}  // namespace
}  // namespace mg
