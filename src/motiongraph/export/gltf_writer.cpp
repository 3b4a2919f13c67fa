#include "motiongraph/export/gltf_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "motiongraph/core/json_text.h"
#include "motiongraph/core/unique_name.h"
#include "motiongraph/export/keyed_joints.h"
#include "motiongraph/export/stick_figure.h"

namespace mg {

namespace {

using Affine = Eigen::Affine3d;

// Appends arrays to the model's one buffer, each as a 4-byte aligned buffer view with an
// accessor over it. Float accessors carry their exact min and max (glTF requires them on
// positions and animation inputs; the others may have them too).
class BufferWriter {
 public:
  explicit BufferWriter(tinygltf::Model& model) : model_(model) { model_.buffers.emplace_back(); }

  int floats(const std::vector<float>& values, int type, int components, int target = 0) {
    const int index = add(values.data(), values.size() * sizeof(float), TINYGLTF_COMPONENT_TYPE_FLOAT, type,
                          static_cast<int>(values.size()) / components, target);
    tinygltf::Accessor& accessor = model_.accessors[index];
    accessor.minValues.assign(components, std::numeric_limits<double>::infinity());
    accessor.maxValues.assign(components, -std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < values.size(); ++i) {
      const size_t c = i % components;
      accessor.minValues[c] = std::min(accessor.minValues[c], static_cast<double>(values[i]));
      accessor.maxValues[c] = std::max(accessor.maxValues[c], static_cast<double>(values[i]));
    }
    return index;
  }

  int unsigned_shorts(const std::vector<uint16_t>& values, int type, int components, int target = 0) {
    return add(values.data(), values.size() * sizeof(uint16_t), TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, type,
               static_cast<int>(values.size()) / components, target);
  }

 private:
  int add(const void* data, size_t bytes, int component_type, int type, int count, int target) {
    std::vector<unsigned char>& buffer = model_.buffers[0].data;
    buffer.resize((buffer.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    if (target != 0) view.target = target;
    const auto* begin = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), begin, begin + bytes);
    model_.bufferViews.push_back(std::move(view));
    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model_.bufferViews.size()) - 1;
    accessor.byteOffset = 0;
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = static_cast<size_t>(count);
    model_.accessors.push_back(std::move(accessor));
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  tinygltf::Model& model_;
};

std::vector<double> to_vector(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
std::vector<double> to_vector(const Quat& q) { return {q.x(), q.y(), q.z(), q.w()}; }

void push(std::vector<float>& out, const Vec3& v) {
  for (int i = 0; i < 3; ++i) out.push_back(static_cast<float>(v[i]));
}

// A unit quaternion in single precision (x, y, z, w), renormalised after rounding.
void push_unit(std::vector<float>& out, const Quat& q) {
  std::array<float, 4> f{static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
                         static_cast<float>(q.w())};
  float norm = 0.0f;
  for (float c : f) norm += c * c;
  norm = std::sqrt(norm);
  for (float c : f) out.push_back(c / norm);
}

}  // namespace

Result<std::string> write_glb(const Skeleton& skeleton, const Motion& motion, const std::string& animation_name,
                              const GltfWriteSettings& settings) {
  const GltfAnimation one{animation_name, &motion};
  return write_glb(skeleton, std::span(&one, 1), settings);
}

Result<std::string> write_glb(const Skeleton& skeleton, std::span<const GltfAnimation> animations,
                              const GltfWriteSettings& settings) {
  return write_gltf_file(skeleton, animations, settings, true);
}

Result<std::string> write_gltf(const Skeleton& skeleton, std::span<const GltfAnimation> animations,
                               const GltfWriteSettings& settings) {
  return write_gltf_file(skeleton, animations, settings, false);
}

Result<std::string> write_gltf_file(const Skeleton& skeleton, std::span<const GltfAnimation> animations,
                                    const GltfWriteSettings& settings, bool binary) {
  auto checked = played_animations(skeleton, animations, "glTF");
  if (!checked) return checked.error();
  const std::vector<const ExportAnimation*>& played = *checked;
  std::vector<const Motion*> motions;
  for (const ExportAnimation* a : played) motions.push_back(a->motion);
  const Motion* first = motions.empty() ? nullptr : motions.front();
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "motiongraph";
  BufferWriter buffer(model);

  // Nodes: the static ancestors (a chain, root first), then one per joint; the skin's joints
  // are the nodes in that order.
  const auto ancestors = skeleton.static_ancestors();
  const int first_joint = static_cast<int>(ancestors.size());
  const int joint_count = skeleton.joint_count();
  const int node_count = first_joint + joint_count;
  const std::vector<Affine> bind = rest_transforms(skeleton, first);
  for (int a = 0; a < first_joint; ++a) {
    tinygltf::Node node;
    node.name = valid_utf8(ancestors[a].name);
    node.translation = to_vector(ancestors[a].translation_m);
    if (!ancestors[a].rotation.isApprox(Quat::Identity(), 0.0)) node.rotation = to_vector(ancestors[a].rotation);
    if (a + 1 < node_count) node.children.push_back(a + 1);
    model.nodes.push_back(std::move(node));
  }
  for (int j = 0; j < joint_count; ++j) {
    const JointDef& joint = skeleton.joint(j);
    const Vec3 translation = rest_node_translation(skeleton, first, j);
    tinygltf::Node node;
    node.name = valid_utf8(joint.name);
    node.translation = to_vector(translation);
    if (j > 0) model.nodes[first_joint + joint.parent].children.push_back(first_joint + j);
    model.nodes.push_back(std::move(node));
  }

  tinygltf::Scene scene;
  scene.name = "motiongraph";
  scene.nodes.push_back(0);

  // The stick figure's bones: none when not asked for, or when no bone is 1 mm long.
  std::vector<float> positions, normals, weights;
  std::vector<uint16_t> joints;
  if (settings.bone_mesh) {
    std::vector<Vec3> rest_world;
    for (int j = 0; j < joint_count; ++j) rest_world.push_back(bind[first_joint + j].translation());
    const StickFigure figure = stick_figure(skeleton, rest_world);
    for (size_t v = 0; v < figure.positions.size(); ++v) {
      push(positions, figure.positions[v]);
      push(normals, figure.normals[v]);
      joints.insert(joints.end(), {static_cast<uint16_t>(first_joint + figure.joints[v]), 0, 0, 0});
      weights.insert(weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
    }
  }
  // The skin: what makes the nodes a skeleton to Blender (an armature) and to engines, with or
  // without a figure for it to deform.
  {
    tinygltf::Skin skin;
    skin.name = "skeleton";
    skin.skeleton = 0;
    std::vector<float> inverse_binds;
    for (int n = 0; n < node_count; ++n) {
      skin.joints.push_back(n);
      const Eigen::Matrix4d inverse = bind[n].inverse().matrix();
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) inverse_binds.push_back(static_cast<float>(inverse(r, c)));  // column-major
      }
    }
    skin.inverseBindMatrices = buffer.floats(inverse_binds, TINYGLTF_TYPE_MAT4, 16);
    model.skins.push_back(std::move(skin));
  }
  if (!positions.empty()) {
    tinygltf::Material material;
    material.name = "bone";
    material.pbrMetallicRoughness.baseColorFactor = {0.8, 0.8, 0.8, 1.0};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    model.materials.push_back(std::move(material));
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = 0;
    primitive.attributes["POSITION"] =
        buffer.floats(positions, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER);
    primitive.attributes["NORMAL"] = buffer.floats(normals, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER);
    primitive.attributes["JOINTS_0"] =
        buffer.unsigned_shorts(joints, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER);
    primitive.attributes["WEIGHTS_0"] =
        buffer.floats(weights, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER);
    tinygltf::Mesh mesh;
    mesh.name = "stick_figure";
    mesh.primitives.push_back(std::move(primitive));
    model.meshes.push_back(std::move(mesh));
    tinygltf::Node node;
    node.name = unique_name("stick_figure", [&](const std::string& n) {
      return std::any_of(model.nodes.begin(), model.nodes.end(), [&](const tinygltf::Node& other) { return other.name == n; });
    });
    node.mesh = 0;
    node.skin = 0;
    model.nodes.push_back(std::move(node));
    scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
  model.scenes.push_back(std::move(scene));
  model.defaultScene = 0;

  const KeyedJoints keyed = keyed_joints(skeleton, motions);
  std::vector<std::string> names;
  for (const ExportAnimation* a : played) {
    const Motion& motion = *a->motion;
    tinygltf::Animation animation;
    animation.name = unique_name(valid_utf8(a->name), [&](const std::string& n) {
      return std::find(names.begin(), names.end(), n) != names.end();
    });
    names.push_back(animation.name);
    std::vector<float> times;
    for (int f = 0; f < motion.frame_count; ++f) times.push_back(static_cast<float>(f / motion.fps));
    const int input = buffer.floats(times, TINYGLTF_TYPE_SCALAR, 1);
    const auto track = [&](int node, const char* path, int output) {
      tinygltf::AnimationSampler sampler;
      sampler.input = input;
      sampler.output = output;
      sampler.interpolation = "LINEAR";
      animation.samplers.push_back(std::move(sampler));
      tinygltf::AnimationChannel channel;
      channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
      channel.target_node = node;
      channel.target_path = path;
      animation.channels.push_back(std::move(channel));
    };
    for (int j : keyed.turned) {
      std::vector<float> rotations;
      Quat previous = Quat::Identity();
      for (int f = 0; f < motion.frame_count; ++f) {
        Quat q = motion.rotations(f)[j];
        if (j == 0) q = below_static_ancestors(skeleton, q);
        q = same_hemisphere(q, previous);  // slerp between neighbours takes the short way
        push_unit(rotations, q);
        previous = q;
      }
      track(first_joint + j, "rotation", buffer.floats(rotations, TINYGLTF_TYPE_VEC4, 4));
    }
    for (int j : keyed.moved) {
      const int slot = skeleton.translation_slot(j);
      std::vector<float> translations;
      for (int f = 0; f < motion.frame_count; ++f) {
        const Vec3& t = motion.translations(f)[slot];
        push(translations, j == 0 ? below_static_ancestors(skeleton, t) : t);
        // glTF's numbers are single precision: a value past them would be written as infinity,
        // which no reader takes.
        if (!std::isfinite(translations.back()) || !std::isfinite(translations[translations.size() - 2]) ||
            !std::isfinite(translations[translations.size() - 3])) {
          return Error{"", 0, fmt::format("animation '{}': joint '{}' at frame {} lies {:g} m away, past what glTF's "
                                          "single-precision numbers hold", animation.name, skeleton.joint(j).name,
                                          f + 1, t.cwiseAbs().maxCoeff())};
        }
      }
      track(first_joint + j, "translation", buffer.floats(translations, TINYGLTF_TYPE_VEC3, 3));
    }
    model.animations.push_back(std::move(animation));
  }

  model.buffers[0].data.resize((model.buffers[0].data.size() + 3) / 4 * 4, 0);
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  try {
    // (as text, the buffer goes in as a base64 data URI: one file)
    if (!writer.WriteGltfSceneToStream(&model, out, false, binary)) return Error{"", 0, "glTF serialisation failed"};
  } catch (const std::exception& e) {
    return Error{"", 0, fmt::format("glTF serialisation failed: {}", e.what())};
  }
  return out.str();
}

}  // namespace mg
