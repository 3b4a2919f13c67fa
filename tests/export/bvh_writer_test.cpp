#include "motiongraph/export/bvh_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
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
    Clip back = read_back(write_bvh(clip.skeleton, clip.motion, {}));
    EXPECT_LT(test::max_position_error_by_name(clip, back), 1e-5) << file;
    // Each joint keeps the rotation order it was read with.
    for (int j = 0; j < clip.skeleton.joint_count(); ++j) {
      if (clip.skeleton.joint(j).end_site) continue;
      EXPECT_EQ(back.skeleton.joint(*back.skeleton.find(clip.skeleton.joint(j).name)).euler_order,
                clip.skeleton.joint(j).euler_order);
    }
  }
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
