// An animation set written by write_animation_set reads back (motion/gltf_import.h) to each of
// its motions, a held pose of a static-root rig folded as the rig's travelling clips are; a
// motion without frames, another rig, or another format is an error naming what is wrong.
#include "motiongraph/export/motion_file.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "motion/static_root_bvh.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/gltf_import.h"
#include "motiongraph/motion/trajectory_joint.h"
#include "motiongraph/synthesis/facing.h"
#include "test_data.h"

namespace mg {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / fs::path("motion_file_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

// Frame `frame` of the clip held for 4 frames, as a static-root rig's BVH reads it: its hips
// never travel, so its static root is not folded.
Clip held_pose(const Clip& plain, int frame) {
  Clip pose = plain;
  pose.motion = plain.motion.slice(frame, 4);
  for (int f = 1; f < pose.motion.frame_count; ++f) {
    for (int j = 0; j < plain.skeleton.joint_count(); ++j) pose.motion.rotations(f)[j] = pose.motion.rotations(0)[j];
    pose.motion.translations(f)[0] = pose.motion.translations(0)[0];
  }
  return test::import_bvh(test::static_root_bvh(pose));
}

TEST(AnimationSet, AHeldPoseOfAStaticRootRigJoinsItsTravellingClips) {
  const Clip plain = test::load_data_clip("cmu/16/16_35.amc");
  const Clip walk = test::import_bvh(test::static_root_bvh(plain));
  const Clip held = held_pose(plain, 40);
  ASSERT_NE(held.skeleton.joint_count(), walk.skeleton.joint_count());  // not folded
  TempDir dir;
  const std::string out = (dir.path / "set.glb").string();
  const std::vector<NamedMotion> set{{"walk.bvh", "walk", &walk.skeleton, &walk.motion},
                                     {"pose.bvh", "pose", &held.skeleton, &held.motion}};
  for (const bool root_motion : {false, true}) {
    MotionFileSettings settings;
    if (root_motion) settings.root_motion = RootMotionOutput{};
    ASSERT_TRUE(write_animation_set(out, set, settings));
    auto bytes = read_text_file(out);
    ASSERT_TRUE(bytes);
    auto clips = clips_from_gltf(*bytes, out, {});
    ASSERT_TRUE(clips) << clips.error().message;
    ASSERT_EQ(clips->size(), 2u);
    // One skeleton for both: the pose read back folded as the walk is.
    EXPECT_EQ((*clips)[0].skeleton.joint_count(), (*clips)[1].skeleton.joint_count()) << root_motion;
    EXPECT_LT(test::max_position_error_by_name(walk, (*clips)[0]), 2e-5) << root_motion;
    // Every joint where it was (but the static root, which becomes the root-motion joint).
    EXPECT_LT(test::max_position_error_by_name(fold_as(held, walk.skeleton), (*clips)[1]), 2e-5) << root_motion;
  }
}

// With root motion, the held pose's root-motion joint faces where its hips do by the walk's
// forward axis (its own was learnt on the static root it had before the fold).
TEST(AnimationSet, AHeldPoseFoldedFacesByItsRigsAxis) {
  const Clip plain = test::load_data_clip("cmu/16/16_35.amc");
  const Clip walk = test::import_bvh(test::static_root_bvh(plain));
  const Clip held = held_pose(plain, 60);
  const Vec3 axis = learn_clip_forward_axis(walk.skeleton, walk.motion);
  const std::vector<NamedMotion> set{{"walk.bvh", "walk", &walk.skeleton, &walk.motion, axis},
                                     {"pose.bvh", "pose", &held.skeleton, &held.motion,
                                      learn_clip_forward_axis(held.skeleton, held.motion)}};
  TempDir dir;
  const std::string out = (dir.path / "set.glb").string();
  MotionFileSettings settings;
  settings.root_motion = RootMotionOutput{};
  ASSERT_TRUE(write_animation_set(out, set, settings));
  auto bytes = read_text_file(out);
  ASSERT_TRUE(bytes);
  auto clips = clips_from_gltf(*bytes, out, {});
  ASSERT_TRUE(clips) << clips.error().message;
  const Clip& read = (*clips)[1];
  ASSERT_EQ(read.skeleton.joint(0).name, test::kStaticRootName);  // the root-motion joint
  const Vec2 want = facing_on_floor(fold_as(held, walk.skeleton).motion.rotations(0)[0], axis);
  const Vec2 got = facing_on_floor(read.motion.rotations(0)[0], Vec3::UnitZ());
  EXPECT_LT((got - want).norm(), 1e-4) << got.transpose() << " / " << want.transpose();
}

TEST(AnimationSet, NoFramesAnotherRigOrFormatIsAnErrorAndNoFile) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip other = test::load_data_clip("bvh/16_01.bvh");
  const Motion none = walk.motion.slice(0, 0);
  TempDir dir;
  const std::string out = (dir.path / "set.glb").string();
  const auto message = [&](const std::string& path, const std::vector<NamedMotion>& set) {
    const Status s = write_animation_set(path, set);
    EXPECT_FALSE(s);
    EXPECT_FALSE(fs::exists(path));
    return s ? std::string() : s.error().to_string();
  };
  EXPECT_NE(message(out, {{"a.amc", "a", &walk.skeleton, &walk.motion}, {"empty.amc", "e", &walk.skeleton, &none}})
                .find("empty.amc: has no frames"),
            std::string::npos);
  EXPECT_NE(message(out, {{"a.amc", "a", &walk.skeleton, &walk.motion}, {"b.bvh", "b", &other.skeleton, &other.motion}})
                .find("b.bvh: its rig is not a.amc's"),
            std::string::npos);
  EXPECT_NE(message((dir.path / "set.bvh").string(), {{"a.amc", "a", &walk.skeleton, &walk.motion}})
                .find("several motions go into a .glb, .gltf or .fbx only"),
            std::string::npos);
  EXPECT_NE(message(out, {}).find("no motion to write"), std::string::npos);
}

}  // namespace
}  // namespace mg
