#include "motiongraph/export/positions_json.h"

#include <gtest/gtest.h>

#include "motiongraph/core/json_text.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

// Two joints, the second named in Latin-1 ("Genou_\xe9"), two frames.
constexpr const char* kLatin1Bvh =
    "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "  JOINT Genou_\xe9\n  {\n    OFFSET 0 -0.5 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n"
    "    End Site\n    {\n      OFFSET 0 -0.4 0\n    }\n  }\n}\n"
    "MOTION\nFrames: 2\nFrame Time: 0.0333333\n0 1 0 0 0 0 0 0 0\n0.1 1 0.2 0 0 90 30 0 0\n";

// kLatin1Bvh's clip, every frame kept.
Result<Clip> latin1_clip() {
  auto doc = parse_bvh(kLatin1Bvh, "latin1.bvh");
  if (!doc) return doc.error();
  BvhImportSettings settings;
  settings.drop_rest_frames = false;
  return clip_from_bvh(*doc, settings);
}

TEST(PositionsJson, WritesWorldPositionsAndSurvivesNamesThatAreNotUtf8) {
  auto clip = latin1_clip();
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

// A root far out (a file may put it at 1e305 m) is written as a number: its micrometres overflowed
// a double, and JSON got null.
TEST(PositionsJson, FarPositionsAreNumbersNotNull) {
  auto clip = latin1_clip();
  ASSERT_TRUE(clip.ok()) << clip.error().to_string();
  for (const double far : {1e14, 1e16, 1e305, -1e305}) {
    clip->motion.translations(1)[0].x() = far;
    auto back = parse_json_text(write_positions_json(clip->skeleton, clip->motion), "positions.json");
    ASSERT_TRUE(back.ok());
    const auto world = world_positions(clip->skeleton, clip->motion);
    const auto& root = (*back)["positions"][1][0];
    ASSERT_TRUE(root[0].is_number()) << far << ": " << root;
    const Vec3& at = world[static_cast<size_t>(clip->skeleton.joint_count())];  // frame 1, the root
    EXPECT_NEAR(root[0].get<double>(), at.x(), std::abs(far) * 1e-15 + 1e-6) << far;
  }
}

TEST(PositionsJson, WritesTheFeetsContactsPerFrameWhenGiven) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const FootJoints feet = *find_foot_joints(clip.skeleton);
  const FootContacts contacts = *detect_foot_contacts(clip.skeleton, clip.motion, feet, {});
  std::vector<ContactMask> masks;
  for (int f = 0; f < clip.motion.frame_count; ++f) masks.push_back(contact_mask(contacts, f));
  const PositionsJsonContacts given{feet, masks};
  auto back = parse_json_text(write_positions_json(clip.skeleton, clip.motion, &given), "positions.json");
  ASSERT_TRUE(back.ok());
  const auto& written = (*back)["contacts"];
  ASSERT_EQ(written["joints"], nlohmann::json({"lfoot", "ltoes", "rfoot", "rtoes"}));
  ASSERT_EQ(written["joint_indices"],
            nlohmann::json({feet.left.ankle, feet.left.toe, feet.right.ankle, feet.right.toe}));
  ASSERT_EQ(written["planted"].size(), static_cast<size_t>(clip.motion.frame_count));
  int planted = 0;
  for (const FootContactTrack& track : contacts.tracks) {
    const size_t column = 2 * (track.side == FootSide::kRight ? 1 : 0) + (track.part == FootPart::kToe ? 1 : 0);
    for (int f = 0; f < clip.motion.frame_count; ++f) {
      ASSERT_EQ(written["planted"][f][column].get<int>(), track.planted[f] ? 1 : 0) << f;
      planted += track.planted[f];
    }
  }
  EXPECT_GT(planted, clip.motion.frame_count);  // two feet, each down more than half the time
  // Without contacts there is no such member.
  auto plain = parse_json_text(write_positions_json(clip.skeleton, clip.motion), "positions.json");
  ASSERT_TRUE(plain.ok());
  EXPECT_FALSE(plain->contains("contacts"));
}

}  // namespace
}  // namespace mg
