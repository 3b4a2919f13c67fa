// FBX in: a file built here by FBX's rules alone (motion/ascii_fbx.h: joints resting turned in
// frames of their own, PreRotations, all six rotation orders, an armature turned and scaled,
// inches or centimetres, +y or +z up, two animation stacks, a skinned mesh beside an animated
// prop) reads to the world positions of the clips it was made from, at their rate; and what cannot
// be read is one error each. (FBX that Blender writes is read in tests/blender.)
#include "motiongraph/motion/fbx_import.h"

#include <gtest/gtest.h>

#include "motion/ascii_fbx.h"
#include "motion/max_apart.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "test_data.h"

namespace mg {
namespace {

// A clip of subject 16 at 30 fps, its first `frames`.
Clip walk(const std::string& amc, int frames) {
  Clip clip = test::load_data_clip(amc);
  auto at30 = resample(clip.motion, 30.0);
  EXPECT_TRUE(at30);
  Motion cut(clip.skeleton, frames, 30.0);
  for (int f = 0; f < frames; ++f) {
    for (int j = 0; j < clip.skeleton.joint_count(); ++j) cut.rotations(f)[j] = at30->rotations(f)[j];
    cut.translations(f)[0] = at30->translations(f)[0];
  }
  clip.motion = std::move(cut);
  return clip;
}

std::vector<Clip> read(const std::string& text, const FbxImportSettings& settings = {}) {
  auto clips = clips_from_fbx(text, "test.fbx", settings);
  EXPECT_TRUE(clips) << clips.error().message;
  return clips ? std::move(*clips) : std::vector<Clip>();
}

std::string message(const std::string& text, const FbxImportSettings& settings = {}) {
  auto clips = clips_from_fbx(text, "bad.fbx", settings);
  EXPECT_FALSE(clips);
  return clips ? std::string() : clips.error().message;
}

class FbxImport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    walk_ = new Clip(walk("cmu/16/16_15.amc", 40));
    run_ = new Clip(walk("cmu/16/16_35.amc", 25));
  }
  static void TearDownTestSuite() {
    delete walk_;
    delete run_;
  }
  static std::vector<std::pair<std::string, Clip>> stacks() { return {{"walk", *walk_}, {"run", *run_}}; }
  static Clip* walk_;
  static Clip* run_;
};
Clip* FbxImport::walk_ = nullptr;
Clip* FbxImport::run_ = nullptr;

TEST_F(FbxImport, ARigByFbxRulesReadsToItsClipsJoints) {
  for (const bool z_up : {false, true}) {
    test::AsciiFbxSettings settings;
    settings.z_up = z_up;
    settings.unit_scale_factor = z_up ? 2.54 : 1.0;  // inches, centimetres
    settings.armature_scale = z_up ? 0.5 : 100.0;
    settings.armature_rotation = Quat(Eigen::AngleAxisd(0.4, Vec3(0.2, 1.0, 0.3).normalized()));
    SCOPED_TRACE(z_up ? "z up, inches" : "y up, centimetres");
    const std::vector<Clip> clips = read(test::ascii_fbx(stacks(), settings));
    ASSERT_EQ(clips.size(), 2u);
    EXPECT_EQ(clips[0].name, "walk");
    EXPECT_EQ(clips[1].name, "run");
    for (size_t c = 0; c < 2; ++c) {
      const Clip& source = c == 0 ? *walk_ : *run_;
      EXPECT_EQ(clips[c].motion.fps, 30.0);
      EXPECT_EQ(clips[c].skeleton.joint_count(), source.skeleton.joint_count());
      EXPECT_LT(test::max_apart(source, clips[c]), 1e-5);  // ASCII keys of 9 digits
      EXPECT_EQ(clips[c].skeleton.translated_joints().size(), 1u);
    }
  }
}

TEST_F(FbxImport, ASkinMakesTheSkeletonAndAnimatedPropsAreLeftOut) {
  test::AsciiFbxSettings settings;
  settings.skin = true;
  const std::string text = test::ascii_fbx(stacks(), settings);
  const std::vector<Clip> clips = read(text);
  ASSERT_EQ(clips.size(), 2u);
  EXPECT_FALSE(clips[0].skeleton.find("Prop"));
  EXPECT_FALSE(clips[0].skeleton.find("Body"));
  EXPECT_LT(test::max_apart(*walk_, clips[0]), 1e-5);
  // Without the mesh, the prop the stacks move would be a joint beside the armature.
  settings.skin = false;
  EXPECT_FALSE(read(test::ascii_fbx(stacks(), settings))[0].skeleton.find("Prop"));
}

TEST_F(FbxImport, NamesAsBlenderWritesThemAndRates) {
  test::AsciiFbxSettings settings;
  settings.stack_prefix = "Armature|";  // Blender's OBJECT|ACTION, OBJECT a node of the file
  const std::string text = test::ascii_fbx(stacks(), settings);
  auto names = fbx_animation_names(text, "set.fbx");
  ASSERT_TRUE(names) << names.error().message;
  EXPECT_EQ(*names, (std::vector<std::string>{"walk", "run"}));
  settings.stack_prefix = "Take|";  // not a node: the name is kept whole
  names = fbx_animation_names(test::ascii_fbx(stacks(), settings), "set.fbx");
  ASSERT_TRUE(names);
  EXPECT_EQ(names->front(), "Take|walk");
  // A rate given: sampled between the keys.
  FbxImportSettings at60;
  at60.fps_override = 60.0;
  const std::vector<Clip> clips = read(text, at60);
  ASSERT_EQ(clips.size(), 2u);
  EXPECT_EQ(clips[0].motion.fps, 60.0);
  EXPECT_EQ(clips[0].motion.frame_count, 2 * walk_->motion.frame_count - 1);
  auto back = resample(clips[0].motion, 30.0);
  ASSERT_TRUE(back);
  Clip every_other = clips[0];
  every_other.motion = std::move(*back);
  EXPECT_LT(test::max_apart(*walk_, every_other), 1e-5);  // the keys' frames are the keys
}

TEST_F(FbxImport, UpAxisGivenOverridesTheFiles) {
  test::AsciiFbxSettings settings;
  settings.z_up = true;
  const std::string text = test::ascii_fbx(stacks(), settings);
  FbxImportSettings as_y;
  as_y.up_axis = UpAxis::kY;  // the file's z up taken as it stands: the figure lies along z
  const std::vector<Clip> lying = read(text, as_y);
  ASSERT_FALSE(lying.empty());
  const std::vector<Vec3> p = world_positions(lying[0].skeleton, lying[0].motion);
  const std::vector<Vec3> q = world_positions(walk_->skeleton, walk_->motion);
  // Ours (x, y, z) was written (x, -z, y): y up in the file is z here.
  const int joints = walk_->skeleton.joint_count();
  for (int j = 0; j < joints; ++j) {
    const auto k = lying[0].skeleton.find(walk_->skeleton.joint(j).name);
    ASSERT_TRUE(k);
    for (int f = 0; f < walk_->motion.frame_count; f += 5) {
      const Vec3& ours = q[static_cast<size_t>(f * joints + j)];
      const Vec3& read_lying = p[static_cast<size_t>(f * joints + *k)];
      EXPECT_LT((read_lying - Vec3(ours.x(), -ours.z(), ours.y())).norm(), 1e-5);
    }
  }
}

TEST_F(FbxImport, WhatCannotBeReadIsOneError) {
  EXPECT_EQ(clips_from_fbx("not an fbx file at all", "bad.fbx", {}).error().file, "bad.fbx");
  EXPECT_NE(message("not an fbx file at all").find("cannot read FBX"), std::string::npos);
  EXPECT_NE(message("").find("cannot read FBX"), std::string::npos);
  std::string text = test::ascii_fbx(stacks());
  // No animation stack: nothing to read.
  std::string still = text.substr(0, text.find("\tAnimationStack:")) + "}\nConnections:  {\n\tC: \"OO\",1000,0\n}\n";
  EXPECT_NE(message(still).find("has no animation"), std::string::npos);
  // An up axis of x: said, with the way out.
  std::string sideways = text;
  sideways.replace(sideways.find("\"UpAxis\", \"int\", \"Integer\", \"\",1"), 34, "\"UpAxis\", \"int\", \"Integer\", \"\",0");
  EXPECT_NE(message(sideways).find("up axis is +x"), std::string::npos);
  FbxImportSettings given;
  given.up_axis = UpAxis::kY;
  EXPECT_EQ(read(sideways, given).size(), 2u);
  // A joint scaled: the project reads rigid skeletons.
  std::string scaled = text;
  const size_t hips = scaled.find("\"Model::lhipjoint\"");
  ASSERT_NE(hips, std::string::npos);
  scaled.insert(scaled.find("\t\t\tP: \"Lcl Translation\"", hips), "\t\t\tP: \"Lcl Scaling\", \"Lcl Scaling\", \"\", \"A\",2,2,2\n");
  EXPECT_NE(message(scaled).find("node 'lhipjoint' is scaled"), std::string::npos);
  FbxImportSettings negative;
  negative.fps_override = -1.0;
  EXPECT_NE(message(text, negative).find("frame rate"), std::string::npos);
  // Cut anywhere, a file is read or refused with one error, never a crash.
  for (size_t cut = 0; cut < text.size(); cut += text.size() / 37) {
    auto clips = clips_from_fbx(text.substr(0, cut), "cut.fbx", {});
    if (!clips) {
      EXPECT_EQ(clips.error().file, "cut.fbx");
    }
  }
}

}  // namespace
}  // namespace mg
