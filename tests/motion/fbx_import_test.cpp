// FBX in: a file built here by FBX's rules alone (motion/ascii_fbx.h: joints resting turned in
// frames of their own, PreRotations, all six rotation orders, an armature turned and scaled,
// inches or centimetres, +y or +z up, two animation stacks, a skinned mesh beside an animated
// prop) reads to the world positions of the clips it was made from, at their rate; and what cannot
// be read is one error each. (FBX that Blender writes is read in tests/blender.)
#include "motiongraph/motion/fbx_import.h"

#include <cstring>
#include <numbers>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "motion/ascii_fbx.h"
#include "motion/max_apart.h"
#include "motiongraph/export/fbx_writer.h"
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
  for (const char* up : {"+y", "+z", "-z", "+x", "-y"}) {
    const bool y_up = std::string(up) == "+y";
    test::AsciiFbxSettings settings;
    settings.up = up;
    settings.unit_scale_factor = y_up ? 1.0 : 2.54;  // centimetres, inches
    settings.armature_scale = y_up ? 100.0 : 0.5;
    settings.armature_rotation = Quat(Eigen::AngleAxisd(0.4, Vec3(0.2, 1.0, 0.3).normalized()));
    SCOPED_TRACE(up);
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

// A skin's bones are the joints vertices hang from; end bones and fingers that none does (Mixamo's
// HeadTop_End) are joints of the skeleton all the same.
TEST_F(FbxImport, BonesNoVertexHangsFromAreJointsToo) {
  test::AsciiFbxSettings settings;
  settings.skin = true;
  settings.skin_leaves = false;
  const std::vector<Clip> clips = read(test::ascii_fbx(stacks(), settings));
  ASSERT_EQ(clips.size(), 2u);
  EXPECT_EQ(clips[0].skeleton.joint_count(), walk_->skeleton.joint_count());
  EXPECT_FALSE(clips[0].skeleton.find("Prop"));
  EXPECT_FALSE(clips[0].skeleton.find("Body"));
  EXPECT_LT(test::max_apart(*walk_, clips[0]), 1e-5);
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

TEST_F(FbxImport, KeysOnTheFramesOfTheRateTheFileDeclaresAreReadAtItHoweverSlow) {
  // Our own FBX at 15 fps (TimeMode custom, CustomFrameRate 15): read back at 15, every key a
  // frame (keys slower than 24 a second were sampled at 30 where no rate was declared).
  auto at15 = resample(walk_->motion, 15.0);
  ASSERT_TRUE(at15);
  auto bytes = write_fbx(walk_->skeleton, *at15, "walk");
  ASSERT_TRUE(bytes) << bytes.error().message;
  const std::vector<Clip> clips = read(*bytes);
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0].motion.fps, 15.0);
  EXPECT_EQ(clips[0].motion.frame_count, at15->frame_count);
  Clip fifteen = *walk_;
  fifteen.motion = *at15;
  EXPECT_LT(test::max_apart(fifteen, clips[0]), 1e-4);
}

TEST_F(FbxImport, UpAxisGivenOverridesTheFiles) {
  test::AsciiFbxSettings settings;
  settings.up = "+z";
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
  EXPECT_NE(message("").find("the FBX file is empty"), std::string::npos);
  std::string text = test::ascii_fbx(stacks());
  // No animation stack: nothing to read.
  std::string still = text.substr(0, text.find("\tAnimationStack:")) + "}\nConnections:  {\n\tC: \"OO\",1000,0\n}\n";
  EXPECT_NE(message(still).find("has no animation"), std::string::npos);
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

// Files that crash assimp itself (Debian's 5.2) are one error too, and the program goes on: our
// own figure's FBX with two bones of one name (a double free as assimp frees the scene) or a
// skin's vertex index past the mesh (an assertion in its converter). The same file unbroken is
// read as before.
TEST_F(FbxImport, AFileThatCrashesTheReaderIsOneError) {
  auto bytes = write_fbx(walk_->skeleton, walk_->motion, "walk");
  ASSERT_TRUE(bytes);
  ASSERT_EQ(read(*bytes).size(), 1u);
  const std::string model = std::string("\0\1Model", 7);
  std::string twice = *bytes;
  const size_t right = twice.find("rfemur" + model);
  ASSERT_NE(right, std::string::npos);
  twice.replace(right, 6, "lfemur");
  std::string far_index = *bytes;
  const size_t indexes = far_index.find("\x07Indexesi");
  ASSERT_NE(indexes, std::string::npos);
  const int32_t past = 8323719;
  std::memcpy(far_index.data() + indexes + 21, &past, sizeof past);
  for (const std::string* broken : {&twice, &far_index}) {
    auto clips = clips_from_fbx(*broken, "broken.fbx", {});
    ASSERT_FALSE(clips);
    EXPECT_EQ(clips.error().file, "broken.fbx");
    EXPECT_NE(clips.error().message.find("cannot read FBX"), std::string::npos) << clips.error().message;
  }
  EXPECT_NE(clips_from_fbx(twice, "broken.fbx", {}).error().message.find("the reader (assimp) crashed on it"),
            std::string::npos);
  ASSERT_EQ(read(*bytes).size(), 1u);
}

// A rotation key of a million degrees: assimp splits it into thousands of keys microseconds apart,
// which were read as 167 597 frames a second (and the feet's contacts took minutes over them).
// Keys closer than a millisecond are no frames: the file's rate samples the curve.
TEST_F(FbxImport, KeysAReaderSplitsAreNoFrames) {
  auto bytes = write_fbx(walk_->skeleton, walk_->motion, "walk");
  ASSERT_TRUE(bytes);
  const size_t keys = bytes->find("\rKeyValueFloatf");
  ASSERT_NE(keys, std::string::npos);
  const float huge = 1e6f;
  std::memcpy(bytes->data() + keys + 27 + 4 * 30, &huge, sizeof huge);
  const std::vector<Clip> clips = read(*bytes);
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0].motion.fps, 30.0);
  EXPECT_EQ(clips[0].motion.frame_count, walk_->motion.frame_count);
}


}  // namespace
}  // namespace mg

namespace mg {
namespace {

// A chain Hips > Knee > Foot > Toe by hand, in FBX's own words, with what is asked of the Knee
// (`knee`: properties) and of the file (`extra`: objects, `links`: connections); the Knee turns
// about x over 3 keys at 30 fps, the Hips travel along z.
std::string chain_fbx(const std::string& knee, const std::string& extra = "", const std::string& links = "") {
  const auto model = [](int id, const char* name, const std::string& properties) {
    return fmt::format("\tModel: {}, \"Model::{}\", \"LimbNode\" {{\n\t\tVersion: 232\n\t\tProperties70:  {{\n{}\t\t}}\n\t}}\n",
                       id, name, properties);
  };
  const auto curve = [](int id, const char* values) {
    return fmt::format("\tAnimationCurve: {}, \"AnimCurve::\", \"\" {{\n\t\tDefault: 0\n\t\tKeyVer: 4008\n"
                       "\t\tKeyTime: *3 {{\n\t\t\ta: 0,1539538600,3079077200\n\t\t}}\n"
                       "\t\tKeyValueFloat: *3 {{\n\t\t\ta: {}\n\t\t}}\n\t}}\n", id, values);
  };
  const auto lcl = [](const char* t, const char* r) {
    return fmt::format("\t\t\tP: \"Lcl Translation\", \"Lcl Translation\", \"\", \"A\",{}\n"
                       "\t\t\tP: \"Lcl Rotation\", \"Lcl Rotation\", \"\", \"A\",{}\n", t, r);
  };
  std::string out =
      "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXHeaderVersion: 1003\n\tFBXVersion: 7400\n}\n"
      "GlobalSettings:  {\n\tVersion: 1000\n\tProperties70:  {\n\t\tP: \"UnitScaleFactor\", \"double\", \"Number\", \"\",1\n"
      "\t\tP: \"TimeMode\", \"enum\", \"\", \"\",6\n\t}\n}\nObjects:  {\n";
  out += model(10, "Hips", lcl("0,90,0", "0,0,0"));
  out += model(11, "Knee", lcl("0,-40,2", "10,0,0") + knee);
  out += model(12, "Foot", lcl("0,-42,-3", "20,0,0"));
  out += model(13, "Toe", lcl("0,-5,12", "0,0,0"));
  out += "\tAnimationStack: 20, \"AnimStack::walk\", \"\" {\n\t}\n\tAnimationLayer: 21, \"AnimLayer::Base\", \"\" {\n\t}\n";
  out += "\tAnimationCurveNode: 30, \"AnimCurveNode::R\", \"\" {\n\t}\n";
  out += curve(31, "10,40,70") + curve(32, "0,0,0") + curve(33, "0,0,0");
  out += "\tAnimationCurveNode: 40, \"AnimCurveNode::T\", \"\" {\n\t}\n";
  out += curve(41, "0,0,0") + curve(42, "90,90,90") + curve(43, "0,10,20");
  out += extra + "}\nConnections:  {\n\tC: \"OO\",10,0\n\tC: \"OO\",11,10\n\tC: \"OO\",12,11\n\tC: \"OO\",13,12\n";
  out += "\tC: \"OO\",21,20\n\tC: \"OO\",30,21\n\tC: \"OP\",30,11, \"Lcl Rotation\"\n";
  out += "\tC: \"OP\",31,30, \"d|X\"\n\tC: \"OP\",32,30, \"d|Y\"\n\tC: \"OP\",33,30, \"d|Z\"\n";
  out += "\tC: \"OO\",40,21\n\tC: \"OP\",40,10, \"Lcl Translation\"\n";
  out += "\tC: \"OP\",41,40, \"d|X\"\n\tC: \"OP\",42,40, \"d|Y\"\n\tC: \"OP\",43,40, \"d|Z\"\n" + links + "}\n";
  return out;
}

Quat about_x(double degrees) { return Quat(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Vec3::UnitX())); }

// The chain's joints by FBX's transform: T * Roff * Rp * Rpre * R * Rp^-1 (no post-rotation, no
// scaling pivot moves a joint; geometric transforms are the mesh's), in metres, at frame f.
std::vector<Vec3> chain_positions(int f, const Vec3& rotation_offset, const Vec3& rotation_pivot, double pre_x) {
  const double knee_x = 10.0 + 30.0 * f;
  Eigen::Affine3d hips = Eigen::Translation3d(0, 90, 10.0 * f) * Eigen::Affine3d::Identity();
  Eigen::Affine3d knee = hips * Eigen::Translation3d(0, -40, 2) * Eigen::Translation3d(rotation_offset) *
                         Eigen::Translation3d(rotation_pivot) * about_x(pre_x) * about_x(knee_x) *
                         Eigen::Translation3d(-rotation_pivot);
  Eigen::Affine3d foot = knee * Eigen::Translation3d(0, -42, -3) * about_x(20.0);
  Eigen::Affine3d toe = foot * Eigen::Translation3d(0, -5, 12);
  std::vector<Vec3> out;
  for (const Eigen::Affine3d* a : {&hips, &knee, &foot, &toe}) out.push_back(0.01 * a->translation());
  return out;
}

void expect_chain(const Clip& clip, const Vec3& rotation_offset, const Vec3& rotation_pivot, double pre_x) {
  ASSERT_EQ(clip.motion.frame_count, 3);
  const std::vector<Vec3> p = world_positions(clip.skeleton, clip.motion);
  const char* names[4] = {"Hips", "Knee", "Foot", "Toe"};
  for (int f = 0; f < 3; ++f) {
    const std::vector<Vec3> want = chain_positions(f, rotation_offset, rotation_pivot, pre_x);
    for (int i = 0; i < 4; ++i) {
      const auto j = clip.skeleton.find(names[i]);
      ASSERT_TRUE(j) << names[i];
      EXPECT_LT((p[static_cast<size_t>(f * clip.skeleton.joint_count() + *j)] - want[static_cast<size_t>(i)]).norm(), 1e-6)
          << names[i] << " frame " << f;
    }
  }
}

TEST(FbxImportPivots, PivotsOffsetsAndGeometryMoveTheJointAsFbxSays) {
  const Vec3 none = Vec3::Zero();
  SCOPED_TRACE("plain");
  expect_chain(read(chain_fbx(""))[0], none, none, 0.0);
  const auto property = [](const char* name, const char* value) {
    return fmt::format("\t\t\tP: \"{}\", \"Vector3D\", \"Vector\", \"\",{}\n", name, value);
  };
  {
    SCOPED_TRACE("pre-rotation");
    expect_chain(read(chain_fbx(property("PreRotation", "25,0,0")))[0], none, none, 25.0);
  }
  {
    SCOPED_TRACE("rotation pivot and offset");  // the pivots' helpers carry the keys
    const std::string knee = property("RotationPivot", "3,-2,1.5") + property("RotationOffset", "2,4,-1");
    expect_chain(read(chain_fbx(knee))[0], Vec3(2, 4, -1), Vec3(3, -2, 1.5), 0.0);
  }
  {
    SCOPED_TRACE("scaling pivot, geometric transform");  // neither moves a joint
    const std::string knee = property("ScalingPivot", "5,1,-2") + property("GeometricTranslation", "4,5,6") +
                             property("GeometricRotation", "30,40,50");
    expect_chain(read(chain_fbx(knee))[0], none, none, 0.0);
  }
}

TEST(FbxImportPivots, TheSkeletonIsTheArmaturesTreeWithItsStillBones) {
  // A prop and a camera beside the chain, each animated; a bone below the Toe no key moves.
  const std::string extra =
      "\tModel: 50, \"Model::Ball\", \"Null\" {\n\t\tVersion: 232\n\t}\n"
      "\tModel: 51, \"Model::Tip\", \"LimbNode\" {\n\t\tVersion: 232\n\t\tProperties70:  {\n"
      "\t\t\tP: \"Lcl Translation\", \"Lcl Translation\", \"\", \"A\",0,0,4\n\t\t}\n\t}\n"
      "\tAnimationCurveNode: 52, \"AnimCurveNode::T\", \"\" {\n\t}\n"
      "\tAnimationCurve: 53, \"AnimCurve::\", \"\" {\n\t\tDefault: 0\n\t\tKeyVer: 4008\n"
      "\t\tKeyTime: *2 {\n\t\t\ta: 0,3079077200\n\t\t}\n\t\tKeyValueFloat: *2 {\n\t\t\ta: 0,300\n\t\t}\n\t}\n";
  const std::string links = "\tC: \"OO\",50,0\n\tC: \"OO\",51,13\n\tC: \"OO\",52,21\n\tC: \"OP\",52,50, \"Lcl Translation\"\n"
                            "\tC: \"OP\",53,52, \"d|X\"\n";
  const std::vector<Clip> clips = read(chain_fbx("", extra, links));
  ASSERT_EQ(clips.size(), 1u);
  const Skeleton& skeleton = clips[0].skeleton;
  EXPECT_EQ(skeleton.joint_count(), 5);
  EXPECT_FALSE(skeleton.find("Ball"));
  EXPECT_TRUE(skeleton.find("Tip"));
  expect_chain(clips[0], Vec3::Zero(), Vec3::Zero(), 0.0);
}

TEST(FbxImportPivots, ANameTwoMovedNodesBearIsAnError) {
  // A second Knee, beside the first: the channel "Knee" could be either.
  const std::string extra = "\tModel: 60, \"Model::Knee\", \"LimbNode\" {\n\t\tVersion: 232\n\t}\n";
  const std::string error = message(chain_fbx("", extra, "\tC: \"OO\",60,10\n"));
  EXPECT_NE(error.find("node 'Knee', a name 2 nodes bear"), std::string::npos) << error;
}

}  // namespace
}  // namespace mg
