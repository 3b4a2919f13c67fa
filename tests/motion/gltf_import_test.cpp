// glTF in: what the project's glTF writer writes reads back to the same world positions (a CMU
// rig, a static root above the hips, several animations); a rig built here by glTF's rules alone
// (joints resting turned along their bones, an armature turned and scaled by 0.01 above them,
// LINEAR, STEP and CUBICSPLINE keys at half the rate sampled, tracks in sparse accessors) reads
// where those rules put its joints; and files that cannot be read are one error each.
#include "motiongraph/motion/gltf_import.h"

#include <cmath>
#include <functional>
#include <numeric>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "motion/max_apart.h"
#include "motion/static_root_bvh.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/export/gltf_writer.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "test_data.h"

namespace mg {
namespace {

std::vector<Clip> read_back(const std::string& bytes, const GltfImportSettings& settings = {}) {
  auto clips = clips_from_gltf(bytes, "test.glb", settings);
  EXPECT_TRUE(clips) << clips.error().message;
  return clips ? std::move(*clips) : std::vector<Clip>();
}

TEST(GltfImport, OurOwnFileReadsBackToTheSameJointsAndRate) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  auto bytes = write_glb(clip.skeleton, clip.motion, "walk");
  ASSERT_TRUE(bytes);
  const std::vector<Clip> clips = read_back(*bytes);
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0].name, "walk");
  EXPECT_EQ(clips[0].motion.fps, clip.motion.fps);  // 120, from float32 key times
  EXPECT_EQ(clips[0].skeleton.joint_count(), clip.skeleton.joint_count());
  EXPECT_LT(test::max_apart(clip, clips[0]), 2e-5);  // float32 keys
  EXPECT_EQ(clips[0].skeleton.translated_joints().size(), 1u);
  // The end sites (lhand_end, ...: nodes no animation moves) are end sites again, so that a
  // BVH written from it has the joints the clip had, however often it goes round.
  int end_sites = 0;
  for (const JointDef& joint : clip.skeleton.joints()) {
    const std::optional<int> read = clips[0].skeleton.find(joint.name);
    ASSERT_TRUE(read) << joint.name;
    EXPECT_EQ(clips[0].skeleton.joint(*read).end_site, joint.end_site) << joint.name;
    end_sites += joint.end_site ? 1 : 0;
  }
  EXPECT_GE(end_sites, 5);
  const Clip bvh = test::import_bvh(write_bvh(clips[0].skeleton, clips[0].motion, BvhWriteSettings{}));
  EXPECT_EQ(bvh.skeleton.joint_count(), clip.skeleton.joint_count());
}

// The same model as .gltf text: one JSON file, its buffer a base64 data URI, read back to the
// very clips the .glb gives.
TEST(GltfImport, OurGltfTextReadsBackAsOurGlbDoes) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip run = test::load_data_clip("cmu/16/16_35.amc");
  const std::vector<GltfAnimation> set = {{"walk", &walk.motion}, {"run", &run.motion}};
  auto glb = write_glb(walk.skeleton, set);
  auto text = write_gltf(walk.skeleton, set);
  ASSERT_TRUE(glb && text);
  ASSERT_EQ(text->rfind("{", 0), 0u);  // JSON, not the binary container
  EXPECT_NE(text->find("\"uri\":\"data:application/octet-stream;base64,"), std::string::npos);
  const std::vector<Clip> from_glb = read_back(*glb), from_text = read_back(*text);
  ASSERT_EQ(from_text.size(), 2u);
  ASSERT_EQ(from_glb.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(from_text[i].name, from_glb[i].name);
    EXPECT_EQ(from_text[i].motion.fps, from_glb[i].motion.fps);
    EXPECT_EQ(from_text[i].motion.local_rotations, from_glb[i].motion.local_rotations);  // the same float32 keys
    EXPECT_EQ(from_text[i].motion.local_translations_m, from_glb[i].motion.local_translations_m);
  }
  EXPECT_LT(test::max_apart(walk, from_text[0]), 2e-5);
}

TEST(GltfImport, AStaticRootAboveTheHipsIsFoldedAsForBvh) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Clip clip = test::import_bvh(test::static_root_bvh(plain, Vec3(0.3, 0.0, -0.2)));
  ASSERT_FALSE(clip.skeleton.static_ancestors().empty());
  auto bytes = write_glb(clip.skeleton, clip.motion, "walk");
  ASSERT_TRUE(bytes);
  const std::vector<Clip> clips = read_back(*bytes);
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0].skeleton.joint(0).name, clip.skeleton.joint(0).name);  // the hips, travelling
  EXPECT_EQ(clips[0].skeleton.static_ancestors().size(), clip.skeleton.static_ancestors().size());
  EXPECT_LT(test::max_apart(clip, clips[0]), 2e-5);
}

TEST(GltfImport, EveryAnimationIsAClipOnOneSkeleton) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip jog = test::load_data_clip("cmu/16/16_35.amc");
  const Motion jog30 = *resample(jog.motion, 30.0);
  const std::vector<GltfAnimation> set{{"walk", &walk.motion}, {"jog", &jog30}, {"walk", &walk.motion}};
  auto bytes = write_glb(walk.skeleton, set);
  ASSERT_TRUE(bytes);
  const std::vector<Clip> clips = read_back(*bytes);
  ASSERT_EQ(clips.size(), 3u);
  EXPECT_EQ(clips[1].name, "jog");
  EXPECT_EQ(clips[1].motion.fps, 30.0);
  Clip jog_at30 = jog;
  jog_at30.motion = jog30;
  EXPECT_LT(test::max_apart(jog_at30, clips[1]), 2e-5);
  // The writer named the third "walk_2" (names repeat in no glTF file it writes).
  EXPECT_EQ(clips[2].name, "walk_2");
  // A rate given samples between the keys.
  GltfImportSettings at60;
  at60.fps_override = 60.0;
  const std::vector<Clip> resampled = read_back(*bytes, at60);
  EXPECT_EQ(resampled[1].motion.fps, 60.0);
  EXPECT_EQ(resampled[1].motion.frame_count, 2 * jog30.frame_count - 1);
}

// --- A rig built by glTF's rules alone ---

struct Built {
  tinygltf::Model model;
  std::vector<uint8_t>& buffer() { return model.buffers[0].data; }

  Built() { model.buffers.emplace_back(); model.asset.version = "2.0"; }

  // Bytes appended to the buffer (4-aligned), as a buffer view of their own.
  int view(const void* data, size_t bytes) {
    const size_t offset = (buffer().size() + 3) / 4 * 4;
    buffer().resize(offset + bytes);
    std::memcpy(buffer().data() + offset, data, bytes);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = bytes;
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size()) - 1;
  }

  int floats(const std::vector<float>& values, int type) {
    tinygltf::Accessor accessor;
    accessor.bufferView = view(values.data(), values.size() * sizeof(float));
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.type = type;
    accessor.count = values.size() / static_cast<size_t>(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)));
    if (type == TINYGLTF_TYPE_SCALAR) {
      accessor.minValues = {*std::min_element(values.begin(), values.end())};
      accessor.maxValues = {*std::max_element(values.begin(), values.end())};
    }
    model.accessors.push_back(accessor);
    return static_cast<int>(model.accessors.size()) - 1;
  }

  // Makes an accessor sparse: `values` (floats, its elements' width each) replace its elements
  // at `at`, stored as unsigned bytes, shorts or ints (`index_type`).
  void make_sparse(int accessor, const std::vector<uint32_t>& at, const std::vector<float>& values, int index_type) {
    const size_t size = static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(index_type)));
    std::vector<uint8_t> bytes(at.size() * size);
    for (size_t i = 0; i < at.size(); ++i) std::memcpy(bytes.data() + i * size, &at[i], size);  // little-endian
    auto& sparse = model.accessors[static_cast<size_t>(accessor)].sparse;
    sparse.isSparse = true;
    sparse.count = static_cast<int>(at.size());
    sparse.indices.bufferView = view(bytes.data(), bytes.size());
    sparse.indices.byteOffset = 0;
    sparse.indices.componentType = index_type;
    sparse.values.bufferView = view(values.data(), values.size() * sizeof(float));
    sparse.values.byteOffset = 0;
  }

  std::string glb() {
    tinygltf::TinyGLTF writer;
    std::ostringstream out;
    EXPECT_TRUE(writer.WriteGltfSceneToStream(&model, out, false, true));
    return out.str();
  }
};

Quat turn(double degrees, const Vec3& axis) { return Quat(Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized())); }

// An armature (turned 30 degrees about y, scaled 0.01: lengths in centimetres) above a chain
// hips -> thigh -> shin -> foot whose joints rest turned along the bones (each +y down the leg,
// as Blender makes bones), and a spine. Keys every 1/15 s for 1 s: the hips travel and turn
// (LINEAR), the thigh swings (LINEAR), the shin kicks (STEP), the foot turns by CUBICSPLINE.
struct Rig {
  Built built;
  std::vector<Vec3> t;  // rest translations, by node
  std::vector<Quat> r;  // rest rotations
  std::vector<int> parent;
  static constexpr int kKeys = 16;
  static constexpr double kKeyRate = 15.0;

  static Quat hips_turn(double s) { return turn(40.0 * s, Vec3::UnitY()); }
  // Blender's object animation: the armature itself moved and turned.
  static Vec3 armature_at(double s) { return Vec3(1.0 + 2.0 * s, 0.0, 2.0 - s); }
  static Quat armature_turn(double s) { return turn(30.0 + 50.0 * s, Vec3::UnitY()); }
  bool armature_moves = false;
  static Vec3 hips_at(double s) { return Vec3(10.0 * s, 95.0 + 3.0 * std::sin(6 * s), 120.0 * s); }
  static Quat thigh_swing(double s) { return turn(180.0, Vec3::UnitZ()) * turn(35.0 * std::sin(5 * s), Vec3::UnitX()); }
  static Quat shin_kick(int key) { return turn(key % 2 ? 20.0 : 5.0, Vec3::UnitX()); }
  static Quat foot_turn(int key) { return turn(90.0, Vec3::UnitX()) * turn(4.0 * key, Vec3::UnitZ()); }

  explicit Rig(bool move_armature = false) : armature_moves(move_armature) {
    // Nodes: 0 armature, 1 hips, 2 thigh, 3 shin, 4 foot, 5 spine, 6 mesh-less extra under the scene.
    t = {Vec3(1, 0, 2), Vec3(0, 95, 0), Vec3(10, -5, 0), Vec3(0, 45, 0), Vec3(0, 42, 0), Vec3(0, 20, 0)};
    r = {turn(30, Vec3::UnitY()), Quat::Identity(), turn(180, Vec3::UnitZ()), Quat::Identity(), turn(90, Vec3::UnitX()),
         turn(10, Vec3(1, 0, 1))};
    parent = {-1, 0, 1, 2, 3, 1};
    const char* names[] = {"Armature", "Hips", "Thigh", "Shin", "Foot", "Spine"};
    for (size_t n = 0; n < t.size(); ++n) {
      tinygltf::Node node;
      node.name = names[n];
      node.translation = {t[n].x(), t[n].y(), t[n].z()};
      node.rotation = {r[n].x(), r[n].y(), r[n].z(), r[n].w()};
      if (n == 0) node.scale = {0.01, 0.01, 0.01};
      built.model.nodes.push_back(node);
    }
    for (size_t n = 1; n < t.size(); ++n) built.model.nodes[static_cast<size_t>(parent[n])].children.push_back(static_cast<int>(n));
    tinygltf::Skin skin;
    skin.joints = {1, 2, 3, 4, 5};
    built.model.skins.push_back(skin);
    tinygltf::Scene scene;
    scene.nodes = {0};
    built.model.scenes.push_back(scene);
    built.model.defaultScene = 0;

    std::vector<float> times, hips_t, hips_r, thigh_r, shin_r, foot_r, armature_t, armature_r;
    const auto push_q = [](std::vector<float>& out, const Quat& q) {
      out.insert(out.end(), {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()), static_cast<float>(q.w())});
    };
    for (int k = 0; k < kKeys; ++k) {
      const double s = k / kKeyRate;
      times.push_back(static_cast<float>(s));
      const Vec3 p = hips_at(s);
      hips_t.insert(hips_t.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
      push_q(hips_r, hips_turn(s));
      const Vec3 a = armature_at(s);
      armature_t.insert(armature_t.end(), {static_cast<float>(a.x()), static_cast<float>(a.y()), static_cast<float>(a.z())});
      push_q(armature_r, armature_turn(s));
      push_q(thigh_r, thigh_swing(s));
      push_q(shin_r, shin_kick(k));
      // CUBICSPLINE: in-tangent, value, out-tangent (zero tangents).
      push_q(foot_r, Quat(0, 0, 0, 0));
      push_q(foot_r, foot_turn(k));
      push_q(foot_r, Quat(0, 0, 0, 0));
    }
    const int input = built.floats(times, TINYGLTF_TYPE_SCALAR);
    tinygltf::Animation animation;
    animation.name = "kick";
    const auto track = [&](int node, const char* path, const std::vector<float>& values, int type, const char* rule) {
      tinygltf::AnimationSampler sampler;
      sampler.input = input;
      sampler.output = built.floats(values, type);
      sampler.interpolation = rule;
      animation.samplers.push_back(sampler);
      tinygltf::AnimationChannel channel;
      channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
      channel.target_node = node;
      channel.target_path = path;
      animation.channels.push_back(channel);
    };
    track(1, "translation", hips_t, TINYGLTF_TYPE_VEC3, "LINEAR");
    track(1, "rotation", hips_r, TINYGLTF_TYPE_VEC4, "LINEAR");
    track(2, "rotation", thigh_r, TINYGLTF_TYPE_VEC4, "LINEAR");
    track(3, "rotation", shin_r, TINYGLTF_TYPE_VEC4, "STEP");
    track(4, "rotation", foot_r, TINYGLTF_TYPE_VEC4, "CUBICSPLINE");
    if (armature_moves) {
      track(0, "translation", armature_t, TINYGLTF_TYPE_VEC3, "LINEAR");
      track(0, "rotation", armature_r, TINYGLTF_TYPE_VEC4, "LINEAR");
    }
    built.model.animations.push_back(animation);
  }

  // World positions (metres) of nodes 1..5 at time s, by glTF's rules: local = T R S, the
  // animated values at exact keys (every second frame at 30 fps) or between them as each rule says.
  std::vector<Vec3> world_at(int frame_at_30) const {
    const double s = frame_at_30 / 30.0;
    const int key = frame_at_30 / 2;
    const bool between = frame_at_30 % 2 == 1;
    std::vector<Vec3> tt = t;
    std::vector<Quat> rr = r;
    if (!between) {
      tt[1] = hips_at(s);
      rr[1] = hips_turn(s);
      rr[2] = thigh_swing(s);
      if (armature_moves) tt[0] = armature_at(s), rr[0] = armature_turn(s);
    } else {
      const double s0 = key / kKeyRate, s1 = (key + 1) / kKeyRate;
      tt[1] = 0.5 * (hips_at(s0) + hips_at(s1));
      rr[1] = hips_turn(s0).slerp(0.5, hips_turn(s1));
      rr[2] = thigh_swing(s0).slerp(0.5, thigh_swing(s1));
      if (armature_moves) {
        tt[0] = 0.5 * (armature_at(s0) + armature_at(s1));
        rr[0] = armature_turn(s0).slerp(0.5, armature_turn(s1));
      }
    }
    rr[3] = shin_kick(key);  // STEP: the key before
    // Hermite with zero tangents at s = 1/2: the mean of the two values, renormalised.
    rr[4] = between ? Quat((0.5 * (foot_turn(key).coeffs() + foot_turn(key + 1).coeffs())).normalized())
                    : foot_turn(key);
    std::vector<Eigen::Affine3d> world(t.size());
    for (size_t n = 0; n < t.size(); ++n) {
      Eigen::Affine3d local = Eigen::Translation3d(tt[n]) * rr[n];
      if (n == 0) local = local * Eigen::Scaling(0.01);
      world[n] = n == 0 ? local : world[static_cast<size_t>(parent[n])] * local;
    }
    std::vector<Vec3> out;
    for (size_t n = 1; n < t.size(); ++n) out.push_back(world[n].translation());
    return out;
  }
};

// World positions of the rig's clip against glTF's rules, over every frame (at 30 fps).
double worst_against_rules(const Rig& rig, const Clip& clip) {
  EXPECT_EQ(clip.motion.fps, 30.0);
  EXPECT_EQ(clip.motion.frame_count, 2 * (Rig::kKeys - 1) + 1);
  const std::vector<Vec3> positions = world_positions(clip.skeleton, clip.motion);
  double worst = 0.0;
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    const std::vector<Vec3> want = rig.world_at(f);
    for (int j = 0; j < 5; ++j) worst = std::max(worst, (positions[static_cast<size_t>(f * 5 + j)] - want[static_cast<size_t>(j)]).norm());
  }
  return worst;
}

TEST(GltfImport, ARigRestingTurnedUnderAScaledArmatureReadsWhereGltfPutsItsJoints) {
  Rig rig;
  GltfImportSettings at30;
  at30.fps_override = 30.0;
  const std::vector<Clip> clips = read_back(rig.built.glb(), at30);
  ASSERT_EQ(clips.size(), 1u);
  const Clip& clip = clips[0];
  EXPECT_EQ(clip.name, "kick");
  ASSERT_EQ(clip.skeleton.joint_count(), 5);
  EXPECT_EQ(clip.skeleton.joint(0).name, "Hips");
  EXPECT_LT(worst_against_rules(rig, clip), 1e-5);  // float32 keys, metres
  // Re-expressed on its rest pose: every joint at rest has the identity rotation, its offset the
  // rest offset in the world's axes (the shin 0.45 m straight down from the knee: the thigh
  // rests turned 180 degrees, and the armature's 30-degree turn is in the hips' frame).
  const Vec3 shin = clip.skeleton.joint(*clip.skeleton.find("Shin")).rest_offset_m;
  EXPECT_LT((shin - Vec3(0, -0.45, 0)).norm(), 1e-9) << shin.transpose();
  // Keys 15 a second are sampled at 30 fps without a rate given (a curve between them).
  const std::vector<Clip> at_keys = read_back(rig.built.glb());
  EXPECT_LT(worst_against_rules(rig, at_keys[0]), 1e-5);
  // The armature moved and turned by its own animation (Blender's object animation) carries
  // the skeleton with it.
  Rig moved(true);
  const std::vector<Clip> carried = read_back(moved.built.glb());
  ASSERT_EQ(carried.size(), 1u);
  EXPECT_LT(worst_against_rules(moved, carried[0]), 1e-5);
  // Skins of parts (a mesh each) make one skeleton of them all.
  Rig parts;
  parts.built.model.skins = {tinygltf::Skin(), tinygltf::Skin()};
  parts.built.model.skins[0].joints = {4};
  parts.built.model.skins[1].joints = {1, 2, 3, 5};
  const std::vector<Clip> joined = read_back(parts.built.glb());
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_EQ(joined[0].skeleton.joint_count(), 5);
  EXPECT_LT(worst_against_rules(parts, joined[0]), 1e-5);
}

// What else a scene holds: a camera flying on its own (its animation is no clip, and its keys
// set no rate), a texture in a format no decoder here knows (KTX2).
TEST(GltfImport, ACameraAndATextureAreLeftAlone) {
  Rig rig;
  tinygltf::Model& model = rig.built.model;
  tinygltf::Node camera;
  camera.name = "Camera";
  model.nodes.push_back(camera);
  model.scenes[0].nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
  std::vector<float> times, path;
  for (int k = 0; k < 121; ++k) {
    times.push_back(k / 120.0f);
    path.insert(path.end(), {static_cast<float>(k), 2.0f, 5.0f});
  }
  tinygltf::Animation fly;
  fly.name = "fly";
  tinygltf::AnimationSampler sampler;
  sampler.input = rig.built.floats(times, TINYGLTF_TYPE_SCALAR);
  sampler.output = rig.built.floats(path, TINYGLTF_TYPE_VEC3);
  fly.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = static_cast<int>(model.nodes.size()) - 1;
  channel.target_path = "translation";
  fly.channels.push_back(channel);
  model.animations.push_back(fly);
  tinygltf::Image image;
  image.mimeType = "image/ktx2";
  image.bufferView = 0;
  model.images.push_back(image);
  const std::string bytes = rig.built.glb();
  const std::vector<Clip> clips = read_back(bytes);
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0].name, "kick");
  EXPECT_LT(worst_against_rules(rig, clips[0]), 1e-5);
  auto names = gltf_animation_names(bytes, "scene.glb");
  ASSERT_TRUE(names) << names.error().message;
  EXPECT_EQ(*names, std::vector<std::string>{"kick"});
}

// A long take keyed at 120 fps in float32 (5 minutes, keys from t = 1000 s): 120 fps exactly,
// each frame on its key.
TEST(GltfImport, TheRateOfALongLateTakeIsItsKeys) {
  Built built;
  tinygltf::Node node;
  node.name = "Hips";
  built.model.nodes.push_back(node);
  built.model.scenes.push_back(tinygltf::Scene());
  built.model.scenes[0].nodes = {0};
  std::vector<float> times, positions;
  const int keys = 300 * 120 + 1;
  for (int k = 0; k < keys; ++k) {
    times.push_back(static_cast<float>(1000.0 + k / 120.0));
    positions.insert(positions.end(), {static_cast<float>(std::sin(k * 0.01)), 1.0f, static_cast<float>(k % 7)});
  }
  tinygltf::Animation take;
  tinygltf::AnimationSampler sampler;
  sampler.input = built.floats(times, TINYGLTF_TYPE_SCALAR);
  sampler.output = built.floats(positions, TINYGLTF_TYPE_VEC3);
  take.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 0;
  channel.target_path = "translation";
  take.channels.push_back(channel);
  built.model.animations.push_back(take);
  GltfImportSettings as_read;
  as_read.fold_static_root = false;
  const std::vector<Clip> clips = read_back(built.glb(), as_read);
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0].name, "animation_1");
  EXPECT_EQ(clips[0].motion.fps, 120.0);
  ASSERT_EQ(clips[0].motion.frame_count, keys);
  double worst = 0.0;
  for (int k = 0; k < keys; ++k) {
    const Vec3 want(positions[3 * static_cast<size_t>(k)], positions[3 * static_cast<size_t>(k) + 1],
                    positions[3 * static_cast<size_t>(k) + 2]);
    worst = std::max(worst, (clips[0].motion.translations(k)[0] - want).norm());
  }
  EXPECT_LT(worst, 1e-6);  // STEP-like values (k % 7): off by whole units if a frame fell between keys
}

// A sparse accessor (glTF 2.0, "Sparse Accessors"): its values replace those of its buffer view,
// or of zeros where it has none, at its indices.
TEST(GltfImport, SparseAccessorsReplaceTheirBaseAtTheirIndices) {
  const Rig plain;
  const tinygltf::Animation& kick = plain.built.model.animations[0];
  const auto floats_of = [&](int accessor) {
    const tinygltf::Accessor& a = plain.built.model.accessors[static_cast<size_t>(accessor)];
    const tinygltf::BufferView& v = plain.built.model.bufferViews[static_cast<size_t>(a.bufferView)];
    std::vector<float> out(v.byteLength / sizeof(float));
    std::memcpy(out.data(), plain.built.model.buffers[0].data.data() + v.byteOffset, v.byteLength);
    return out;
  };
  const int hips_t = kick.samplers[0].output, thigh_r = kick.samplers[2].output;
  Rig rig;
  // The hips' translation: no buffer view (zeros), every key given sparse, in unsigned bytes.
  std::vector<uint32_t> every(Rig::kKeys);
  std::iota(every.begin(), every.end(), 0u);
  rig.built.model.accessors[static_cast<size_t>(hips_t)].bufferView = -1;
  rig.built.make_sparse(hips_t, every, floats_of(hips_t), TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
  // The thigh's rotation: a view whose keys 3, 7 and 11 do not turn, put right sparse, in
  // unsigned shorts.
  std::vector<float> wrong = floats_of(thigh_r), right;
  for (size_t k : {3, 7, 11}) {
    for (size_t c = 0; c < 4; ++c) right.push_back(wrong[4 * k + c]);
    for (size_t c = 0; c < 4; ++c) wrong[4 * k + c] = c == 3 ? 1.0f : 0.0f;
  }
  rig.built.model.accessors[static_cast<size_t>(thigh_r)].bufferView =
      rig.built.view(wrong.data(), wrong.size() * sizeof(float));
  rig.built.make_sparse(thigh_r, {3, 7, 11}, right, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  GltfImportSettings at30;
  at30.fps_override = 30.0;
  const std::vector<Clip> clips = read_back(rig.built.glb(), at30);
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_LT(worst_against_rules(rig, clips[0]), 1e-5);
  // Without either one's sparse values the joints are elsewhere: the base alone is read.
  for (const int accessor : {hips_t, thigh_r}) {
    Rig base = rig;
    base.built.model.accessors[static_cast<size_t>(accessor)].sparse.isSparse = false;
    const std::vector<Clip> read = read_back(base.built.glb(), at30);
    ASSERT_EQ(read.size(), 1u);
    EXPECT_GT(worst_against_rules(rig, read[0]), 0.05) << accessor;
  }

  // Sparse parts a file gets wrong: one error each.
  const auto message = [&](const std::function<void(Rig&)>& spoil) {
    Rig bad = rig;
    spoil(bad);
    auto read = clips_from_gltf(bad.built.glb(), "bad.glb", at30);
    EXPECT_FALSE(read);
    return read ? std::string() : read.error().message;
  };
  const auto has = [](const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; };
  const int u8 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, u16 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  const std::string unordered = message([&](Rig& r) { r.built.make_sparse(thigh_r, {7, 3, 11}, right, u16); });
  EXPECT_TRUE(has(unordered, fmt::format("accessor {} has sparse index 1 at 3: sparse indices must increase", thigh_r)))
      << unordered;
  const std::string beyond =
      message([&](Rig& r) { r.built.make_sparse(thigh_r, {3, 7, 16}, right, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT); });
  EXPECT_TRUE(has(beyond, fmt::format("accessor {} has sparse index 2 at 16", thigh_r))) << beyond;
  const std::string signed_indices =
      message([&](Rig& r) { r.built.make_sparse(thigh_r, {3, 7, 11}, right, TINYGLTF_COMPONENT_TYPE_SHORT); });
  EXPECT_TRUE(has(signed_indices, "has sparse indices that are not unsigned integers")) << signed_indices;
  const std::string too_many =
      message([&](Rig& r) { r.built.model.accessors[static_cast<size_t>(thigh_r)].sparse.count = 17; });
  EXPECT_TRUE(has(too_many, fmt::format("accessor {} replaces 17 of its 16 elements", thigh_r))) << too_many;
  const std::string short_values =
      message([&](Rig& r) { r.built.make_sparse(thigh_r, {3, 7, 11}, {right.begin(), right.begin() + 8}, u8); });
  EXPECT_TRUE(has(short_values, fmt::format("accessor {} (sparse values) runs past its buffer", thigh_r)))
      << short_values;
  const std::string no_view = message(
      [&](Rig& r) { r.built.model.accessors[static_cast<size_t>(hips_t)].sparse.indices.bufferView = 99; });
  EXPECT_TRUE(has(no_view, fmt::format("accessor {} (sparse indices) names buffer view 99", hips_t))) << no_view;
}

TEST(GltfImport, FilesThatCannotBeReadAreOneErrorEach) {
  const auto message = [](const std::string& bytes) {
    auto clips = clips_from_gltf(bytes, "bad.glb", {});
    EXPECT_FALSE(clips);
    return clips ? std::string() : clips.error().file + ": " + clips.error().message;
  };
  EXPECT_NE(message(std::string("glTF\x02\0\0\0garbage", 15)).find("bad.glb: cannot read glTF"), std::string::npos);
  EXPECT_NE(message("{\"asset\": {\"version\": \"2.0\"}}").find("has no animation"), std::string::npos);
  Rig scaled;
  scaled.built.model.nodes[3].scale = {1.0, 2.0, 1.0};
  EXPECT_NE(message(scaled.built.glb()).find("node 'Shin' is scaled"), std::string::npos);
  Rig squashed;
  squashed.built.model.nodes[0].scale = {0.01, 0.02, 0.01};
  EXPECT_NE(message(squashed.built.glb()).find("node 'Armature' above the skeleton scales unevenly"), std::string::npos);
  Rig scale_track;
  {
    tinygltf::Animation& animation = scale_track.built.model.animations[0];
    tinygltf::AnimationSampler sampler = animation.samplers[0];
    std::vector<float> scales;
    for (int k = 0; k < Rig::kKeys; ++k) scales.insert(scales.end(), {1.0f, 1.0f + 0.1f * k, 1.0f});
    sampler.output = scale_track.built.floats(scales, TINYGLTF_TYPE_VEC3);
    animation.samplers.push_back(sampler);
    tinygltf::AnimationChannel channel;
    channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
    channel.target_node = 2;
    channel.target_path = "scale";
    animation.channels.push_back(channel);
  }
  EXPECT_NE(message(scale_track.built.glb()).find("animation 'kick' scales node 'Thigh'"), std::string::npos);
  // Indices and sizes the file gets wrong: no crash, one error each.
  Rig no_view;
  no_view.built.model.accessors[0].bufferView = 99;
  EXPECT_NE(message(no_view.built.glb()).find("accessor 0 names buffer view 99, which does not exist"), std::string::npos);
  Rig too_many;
  too_many.built.model.accessors[1].count = size_t{1} << 61;
  EXPECT_NE(message(too_many.built.glb()).find("accessor 1 runs past its buffer"), std::string::npos);
  Rig far_apart;
  {
    std::vector<float> times(Rig::kKeys);
    for (int k = 0; k < Rig::kKeys; ++k) times[static_cast<size_t>(k)] = k == Rig::kKeys - 1 ? 1e9f : k / 15.0f;
    const int input = far_apart.built.floats(times, TINYGLTF_TYPE_SCALAR);
    for (auto& sampler : far_apart.built.model.animations[0].samplers) sampler.input = input;
  }
  EXPECT_NE(message(far_apart.built.glb()).find("animation 'kick' would be"), std::string::npos);
  Rig aimed_nowhere;
  aimed_nowhere.built.model.animations[0].channels[1].target_node = 99;
  EXPECT_NE(message(aimed_nowhere.built.glb()).find("a channel aimed at node 99, which does not exist"),
            std::string::npos);
  std::string version_one = Rig().built.glb();
  version_one[4] = 1;  // the header's version, after the magic
  EXPECT_NE(message(version_one).find("GLB version 1: only glTF 2.0 is read"), std::string::npos);
  Rig cycle;
  cycle.built.model.nodes[5].children = {1};  // the spine above the hips, which hold it
  EXPECT_NE(message(cycle.built.glb()).find("a child that is not a node of one parent"), std::string::npos);
  Rig loop;
  loop.built.model.nodes[0].children.clear();  // nothing above the hips: hips -> spine -> hips
  loop.built.model.nodes[5].children = {1};
  loop.built.model.scenes[0].nodes = {0};
  EXPECT_NE(message(loop.built.glb()).find("form a cycle"), std::string::npos);
  GltfImportSettings negative;
  negative.fps_override = -1.0;
  EXPECT_FALSE(clips_from_gltf(Rig().built.glb(), "x.glb", negative));
}

}  // namespace
}  // namespace mg
