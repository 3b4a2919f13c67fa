// A file's clip judged as info, convert and Python's load_clip judge it: its feet's contacts
// and doubts equal those worked out apart, with or without positions given; feet named but
// missing are an error, feet not found leave the contacts out; a glTF or FBX clip's clock is
// told to export again, a BVH or AMC clip's to --input-fps.
#include "motiongraph/pipeline/clip_as_read.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(ClipAsRead, ContactsAndDoubtsAreThoseWorkedOutApart) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  clip.motion.fps = 30.0;  // read at a quarter of its rate: a clock doubt
  std::string why;
  auto contacts = clip_contacts(clip.skeleton, clip.motion, {}, why);
  ASSERT_TRUE(contacts && *contacts);
  const std::vector<Vec3> positions = world_positions(clip.skeleton, clip.motion);
  const ClipDoubts apart = clip_doubts(positions, clip.skeleton.joint_count(), clip.motion.fps, (*contacts)->masks, {},
                                       ClipClock{clip.motion.fps, false}, (*contacts)->feet);
  ASSERT_FALSE(apart.empty());
  for (const bool given : {false, true}) {
    auto judged = judge_clip_as_read(clip.skeleton, clip.motion, given ? positions : std::vector<Vec3>{},
                                     clip.motion.fps, "amc", {});
    ASSERT_TRUE(judged) << judged.error().to_string();
    ASSERT_TRUE(judged->contacts.has_value());
    EXPECT_EQ(judged->contacts->masks, (*contacts)->masks);
    EXPECT_EQ(judged->doubts.phrases(), apart.phrases());
    EXPECT_TRUE(judged->feet_missing.empty());
  }
}

TEST(ClipAsRead, FeetNamedButMissingAreAnErrorFeetNotFoundAreLeftOut) {
  const Clip clip = test::load_data_clip("cmu/16/16_35.amc");
  auto names = parse_foot_joint_names("lfoot,ltoes,rpes,rtoes");
  ASSERT_TRUE(names) << names.error().to_string();
  auto refused = judge_clip_as_read(clip.skeleton, clip.motion, {}, clip.motion.fps, "amc", *names);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("rpes"), std::string::npos) << refused.error().to_string();
  Skeleton renamed = clip.skeleton;  // no joint the finder knows for a foot
  std::vector<JointDef> joints(renamed.joints().begin(), renamed.joints().end());
  for (JointDef& joint : joints) {
    if (joint.name.find("foot") != std::string::npos) joint.name = "pes" + joint.name;
  }
  auto unknown = judge_clip_as_read(Skeleton(joints), clip.motion, {}, clip.motion.fps, "amc", {});
  ASSERT_TRUE(unknown) << unknown.error().to_string();
  EXPECT_FALSE(unknown->contacts.has_value());
  EXPECT_FALSE(unknown->feet_missing.empty());
}

TEST(ClipAsRead, AClockReadWrongIsToldWhereToSetIt) {
  // 16_15 read at a quarter of its rate (its flights fall 16 times too slowly): a BVH or AMC
  // clip's phrase names --input-fps, a glTF or FBX clip's the export.
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  clip.motion.fps = 30.0;
  for (const char* format : {"amc", "bvh", "gltf", "fbx"}) {
    auto judged = judge_clip_as_read(clip.skeleton, clip.motion, {}, 30.0, format, {});
    ASSERT_TRUE(judged) << judged.error().to_string();
    const std::string text = clip_doubts_text(judged->doubts);
    const bool keyed = std::string(format) == "gltf" || std::string(format) == "fbx";
    EXPECT_EQ(text.find("--input-fps") != std::string::npos, !keyed) << format << ": " << text;
    EXPECT_EQ(text.find("export") != std::string::npos, keyed) << format << ": " << text;
  }
}

TEST(ClipAsRead, AClipResampledIsJudgedAtItsRateItsClockAgainstTheRateRead) {
  // 16_15 read at 30 fps (a quarter of its rate), then resampled to 60: still 4x slow, and the
  // phrase names the rate it was read at, not the one judged.
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  clip.motion.fps = 30.0;
  auto resampled = resample(clip.motion, 60.0);
  ASSERT_TRUE(resampled) << resampled.error().to_string();
  auto judged = judge_clip_as_read(clip.skeleton, *resampled, {}, 30.0, "amc", {});
  ASSERT_TRUE(judged) << judged.error().to_string();
  const std::string text = clip_doubts_text(judged->doubts);
  EXPECT_NE(text.find("its frame rate as read, 30 fps, is likely about 4"), std::string::npos) << text;
  EXPECT_EQ(text.find("60 fps"), std::string::npos) << text;
}

}  // namespace
}  // namespace mg
