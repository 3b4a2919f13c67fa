#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/export/root_rotation_order.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

Clip read_back(const std::string& text) {
  auto doc = parse_bvh(text, "written.bvh");
  EXPECT_TRUE(doc) << doc.error().to_string();
  BvhImportSettings settings;
  settings.metres_per_unit = 1.0;
  settings.drop_rest_frames = false;
  auto clip = clip_from_bvh(*doc, settings);
  EXPECT_TRUE(clip) << clip.error().to_string();
  return *clip;
}

TEST(BvhWriter, AmcToBvhAndBackKeepsWorldPositions) {
  for (const char* file : {"cmu/16/16_01.amc", "cmu/16/16_11.amc", "cmu/16/16_35.amc", "cmu/16/16_57.amc"}) {
    Clip clip = test::load_data_clip(file);
    Clip back = read_back(write_bvh(clip.skeleton, clip.motion, {}));
    EXPECT_EQ(back.motion.fps, clip.motion.fps);
    EXPECT_LT(test::max_position_error_by_name(clip, back), 1e-5) << file;  // 0.01 mm
  }
}

TEST(BvhWriter, EveryBundledBvhSurvivesARoundTrip) {
  for (const char* file : {"bvh/07_01.bvh", "bvh/07_12.bvh", "bvh/111_36.bvh", "bvh/131_01.bvh", "bvh/16_01.bvh"}) {
    Clip clip = test::load_data_clip(file, 0.056444);
    BvhWriteSettings as_read;
    as_read.keep_root_order = true;
    Clip back = read_back(write_bvh(clip.skeleton, clip.motion, as_read));
    EXPECT_LT(test::max_position_error_by_name(clip, back), 1e-5) << file;
    // Each joint keeps the rotation order it was read with.
    for (int j = 0; j < clip.skeleton.joint_count(); ++j) {
      if (clip.skeleton.joint(j).end_site) continue;
      EXPECT_EQ(back.skeleton.joint(*back.skeleton.find(clip.skeleton.joint(j).name)).euler_order,
                clip.skeleton.joint(j).euler_order);
    }
    // By default the root's heading is its outermost angle: the same positions, the other joints'
    // orders as read.
    Clip turned = read_back(write_bvh(clip.skeleton, clip.motion, {}));
    EXPECT_LT(test::max_position_error_by_name(clip, turned), 1e-5) << file;
    EXPECT_EQ(turned.skeleton.joint(0).euler_order, root_rotation_order(clip.skeleton)) << file;
    for (int j = 1; j < clip.skeleton.joint_count(); ++j) {
      if (clip.skeleton.joint(j).end_site) continue;
      EXPECT_EQ(turned.skeleton.joint(*turned.skeleton.find(clip.skeleton.joint(j).name)).euler_order,
                clip.skeleton.joint(j).euler_order);
    }
  }
}

// A figure turning on the spot, a full turn and more in steps of 1.5 degrees, leaning 10 degrees
// forward: written with the heading outermost its root's three curves move by about a step from
// frame to frame (a curve editor shows them smooth); in the file's ZYX the heading is the middle
// angle, and passing east and west the outer two swing between frames by the lean's size (10
// degrees here; 80 in a steering result of subject 16, whose hips lean and roll at once).
TEST(BvhWriter, TheRootsHeadingIsItsOutermostAngle) {
  Clip clip = test::load_data_clip("bvh/16_01.bvh", 0.056444);
  ASSERT_EQ(clip.skeleton.joint(0).euler_order, (ComposeOrder{Axis::kZ, Axis::kY, Axis::kX}));
  const int frames = 300;
  Motion spin = clip.motion.slice(0, 1);
  for (int f = 1; f < frames; ++f) {
    Motion one = clip.motion.slice(0, 1);
    spin.local_rotations.insert(spin.local_rotations.end(), one.local_rotations.begin(), one.local_rotations.end());
    spin.local_translations_m.insert(spin.local_translations_m.end(), one.local_translations_m.begin(),
                                     one.local_translations_m.end());
    ++spin.frame_count;
  }
  for (int f = 0; f < frames; ++f) {
    const double heading = f * 1.5 * std::numbers::pi / 180.0;
    spin.rotations(f)[0] = Quat(Eigen::AngleAxisd(heading, Vec3::UnitY())) *
                           Quat(Eigen::AngleAxisd(10.0 * std::numbers::pi / 180.0, Vec3::UnitX()));
  }
  auto largest_root_step = [&](const BvhWriteSettings& settings) {
    auto doc = parse_bvh(write_bvh(clip.skeleton, spin, settings), "spin.bvh");
    EXPECT_TRUE(doc);
    double most = 0.0;
    for (int f = 1; f < frames; ++f) {
      for (int c = 3; c < 6; ++c) {  // the root's rotation channels, after its positions
        const size_t at = static_cast<size_t>(f * doc->channel_count + c);
        most = std::max(most, std::abs(doc->values[at] - doc->values[at - static_cast<size_t>(doc->channel_count)]));
      }
    }
    return most;
  };
  EXPECT_LT(largest_root_step({}), 1.6);
  BvhWriteSettings as_read;
  as_read.keep_root_order = true;
  EXPECT_GT(largest_root_step(as_read), 5.0);
}

TEST(BvhWriter, WritingWhatWasWrittenIsExact) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const std::string first = write_bvh(clip.skeleton, clip.motion, {});
  Clip back = read_back(first);
  EXPECT_EQ(write_bvh(back.skeleton, back.motion, {}), first);
}

TEST(BvhWriter, RootOnlyPositionChannelsAndUnits) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  BvhWriteSettings centimetres;
  centimetres.units_per_metre = 100.0;
  const std::string text = write_bvh(clip.skeleton, clip.motion, centimetres);
  size_t position_channel_lines = 0;
  for (size_t at = text.find("Xposition"); at != std::string::npos; at = text.find("Xposition", at + 1)) {
    ++position_channel_lines;
  }
  EXPECT_EQ(position_channel_lines, 1u);
  auto doc = parse_bvh(text, "cm.bvh");
  ASSERT_TRUE(doc);
  BvhImportSettings settings;
  settings.metres_per_unit = 0.01;
  auto back = clip_from_bvh(*doc, settings);
  ASSERT_TRUE(back);
  EXPECT_LT(test::max_position_error_by_name(clip, *back), 1e-5);
}

// Numbers of any length are written whole: at 1e60 units a metre an offset has 60 digits (a
// 64-byte buffer once took past its end, writing what lay beyond it).
// Numbers of 64 characters and more are written whole (the CLI and Python refuse an output scale
// above 1e6, BvhWriteSettings::validate, but the writer itself takes any): each number of the
// file at 1e60 units a metre is the one at 1 unit a metre, or it times 1e60 (lengths).
TEST(BvhWriter, HugeUnitsAreWrittenWhole) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  BvhWriteSettings huge;
  huge.units_per_metre = 1e60;
  EXPECT_FALSE(huge.validate());
  const std::string text = write_bvh(clip.skeleton, clip.motion, huge);
  for (const char c : text) ASSERT_TRUE(c == '\n' || (c >= ' ' && c <= '~')) << static_cast<int>(c);
  ASSERT_TRUE(parse_bvh(text, "huge.bvh"));
  std::istringstream huge_words(text), metre_words(write_bvh(clip.skeleton, clip.motion, {}));
  std::string h, m;
  int numbers = 0, lengths = 0;
  while (metre_words >> m) {
    ASSERT_TRUE(huge_words >> h);
    char* end = nullptr;
    const double metres = std::strtod(m.c_str(), &end);
    if (end != m.c_str() + m.size()) {  // a word
      EXPECT_EQ(h, m);
      continue;
    }
    const double big = std::strtod(h.c_str(), &end);
    ASSERT_EQ(end, h.c_str() + h.size()) << h;
    ++numbers;
    if (big == metres) continue;
    ++lengths;
    EXPECT_NEAR(big / 1e60, metres, 1e-6 * std::max(1.0, std::abs(metres))) << h << " against " << m;  // 6 decimals
  }
  EXPECT_FALSE(huge_words >> h);
  EXPECT_GT(lengths, 100);
  EXPECT_GT(numbers, lengths);
}

TEST(BvhWriter, MovingNonRootJointsKeepPositionChannelsWithAZeroOffset) {
  // A child whose translation really moves keeps its position channels; its OFFSET is zero so
  // that readers that add channels to OFFSET (three.js) and readers that replace it agree.
  const std::string text =
      "HIERARCHY\nROOT r\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
      " JOINT c\n {\n  OFFSET 0 2 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
      "  End Site\n  {\n   OFFSET 1 0 0\n  }\n }\n}\nMOTION\nFrames: 2\nFrame Time: 0.04\n"
      "0 0 0 0 0 0 0 2 0 0 0 0\n0 0 0 0 0 0 0.5 2 0 0 0 30\n";
  Clip clip = read_back(text);
  const std::string written = write_bvh(clip.skeleton, clip.motion, {});
  EXPECT_NE(written.find("JOINT c\n  {\n    OFFSET 0 0 0\n    CHANNELS 6 Xposition"), std::string::npos) << written;
  EXPECT_LT(test::max_position_error_by_name(clip, read_back(written)), 1e-6);
}

TEST(BvhWriter, ValidatesSettings) {
  BvhWriteSettings settings;
  settings.units_per_metre = 0.0;
  EXPECT_FALSE(settings.validate());
  settings.units_per_metre = 1.0;
  settings.decimals = 0;
  EXPECT_FALSE(settings.validate());
}

}  // namespace
}  // namespace mg
