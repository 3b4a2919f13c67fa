#include "motiongraph/export/positions_json.h"

#include <gtest/gtest.h>

#include "motiongraph/core/json_text.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/forward_kinematics.h"

namespace mg {
namespace {

// Two joints, the second named in Latin-1 ("Genou_\xe9"), two frames.
constexpr const char* kLatin1Bvh =
    "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "  JOINT Genou_\xe9\n  {\n    OFFSET 0 -0.5 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n"
    "    End Site\n    {\n      OFFSET 0 -0.4 0\n    }\n  }\n}\n"
    "MOTION\nFrames: 2\nFrame Time: 0.0333333\n0 1 0 0 0 0 0 0 0\n0.1 1 0.2 0 0 90 30 0 0\n";

TEST(PositionsJson, WritesWorldPositionsAndSurvivesNamesThatAreNotUtf8) {
  auto doc = parse_bvh(kLatin1Bvh, "latin1.bvh");
  ASSERT_TRUE(doc.ok()) << doc.error().to_string();
  BvhImportSettings settings;
  settings.drop_rest_frames = false;
  auto clip = clip_from_bvh(*doc, settings);
  ASSERT_TRUE(clip.ok()) << clip.error().to_string();
  std::string text;
  ASSERT_NO_THROW(text = write_positions_json(clip->skeleton, clip->motion));
  auto back = parse_json_text(text, "positions.json");
  ASSERT_TRUE(back.ok());
  const auto& joints = (*back)["joints"];
  ASSERT_EQ(joints.size(), static_cast<size_t>(clip->skeleton.joint_count()));
  EXPECT_EQ(joints[1]["name"], "Genou_\xef\xbf\xbd");
  EXPECT_EQ(joints[1]["parent"], 0);
  const auto world = world_positions(clip->skeleton, clip->motion);
  const auto& frames = (*back)["positions"];
  ASSERT_EQ(frames.size(), 2u);
  const size_t count = static_cast<size_t>(clip->skeleton.joint_count());
  for (size_t f = 0; f < 2; ++f) {
    for (size_t j = 0; j < count; ++j) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(frames[f][j][c].get<double>(), world[f * count + j][c], 1e-6);
    }
  }
}

}  // namespace
}  // namespace mg
