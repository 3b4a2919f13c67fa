#include "motiongraph/export/gltf_writer.h"

#include <cstring>
#include <map>
#include <set>
#include <random>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "export/random_motion.h"
#include "motion/static_root_bvh.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

using Affine = Eigen::Affine3d;

// The file read back by tinygltf's own parser, and evaluated here from the glTF rules alone
// (node TRS, animation keys, skins), not from anything the writer computes.
struct Glb {
  tinygltf::Model model;

  explicit Glb(const std::string& bytes) {
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    const bool ok = loader.LoadBinaryFromMemory(&model, &error, &warning,
                                                reinterpret_cast<const unsigned char*>(bytes.data()),
                                                static_cast<unsigned>(bytes.size()));
    EXPECT_TRUE(ok) << error;
    EXPECT_EQ(warning, "");
  }

  template <class T>
  std::vector<T> values(int accessor_index, int component_type, int components) const {
    const tinygltf::Accessor& accessor = model.accessors.at(accessor_index);
    EXPECT_EQ(accessor.componentType, component_type);
    EXPECT_EQ(tinygltf::GetNumComponentsInType(accessor.type), components);
    const tinygltf::BufferView& view = model.bufferViews.at(accessor.bufferView);
    EXPECT_EQ(view.byteStride, 0u);
    const size_t count = accessor.count * components;
    EXPECT_LE(accessor.byteOffset + count * sizeof(T), view.byteLength);
    std::vector<T> out(count);
    std::memcpy(out.data(), model.buffers.at(view.buffer).data.data() + view.byteOffset + accessor.byteOffset,
                count * sizeof(T));
    return out;
  }
  std::vector<float> floats(int accessor, int components) const {
    return values<float>(accessor, TINYGLTF_COMPONENT_TYPE_FLOAT, components);
  }

  int node_named(const std::string& name) const {
    for (size_t n = 0; n < model.nodes.size(); ++n) {
      if (model.nodes[n].name == name) return static_cast<int>(n);
    }
    ADD_FAILURE() << "no node " << name;
    return -1;
  }

  // Every node's world transform at key `frame` of animation `animation_index` (frame < 0: the
  // nodes' own TRS, no animation).
  std::vector<Affine> world(int frame, int animation_index = 0) const {
    const size_t nodes = model.nodes.size();
    std::vector<Vec3> translation(nodes, Vec3::Zero());
    std::vector<Quat> rotation(nodes, Quat::Identity());
    for (size_t n = 0; n < nodes; ++n) {
      const auto& t = model.nodes[n].translation;
      const auto& r = model.nodes[n].rotation;
      EXPECT_TRUE(model.nodes[n].matrix.empty() && model.nodes[n].scale.empty());
      if (!t.empty()) translation[n] = Vec3(t[0], t[1], t[2]);
      if (!r.empty()) rotation[n] = Quat(r[3], r[0], r[1], r[2]);
    }
    if (frame >= 0) {
      const tinygltf::Animation& animation = model.animations.at(animation_index);
      for (const tinygltf::AnimationChannel& channel : animation.channels) {
        const tinygltf::AnimationSampler& sampler = animation.samplers.at(channel.sampler);
        EXPECT_EQ(sampler.interpolation, "LINEAR");
        if (channel.target_path == "rotation") {
          const auto q = floats(sampler.output, 4);
          rotation[channel.target_node] = Quat(q[4 * frame + 3], q[4 * frame], q[4 * frame + 1], q[4 * frame + 2]);
        } else {
          EXPECT_EQ(channel.target_path, "translation");
          const auto t = floats(sampler.output, 3);
          translation[channel.target_node] = Vec3(t[3 * frame], t[3 * frame + 1], t[3 * frame + 2]);
        }
      }
    }
    std::vector<Affine> out(nodes, Affine::Identity());
    std::vector<int> parent(nodes, -1);
    for (size_t n = 0; n < nodes; ++n) {
      for (int child : model.nodes[n].children) parent[child] = static_cast<int>(n);
    }
    // Parents come first in the writer's order; check that instead of sorting.
    for (size_t n = 0; n < nodes; ++n) {
      EXPECT_LT(parent[n], static_cast<int>(n));
      const Affine local = Eigen::Translation3d(translation[n]) * rotation[n].normalized();
      out[n] = parent[n] < 0 ? local : out[parent[n]] * local;
    }
    return out;
  }
};

// The largest distance between a joint's world position by forward kinematics and its node's
// world position read from the file, over all joints and frames.
double max_world_error(const Glb& glb, const Skeleton& skeleton, const Motion& motion, int animation = 0) {
  std::vector<int> node_of(skeleton.joint_count());
  for (int j = 0; j < skeleton.joint_count(); ++j) node_of[j] = glb.node_named(skeleton.joint(j).name);
  std::vector<Vec3> positions(skeleton.joint_count());
  std::vector<Quat> rotations(skeleton.joint_count());
  double worst = 0.0;
  for (int f = 0; f < motion.frame_count; ++f) {
    forward_kinematics(skeleton, motion, f, positions, rotations);
    const auto world = glb.world(f, animation);
    for (int j = 0; j < skeleton.joint_count(); ++j) {
      worst = std::max(worst, (world[node_of[j]].translation() - positions[j]).norm());
    }
  }
  return worst;
}

Glb written(const Skeleton& skeleton, const Motion& motion, const GltfWriteSettings& settings = {}) {
  auto bytes = write_glb(skeleton, motion, "motion", settings);
  EXPECT_TRUE(bytes) << bytes.error().message;
  return Glb(bytes ? *bytes : std::string());
}

TEST(GltfWriter, NodesPlayedByTheFileRulesAreWhereForwardKinematicsPutsTheJoints) {
  for (const char* file : {"cmu/16/16_15.amc", "cmu/16/16_35.amc"}) {
    const Clip clip = test::load_data_clip(file);
    const Glb glb = written(clip.skeleton, clip.motion);
    EXPECT_EQ(glb.model.asset.version, "2.0");
    ASSERT_EQ(glb.model.animations.size(), 1u);
    // Key times are the frames' times; every track has one key per frame.
    const auto& animation = glb.model.animations[0];
    const auto times = glb.floats(animation.samplers.at(0).input, 1);
    ASSERT_EQ(static_cast<int>(times.size()), clip.motion.frame_count);
    for (int f = 0; f < clip.motion.frame_count; ++f) EXPECT_FLOAT_EQ(times[f], static_cast<float>(f / clip.motion.fps));
    EXPECT_LT(max_world_error(glb, clip.skeleton, clip.motion), 1e-5) << file;  // float32 of metres
  }
}

TEST(GltfWriter, AStaticRootAboveTheHipsIsWrittenBackAboveThem) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Vec3 root_at(-2.0, 0.1, 3.0);
  const Quat root_turn(Eigen::AngleAxisd(-2.5, Vec3(0.1, 1.0, 0.2).normalized()));
  const Clip clip = test::import_bvh(test::static_root_bvh(plain, root_at, root_turn));
  ASSERT_EQ(clip.skeleton.static_ancestors().size(), 1u);
  ASSERT_GT(clip.skeleton.translated_joints().size(), 1u);  // every joint has position channels
  const Glb glb = written(clip.skeleton, clip.motion);
  const int root = glb.node_named(test::kStaticRootName);
  const int hips = glb.node_named(clip.skeleton.joint(0).name);
  ASSERT_EQ(glb.model.scenes.at(0).nodes.at(0), root);
  EXPECT_EQ(glb.model.nodes[root].children, std::vector<int>{hips});
  for (int f : {0, clip.motion.frame_count / 2}) {
    EXPECT_LT((glb.world(f)[root].translation() - root_at).norm(), 1e-6);
    EXPECT_LT(Quat(glb.world(f)[root].rotation()).angularDistance(root_turn), 1e-6);
  }
  EXPECT_LT(max_world_error(glb, clip.skeleton, clip.motion), 1e-5);
}

TEST(GltfWriter, TheSkinBindsEachBoneOfTheStickFigureToItsJointAtRest) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const Glb glb = written(clip.skeleton, clip.motion);
  ASSERT_EQ(glb.model.skins.size(), 1u);
  const tinygltf::Skin& skin = glb.model.skins[0];
  const auto rest = glb.world(-1);
  // Inverse bind matrices are the inverses of the joints' rest transforms.
  const auto inverse_binds = glb.floats(skin.inverseBindMatrices, 16);
  ASSERT_EQ(inverse_binds.size(), 16 * skin.joints.size());
  for (size_t i = 0; i < skin.joints.size(); ++i) {
    const Eigen::Matrix4d inverse = Eigen::Map<const Eigen::Matrix4f>(inverse_binds.data() + 16 * i).cast<double>();
    EXPECT_TRUE((inverse * rest[skin.joints[i]].matrix()).isIdentity(1e-5)) << i;
  }
  // The mesh: 24 vertices a bone, each bound to one joint with weight 1, its first vertex on that
  // joint at rest (the bone's head), the bone's tip on one of the joint's children.
  ASSERT_EQ(glb.model.meshes.size(), 1u);
  const auto& attributes = glb.model.meshes[0].primitives.at(0).attributes;
  const auto positions = glb.floats(attributes.at("POSITION"), 3);
  const auto normals = glb.floats(attributes.at("NORMAL"), 3);
  const auto weights = glb.floats(attributes.at("WEIGHTS_0"), 4);
  const auto joints = glb.values<uint16_t>(attributes.at("JOINTS_0"), TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 4);
  const size_t vertices = positions.size() / 3;
  ASSERT_EQ(vertices % 24, 0u);
  int bones = 0;
  for (int j = 1; j < clip.skeleton.joint_count(); ++j) {
    bones += (clip.skeleton.joint(j).rest_offset_m.norm() >= 1e-3 || clip.skeleton.translation_slot(j) >= 0);
  }
  EXPECT_EQ(static_cast<int>(vertices / 24), bones);
  for (size_t v = 0; v < vertices; ++v) {
    EXPECT_EQ(weights[4 * v], 1.0f);
    EXPECT_EQ(weights[4 * v + 1] + weights[4 * v + 2] + weights[4 * v + 3], 0.0f);
    EXPECT_NEAR(Vec3(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]).norm(), 1.0, 1e-6);
    ASSERT_LT(joints[4 * v], skin.joints.size());
  }
  for (size_t b = 0; b < vertices / 24; ++b) {
    const int joint_node = skin.joints[joints[4 * 24 * b]];
    const Vec3 head(positions[3 * 24 * b], positions[3 * 24 * b + 1], positions[3 * 24 * b + 2]);
    EXPECT_LT((head - rest[joint_node].translation()).norm(), 1e-6) << b;
    bool tip_on_a_child = false;
    for (int child : glb.model.nodes[joint_node].children) {
      for (size_t v = 24 * b; v < 24 * (b + 1); ++v) {
        const Vec3 p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
        tip_on_a_child = tip_on_a_child || (p - rest[child].translation()).norm() < 1e-6;
      }
    }
    EXPECT_TRUE(tip_on_a_child) << b;
  }
  // The node that draws it carries mesh and skin, and is a root of the scene.
  const int mesh_node = glb.node_named("stick_figure");
  EXPECT_EQ(glb.model.nodes[mesh_node].skin, 0);
  const auto& roots = glb.model.scenes.at(0).nodes;
  EXPECT_NE(std::find(roots.begin(), roots.end(), mesh_node), roots.end());
}

TEST(GltfWriter, FloatAccessorsCarryTheirExactBounds) {
  const Clip clip = test::load_data_clip("cmu/16/16_01.amc");
  const Glb glb = written(clip.skeleton, clip.motion);
  for (size_t a = 0; a < glb.model.accessors.size(); ++a) {
    const tinygltf::Accessor& accessor = glb.model.accessors[a];
    if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) continue;
    const int components = tinygltf::GetNumComponentsInType(accessor.type);
    const auto values = glb.floats(static_cast<int>(a), components);
    ASSERT_EQ(accessor.minValues.size(), static_cast<size_t>(components));
    for (int c = 0; c < components; ++c) {
      float lo = values[c], hi = values[c];
      for (size_t i = c; i < values.size(); i += components) lo = std::min(lo, values[i]), hi = std::max(hi, values[i]);
      EXPECT_EQ(accessor.minValues[c], lo) << a;
      EXPECT_EQ(accessor.maxValues[c], hi) << a;
    }
  }
}

// Property: any rotations, signs flipped at random from frame to frame (q and -q are one
// rotation), come out as unit keys on one hemisphere after another, so that the slerp between
// two keys takes the short way, and any translations of the joints that have them (CMU's root
// alone; every joint of a rig with position channels everywhere) play where forward kinematics
// puts them.
TEST(GltfWriter, RandomRotationsAndTranslationsGiveContinuousUnitKeysAndTheSamePositions) {
  const Clip cmu = test::load_data_clip("cmu/16/16_15.amc");
  const Clip six_channels = test::import_bvh(test::static_root_bvh(cmu));
  ASSERT_EQ(six_channels.skeleton.translated_joints().size(),
            static_cast<size_t>(std::count_if(six_channels.skeleton.joints().begin(), six_channels.skeleton.joints().end(),
                                              [](const JointDef& joint) { return !joint.end_site; })));
  std::mt19937 rng(3);
  for (int round = 0; round < 6; ++round) {
    const Clip& clip = round % 2 == 0 ? cmu : six_channels;
    const Motion motion = test::random_motion(clip.skeleton, 40, 60.0, rng);
    const Glb glb = written(clip.skeleton, motion);
    // One translation track per joint that has translations (they all move here).
    const auto& samplers = glb.model.animations.at(0).samplers;
    EXPECT_EQ(std::count_if(samplers.begin(), samplers.end(),
                            [&](const auto& s) { return glb.model.accessors.at(s.output).type == TINYGLTF_TYPE_VEC3; }),
              static_cast<long>(clip.skeleton.translated_joints().size()));
    for (const auto& sampler : samplers) {
      if (glb.model.accessors.at(sampler.output).type != TINYGLTF_TYPE_VEC4) continue;
      const auto q = glb.floats(sampler.output, 4);
      for (size_t k = 0; k + 4 <= q.size(); k += 4) {
        EXPECT_NEAR(Eigen::Vector4f(q[k], q[k + 1], q[k + 2], q[k + 3]).norm(), 1.0f, 1e-6f);
        if (k >= 4) {
          EXPECT_GE(q[k] * q[k - 4] + q[k + 1] * q[k - 3] + q[k + 2] * q[k - 2] + q[k + 3] * q[k - 1], 0.0f);
        }
      }
    }
    EXPECT_LT(max_world_error(glb, clip.skeleton, motion), 1e-5);
  }
}

// Position channels that hold still (a rig that gives every joint them) need no track: the
// node's translation holds their value; the root's always moves.
TEST(GltfWriter, TranslationsThatNeverChangeAreTheNodesOwn) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Clip clip = test::import_bvh(test::static_root_bvh(plain));
  ASSERT_GT(clip.skeleton.translated_joints().size(), 20u);
  const Glb glb = written(clip.skeleton, clip.motion);
  int translation_tracks = 0;
  for (const auto& channel : glb.model.animations.at(0).channels) {
    if (channel.target_path != "translation") continue;
    ++translation_tracks;
    EXPECT_EQ(glb.model.nodes.at(channel.target_node).name, clip.skeleton.joint(0).name);
  }
  EXPECT_EQ(translation_tracks, 1);
  EXPECT_LT(max_world_error(glb, clip.skeleton, clip.motion), 1e-5);
  // At rest the root stands over the origin, at its first frame's height.
  const Vec3 rest_root = glb.world(-1)[glb.node_named(clip.skeleton.joint(0).name)].translation();
  EXPECT_NEAR(rest_root.x(), 0.0, 1e-6);
  EXPECT_NEAR(rest_root.z(), 0.0, 1e-6);
  EXPECT_NEAR(rest_root.y(), plain.motion.translations(0)[0].y(), 1e-5);
}

// glTF's JSON is UTF-8: a joint named in Latin-1 (as some older tools write BVH) gets U+FFFD for
// the bytes that are not, instead of failing the file.
TEST(GltfWriter, NamesThatAreNotUtf8AreRepaired) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  joints[1].name = "H\xfc" "fte";
  const Skeleton latin1(joints);
  auto bytes = write_glb(latin1, clip.motion, "H\xfc" "pfen");
  ASSERT_TRUE(bytes) << bytes.error().message;
  const Glb glb(*bytes);
  EXPECT_EQ(glb.model.nodes.at(1).name, "H\xef\xbf\xbd" "fte");
  EXPECT_EQ(glb.model.animations.at(0).name, "H\xef\xbf\xbd" "pfen");
}

TEST(GltfWriter, WithoutFramesOrMeshTheSkeletonIsStillWritten) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  GltfWriteSettings no_mesh;
  no_mesh.bone_mesh = false;
  const Glb skeleton_only = written(clip.skeleton, clip.motion, no_mesh);
  EXPECT_TRUE(skeleton_only.model.meshes.empty());
  // The skin stays: it makes the nodes a skeleton (Blender's armature).
  ASSERT_EQ(skeleton_only.model.skins.size(), 1u);
  EXPECT_EQ(skeleton_only.model.skins[0].joints.size(), static_cast<size_t>(clip.skeleton.joint_count()));
  EXPECT_EQ(skeleton_only.model.animations.size(), 1u);
  EXPECT_LT(max_world_error(skeleton_only, clip.skeleton, clip.motion), 1e-5);
  const Glb still = written(clip.skeleton, clip.motion.slice(0, 0));
  EXPECT_TRUE(still.model.animations.empty());
  EXPECT_EQ(still.model.nodes.size(), static_cast<size_t>(clip.skeleton.joint_count()) + 1);  // + the mesh's
}

// A root without position channels keeps its offset: with no translation track, the node's own
// translation is where forward kinematics puts it.
TEST(GltfWriter, ARootWithoutPositionChannelsStaysAtItsOffset) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  joints[0].animated_translation = false;
  joints[0].rest_offset_m = Vec3(0.3, 0.9, -0.2);
  const Skeleton fixed(joints);
  Motion motion(fixed, clip.motion.frame_count, clip.motion.fps);
  motion.local_rotations = clip.motion.local_rotations;
  EXPECT_LT(max_world_error(written(fixed, motion), fixed, motion), 1e-5);
}

// A root further away than single precision holds is refused, not written as infinity (which no
// reader takes); as far as it holds, written.
TEST(GltfWriter, ATranslationPastSinglePrecisionIsAnError) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  Motion far = clip.motion;
  far.translations(40)[0].x() = 1e39;
  auto refused = write_glb(clip.skeleton, far, "far");
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().message, "animation 'far': joint 'root' at frame 41 lies 1e+39 m away, past what glTF's "
                                     "single-precision numbers hold");
  far.translations(40)[0].x() = 1e37;
  EXPECT_TRUE(write_glb(clip.skeleton, far, "far"));
}

TEST(GltfWriter, AMotionThatDoesNotFitItsSkeletonIsAnError) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  Motion fewer_joints = clip.motion;
  fewer_joints.joint_count -= 1;
  EXPECT_FALSE(write_glb(clip.skeleton, fewer_joints, "motion"));
  Motion no_rate = clip.motion;
  no_rate.fps = 0.0;
  EXPECT_FALSE(write_glb(clip.skeleton, no_rate, "motion"));
  EXPECT_FALSE(write_glb(clip.skeleton, clip.motion, ""));
  // Among several, any one that does not fit, or has no name or motion, fails the file.
  const std::vector<GltfAnimation> second_bad{{"a", &clip.motion}, {"b", &fewer_joints}};
  EXPECT_FALSE(write_glb(clip.skeleton, second_bad));
  const std::vector<GltfAnimation> unnamed{{"a", &clip.motion}, {"", &clip.motion}};
  EXPECT_FALSE(write_glb(clip.skeleton, unnamed));
  const std::vector<GltfAnimation> empty{{"a", &clip.motion}, {"b", nullptr}};
  EXPECT_FALSE(write_glb(clip.skeleton, empty));
}

// An animation set: each motion its own animation, named as given (a name repeated made unique),
// each played by the file's rules where forward kinematics puts the joints, at its own frame
// rate; a joint only one of them turns or moves is keyed in every one, so each poses the whole
// figure whichever played before it; a motion without frames makes none.
TEST(GltfWriter, SeveralMotionsAreOneAnimationEachKeyingTheSameJoints) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip jog = test::load_data_clip("cmu/16/16_35.amc");
  ASSERT_EQ(walk.skeleton.joint_count(), jog.skeleton.joint_count());
  // A joint turned in the jog only (held at identity in the walk).
  const int held = *walk.skeleton.find("lradius");
  Motion stiff = walk.motion;
  for (int f = 0; f < stiff.frame_count; ++f) stiff.rotations(f)[held] = Quat::Identity();
  Motion slow = jog.motion;
  slow.fps = 60.0;
  const Motion none = walk.motion.slice(0, 0);
  const std::vector<GltfAnimation> set{{"walk", &stiff}, {"empty", &none}, {"jog", &slow}, {"walk", &walk.motion}};
  auto bytes = write_glb(walk.skeleton, set);
  ASSERT_TRUE(bytes) << bytes.error().message;
  const Glb glb(*bytes);
  ASSERT_EQ(glb.model.animations.size(), 3u);
  EXPECT_EQ(glb.model.animations[0].name, "walk");
  EXPECT_EQ(glb.model.animations[1].name, "jog");
  EXPECT_EQ(glb.model.animations[2].name, "walk_2");
  EXPECT_LT(max_world_error(glb, walk.skeleton, stiff, 0), 1e-5);
  EXPECT_LT(max_world_error(glb, walk.skeleton, slow, 1), 1e-5);
  EXPECT_LT(max_world_error(glb, walk.skeleton, walk.motion, 2), 1e-5);
  const auto keyed = [&](int a) {
    std::set<std::pair<int, std::string>> out;
    for (const auto& channel : glb.model.animations[a].channels) out.emplace(channel.target_node, channel.target_path);
    return out;
  };
  EXPECT_TRUE(keyed(0).count({glb.node_named("lradius"), "rotation"}));
  EXPECT_EQ(keyed(0), keyed(1));
  EXPECT_EQ(keyed(0), keyed(2));
  // Each animation's keys at its own rate.
  const auto& jog_sampler = glb.model.animations[1].samplers.at(0);
  const auto times = glb.floats(jog_sampler.input, 1);
  ASSERT_EQ(static_cast<int>(times.size()), slow.frame_count);
  EXPECT_NEAR(times.back(), (slow.frame_count - 1) / 60.0, 1e-5);
  EXPECT_FLOAT_EQ(static_cast<float>(glb.model.accessors.at(jog_sampler.input).maxValues.at(0)), times.back());
}

// A translation one animation moves and another holds still is keyed in both: the one holding
// it still would otherwise leave the joint wherever the other put it.
TEST(GltfWriter, ATranslationOneAnimationMovesIsKeyedInAll) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Clip clip = test::import_bvh(test::static_root_bvh(plain));
  ASSERT_GT(clip.skeleton.translated_joints().size(), 4u);
  const int joint = clip.skeleton.translated_joints()[3];
  const int slot = clip.skeleton.translation_slot(joint);
  ASSERT_GE(slot, 0);
  Motion stretched = clip.motion;
  for (int f = 0; f < stretched.frame_count; ++f) stretched.translations(f)[slot] += Vec3(0.0, 0.05 * f / stretched.frame_count, 0.0);
  const std::vector<GltfAnimation> set{{"still", &clip.motion}, {"stretched", &stretched}};
  auto bytes = write_glb(clip.skeleton, set);
  ASSERT_TRUE(bytes) << bytes.error().message;
  const Glb glb(*bytes);
  for (int a = 0; a < 2; ++a) {
    int tracks = 0;
    for (const auto& channel : glb.model.animations.at(a).channels) {
      if (channel.target_path == "translation") ++tracks;
    }
    EXPECT_EQ(tracks, 2) << a;  // the root's and the joint's
  }
  EXPECT_LT(max_world_error(glb, clip.skeleton, clip.motion, 0), 1e-5);
  EXPECT_LT(max_world_error(glb, clip.skeleton, stretched, 1), 1e-5);
}

}  // namespace
}  // namespace mg
