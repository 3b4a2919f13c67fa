#include "motiongraph/motion/fbx_import.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <memory>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/scene.h>
#include <fmt/format.h>

// Assimp 5.2's FBX parser leaks what it had read when it refuses a file (its tokens and parse,
// thrown past): not ours to free. A build under LeakSanitizer is told so here, where the only
// call into assimp is, rather than in every test's environment.
#if defined(__SANITIZE_ADDRESS__)
#define MOTIONGRAPH_LEAK_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MOTIONGRAPH_LEAK_SANITIZER 1
#endif
#endif
#ifdef MOTIONGRAPH_LEAK_SANITIZER
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }
#endif

namespace mg {

namespace {

// A file the size of this many bytes or more is refused before it is parsed (assimp holds all of
// it, and its parse, in memory): 2 GB.
constexpr size_t kMaxBytes = size_t{1} << 31;

Result<const aiScene*> parse(Assimp::Importer& importer, std::string_view bytes, const std::string& file) {
  if (bytes.size() >= kMaxBytes) return Error{file, 0, "the FBX file is larger than motiongraph reads (2 GB)"};
  // Pivots folded into each node's transform, not kept as helper nodes between the joints.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_MATERIALS, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_TEXTURES, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_LIGHTS, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_CAMERAS, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_EMBEDDED_TEXTURES_LEGACY_NAMING, false);
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), 0, "fbx");
  } catch (const std::exception& e) {
    return Error{file, 0, fmt::format("cannot read FBX: {}", e.what())};
  }
  if (!scene) {
    std::string why = importer.GetErrorString();
    why = why.substr(0, why.find('\n'));
    if (why.empty()) why = "not an FBX file";
    return Error{file, 0, fmt::format("cannot read FBX: {}", why)};
  }
  if (!scene->mRootNode) return Error{file, 0, "cannot read FBX: the file has no nodes"};
  return scene;
}

// An integer or a real of the file's metadata (assimp keeps FBX's GlobalSettings there).
std::optional<double> metadata_number(const aiScene& scene, const char* key) {
  if (!scene.mMetaData) return std::nullopt;
  int32_t i = 0;
  float f = 0.0f;
  double d = 0.0;
  if (scene.mMetaData->Get(key, i)) return i;
  if (scene.mMetaData->Get(key, f)) return f;
  if (scene.mMetaData->Get(key, d)) return d;
  return std::nullopt;
}

Result<NodeTrs> trs_of(const aiMatrix4x4& matrix) {
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = matrix[static_cast<unsigned>(r)][static_cast<unsigned>(c)];
  }
  if (!m.allFinite()) return Error{"", 0, "has a transform that is not finite"};
  NodeTrs out;
  out.translation = m.block<3, 1>(0, 3);
  Eigen::Matrix3d a = m.block<3, 3>(0, 0);
  for (int c = 0; c < 3; ++c) out.scale[c] = a.col(c).norm();
  if (!(out.scale.minCoeff() > 0.0) || a.determinant() < 0.0) {
    return Error{"", 0, "has a transform that is not a rotation and a positive scale"};
  }
  for (int c = 0; c < 3; ++c) a.col(c) /= out.scale[c];
  out.rotation = Quat(a).normalized();
  return out;
}

// The file as a scene of nodes (depth first from assimp's root), its meshes' bones as skins and
// its animation stacks as animations, key times in seconds.
Result<NodeScene> scene_of(const aiScene& in, const std::string& file) {
  NodeScene scene;
  scene.format = "FBX";
  std::map<std::string, int> by_name;  // the first node of each name
  // Depth first; a node's index is known before its children are visited.
  std::vector<std::pair<const aiNode*, int>> stack{{in.mRootNode, -1}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    const int index = static_cast<int>(scene.nodes.size());
    if (index > 10'000'000) return Error{file, 0, "the FBX file has more nodes than motiongraph reads"};
    SceneNode out;
    out.name = node->mName.C_Str();
    if (auto trs = trs_of(node->mTransformation)) {
      out.rest = *trs;
    } else {
      out.rest_error = trs.error().message;
    }
    by_name.emplace(out.name, index);
    scene.nodes.push_back(std::move(out));
    if (parent >= 0) scene.nodes[static_cast<size_t>(parent)].children.push_back(index);
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      if (node->mChildren[c]) stack.push_back({node->mChildren[c], index});
    }
  }
  // Children were pushed last first: put each node's children back in the file's order.
  for (SceneNode& node : scene.nodes) std::sort(node.children.begin(), node.children.end());
  for (unsigned m = 0; m < in.mNumMeshes; ++m) {
    const aiMesh* mesh = in.mMeshes[m];
    if (!mesh || mesh->mNumBones == 0) continue;
    std::vector<int> joints;
    for (unsigned b = 0; b < mesh->mNumBones; ++b) {
      const auto it = by_name.find(mesh->mBones[b]->mName.C_Str());
      if (it != by_name.end()) joints.push_back(it->second);
    }
    if (!joints.empty()) scene.skins.push_back(std::move(joints));
  }
  for (unsigned a = 0; a < in.mNumAnimations; ++a) {
    const aiAnimation& animation = *in.mAnimations[a];
    SceneAnimation out;
    out.name = animation.mName.C_Str();
    // Blender names a stack "OBJECT|ACTION": the action's name, when OBJECT is a node here.
    if (const size_t bar = out.name.find('|'); bar != std::string::npos && bar + 1 < out.name.size() &&
                                               by_name.count(out.name.substr(0, bar))) {
      out.name = out.name.substr(bar + 1);
    }
    // Ticks per second: assimp gives FBX's frame rate, and 0 when the file has none (then 25,
    // as assimp's own viewer takes it).
    const double ticks = animation.mTicksPerSecond > 0.0 ? animation.mTicksPerSecond : 25.0;
    for (unsigned c = 0; c < animation.mNumChannels && out.error.empty(); ++c) {
      const aiNodeAnim& channel = *animation.mChannels[c];
      const auto it = by_name.find(channel.mNodeName.C_Str());
      if (it == by_name.end()) continue;  // a node assimp left out (a light's, a camera's)
      const int node = it->second;
      out.targets.push_back(node);
      const auto add = [&](TrackPath path, unsigned keys, auto&& key_of) {
        if (keys == 0 || !out.error.empty()) return;
        KeyTrack track;
        track.width = path == TrackPath::kRotation ? 4 : 3;
        for (unsigned k = 0; k < keys; ++k) {
          const auto [time, value] = key_of(k);
          if (!std::isfinite(time) || !value.allFinite()) {
            out.error = fmt::format("a key of node '{}' is not finite", channel.mNodeName.C_Str());
            return;
          }
          track.times.push_back(time / ticks);
          for (int i = 0; i < track.width; ++i) track.values.push_back(value[i]);
        }
        if (!std::is_sorted(track.times.begin(), track.times.end())) {
          out.error = fmt::format("the key times of node '{}' are not in order", channel.mNodeName.C_Str());
          return;
        }
        out.tracks[{node, path}] = std::move(track);
      };
      add(TrackPath::kTranslation, channel.mNumPositionKeys, [&](unsigned k) {
        const aiVectorKey& key = channel.mPositionKeys[k];
        return std::pair{key.mTime, KeyTrack::Value(key.mValue.x, key.mValue.y, key.mValue.z, 0.0)};
      });
      add(TrackPath::kRotation, channel.mNumRotationKeys, [&](unsigned k) {
        const aiQuatKey& key = channel.mRotationKeys[k];
        return std::pair{key.mTime, KeyTrack::Value(key.mValue.x, key.mValue.y, key.mValue.z, key.mValue.w)};
      });
      add(TrackPath::kScale, channel.mNumScalingKeys, [&](unsigned k) {
        const aiVectorKey& key = channel.mScalingKeys[k];
        return std::pair{key.mTime, KeyTrack::Value(key.mValue.x, key.mValue.y, key.mValue.z, 0.0)};
      });
    }
    scene.animations.push_back(std::move(out));
  }
  // FBX's unit is the centimetre times UnitScaleFactor.
  const double unit = metadata_number(in, "UnitScaleFactor").value_or(1.0);
  if (!(unit > 0.0) || !std::isfinite(unit)) {
    return Error{file, 0, fmt::format("the FBX file's unit scale factor {} is not a positive number", unit)};
  }
  scene.metres_per_unit = unit * 0.01;
  return scene;
}

// The file's up axis as assimp reports FBX's GlobalSettings: y or z (pointing up), else an error.
Result<UpAxis> up_axis_of(const aiScene& scene, const std::string& file) {
  const double axis = metadata_number(scene, "UpAxis").value_or(1.0);
  const double sign = metadata_number(scene, "UpAxisSign").value_or(1.0);
  if (axis == 1.0 && sign > 0.0) return UpAxis::kY;
  if (axis == 2.0 && sign > 0.0) return UpAxis::kZ;
  const char* name = axis == 0.0 ? "x" : axis == 1.0 ? "y" : axis == 2.0 ? "z" : "?";
  return Error{file, 0, fmt::format("the FBX file's up axis is {}{}, which is not read (give the axis with --up-axis)",
                                    sign < 0.0 ? "-" : "+", name)};
}

}  // namespace

Result<std::vector<std::string>> fbx_animation_names(std::string_view bytes, const std::string& file) {
  Assimp::Importer importer;
  auto parsed = parse(importer, bytes, file);
  if (!parsed) return parsed.error();
  auto scene = scene_of(**parsed, file);
  if (!scene) return scene.error();
  return scene_clip_names(*scene, file);
}

Result<std::vector<Clip>> clips_from_fbx(std::string_view bytes, const std::string& file,
                                         const FbxImportSettings& settings, FbxFileFacts* facts) {
  if (auto s = settings.validate(); !s) return Error{file, 0, s.error().message};
  Assimp::Importer importer;
  auto parsed = parse(importer, bytes, file);
  if (!parsed) return parsed.error();
  FbxImportSettings as_read = settings;
  auto up = up_axis_of(**parsed, file);
  if (!as_read.up_axis) {
    if (!up) return up.error();
    as_read.up_axis = *up;
  }
  auto scene = scene_of(**parsed, file);
  if (!scene) return scene.error();
  if (facts) *facts = {scene->metres_per_unit, up ? *up : *as_read.up_axis};
  importer.FreeScene();
  return clips_from_scene(*scene, file, as_read);
}

}  // namespace mg
