#include "motiongraph/motion/gltf_import.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <tiny_gltf.h>

#include "motiongraph/io/file.h"

namespace mg {

namespace {

// The most frames an animation is sampled to (9 hours at 30 fps): key times far apart, or a
// rate far above the keys', would otherwise ask for more memory than a machine has.
constexpr int kMaxFrames = 1'000'000;

std::string node_label(const tinygltf::Model& model, int node) {
  if (node < 0 || node >= static_cast<int>(model.nodes.size())) return fmt::format("node {}", node);
  const std::string& name = model.nodes[static_cast<size_t>(node)].name;
  return name.empty() ? fmt::format("node {}", node) : fmt::format("node '{}'", name);
}

Result<NodeTrs> node_trs(const tinygltf::Model& model, int index, const std::string& file) {
  const tinygltf::Node& node = model.nodes[static_cast<size_t>(index)];
  NodeTrs out;
  if (node.matrix.size() == 16) {
    Eigen::Matrix4d m;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[static_cast<size_t>(4 * c + r)];
    }
    out.translation = m.block<3, 1>(0, 3);
    Eigen::Matrix3d a = m.block<3, 3>(0, 0);
    for (int c = 0; c < 3; ++c) out.scale[c] = a.col(c).norm();
    if (!(out.scale.minCoeff() > 0.0) || a.determinant() < 0.0) {
      return Error{file, 0, fmt::format("{} has a matrix that is not a rotation and a positive scale",
                                        node_label(model, index))};
    }
    for (int c = 0; c < 3; ++c) a.col(c) /= out.scale[c];
    out.rotation = Quat(a).normalized();
    return out;
  }
  if (node.translation.size() == 3) out.translation = Vec3(node.translation[0], node.translation[1], node.translation[2]);
  if (node.rotation.size() == 4) {
    out.rotation = Quat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized();
  }
  if (node.scale.size() == 3) out.scale = Vec3(node.scale[0], node.scale[1], node.scale[2]);
  return out;
}

// One component at `p` as a double: floats as they are, normalised integers as glTF maps them
// to [-1, 1] or [0, 1]; nullopt for a component type glTF does not have.
std::optional<double> component_value(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, sizeof f);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t x;
      std::memcpy(&x, p, 1);
      return normalized ? std::max(x / 127.0, -1.0) : x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t x;
      std::memcpy(&x, p, 2);
      return normalized ? std::max(x / 32767.0, -1.0) : x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t x;
      std::memcpy(&x, p, 2);
      return normalized ? x / 65535.0 : x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t x;
      std::memcpy(&x, p, 4);
      return normalized ? x / 4294967295.0 : x;
    }
    default:
      return std::nullopt;
  }
}

// Where a run of elements lies in a buffer view, as an accessor or a sparse accessor's indices
// or values name it; `what` names it in errors ("accessor 3", "accessor 3 (sparse indices)").
struct ElementRun {
  int view = -1;
  size_t offset = 0;  // bytes into the view
  size_t count = 0;
  int components = 1;
  int component_type = -1;
  bool normalized = false;
  bool strided = true;  // the view's byteStride applies (not to sparse indices and values)
  std::string what;
};

Result<std::vector<double>> run_values(const tinygltf::Model& model, const ElementRun& run, const std::string& file) {
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(run.component_type));
  if (size <= 0) return Error{file, 0, fmt::format("{} has an unknown component type", run.what)};
  if (run.view < 0 || run.view >= static_cast<int>(model.bufferViews.size())) {
    return Error{file, 0, fmt::format("{} names buffer view {}, which does not exist", run.what, run.view)};
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(run.view)];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size())) {
    return Error{file, 0, fmt::format("buffer view {} names buffer {}, which does not exist", run.view, view.buffer)};
  }
  const std::vector<unsigned char>& buffer = model.buffers[static_cast<size_t>(view.buffer)].data;
  const size_t element = static_cast<size_t>(size * run.components);
  const size_t stride = run.strided && view.byteStride > 0 ? view.byteStride : element;
  const size_t end = view.byteLength <= buffer.size() && view.byteOffset <= buffer.size() - view.byteLength
                         ? view.byteOffset + view.byteLength
                         : 0;
  const size_t start = view.byteOffset + run.offset;
  // In size_t without overflow: the last element ends within the view, which lies in the buffer.
  if (run.count > 0 && (end == 0 || start < view.byteOffset || start > end || end - start < element ||
                        (run.count - 1) > (end - start - element) / stride)) {
    return Error{file, 0, fmt::format("{} runs past its buffer", run.what)};
  }
  std::vector<double> out(run.count * static_cast<size_t>(run.components), 0.0);
  for (size_t i = 0; i < run.count; ++i) {
    const unsigned char* at = buffer.data() + start + i * stride;
    for (int c = 0; c < run.components; ++c) {
      const std::optional<double> v = component_value(at + c * size, run.component_type, run.normalized);
      if (!v) return Error{file, 0, fmt::format("{} has an unknown component type", run.what)};
      if (!std::isfinite(*v)) return Error{file, 0, fmt::format("{} holds a value that is not finite", run.what)};
      out[i * static_cast<size_t>(run.components) + static_cast<size_t>(c)] = *v;
    }
  }
  return out;
}

// An accessor's elements as doubles, `components` each: floats as they are, normalised integers
// as glTF maps them to [-1, 1] or [0, 1]. A sparse accessor's values replace those of its buffer
// view (or of zeros, without one) at its indices.
Result<std::vector<double>> accessor_values(const tinygltf::Model& model, int index, int components,
                                            const std::string& file) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size())) {
    return Error{file, 0, fmt::format("accessor {} does not exist", index)};
  }
  const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(index)];
  if (tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type)) != components) {
    return Error{file, 0, fmt::format("accessor {} has {} components, not {}", index,
                                      tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type)), components)};
  }
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(accessor.componentType));
  if (size <= 0) return Error{file, 0, fmt::format("accessor {} has an unknown component type", index)};
  if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT || size > 4) {
    return Error{file, 0, fmt::format("accessor {} has a component type animation cannot use", index)};
  }
  ElementRun run;
  run.view = accessor.bufferView;
  run.offset = accessor.byteOffset;
  run.count = accessor.count;
  run.components = components;
  run.component_type = accessor.componentType;
  run.normalized = accessor.normalized;
  run.what = fmt::format("accessor {}", index);
  std::vector<double> out;
  if (accessor.bufferView < 0) {  // all zeros, as glTF says
    if (accessor.count > static_cast<size_t>(kMaxFrames) * 4) {
      return Error{file, 0, fmt::format("accessor {} holds {} zeros, more than any animation reads", index, accessor.count)};
    }
    out.assign(accessor.count * static_cast<size_t>(components), 0.0);
  } else {
    auto values = run_values(model, run, file);
    if (!values) return values.error();
    out = std::move(*values);
  }
  if (!accessor.sparse.isSparse) return out;

  const auto& sparse = accessor.sparse;
  if (sparse.count < 1 || static_cast<size_t>(sparse.count) > accessor.count) {
    return Error{file, 0, fmt::format("accessor {} replaces {} of its {} elements", index, sparse.count, accessor.count)};
  }
  const int index_type = sparse.indices.componentType;
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    return Error{file, 0, fmt::format("accessor {} has sparse indices that are not unsigned integers", index)};
  }
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
    return Error{file, 0, fmt::format("accessor {} has sparse indices or values before their buffer view", index)};
  }
  ElementRun at = run;
  at.view = sparse.indices.bufferView;
  at.offset = static_cast<size_t>(sparse.indices.byteOffset);
  at.count = static_cast<size_t>(sparse.count);
  at.components = 1;
  at.component_type = index_type;
  at.normalized = false;
  at.strided = false;
  at.what = fmt::format("accessor {} (sparse indices)", index);
  auto indices = run_values(model, at, file);
  if (!indices) return indices.error();
  ElementRun replaced = run;
  replaced.view = sparse.values.bufferView;
  replaced.offset = static_cast<size_t>(sparse.values.byteOffset);
  replaced.count = static_cast<size_t>(sparse.count);
  replaced.strided = false;
  replaced.what = fmt::format("accessor {} (sparse values)", index);
  auto values = run_values(model, replaced, file);
  if (!values) return values.error();
  const size_t width = static_cast<size_t>(components);
  for (size_t i = 0; i < indices->size(); ++i) {
    const double element = (*indices)[i];
    if (element >= static_cast<double>(accessor.count) || (i > 0 && element <= (*indices)[i - 1])) {
      return Error{file, 0,
                   fmt::format("accessor {} has sparse index {} at {}: sparse indices must increase and stay under "
                               "the accessor's {} elements",
                               index, i, static_cast<uint64_t>(element), accessor.count)};
    }
    std::copy_n(values->begin() + static_cast<std::ptrdiff_t>(i * width), width,
                out.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(element) * width));
  }
  return out;
}

// The tracks of one animation.
void read_tracks(const tinygltf::Model& model, const tinygltf::Animation& animation, SceneAnimation& out,
                 const std::string& file) {
  const int node_count = static_cast<int>(model.nodes.size());
  for (const tinygltf::AnimationChannel& channel : animation.channels) {
    const std::string& path = channel.target_path;
    if (path == "weights" || channel.target_node < 0) continue;  // morph targets: not a skeleton's
    if (channel.target_node < node_count) out.targets.push_back(channel.target_node);
    if (!out.error.empty()) continue;
    const auto fail = [&](std::string message) { out.error = std::move(message); };
    if (channel.target_node >= node_count) {
      fail(fmt::format("it has a channel aimed at node {}, which does not exist", channel.target_node));
      continue;
    }
    if (path != "translation" && path != "rotation" && path != "scale") {
      fail(fmt::format("it animates '{}', which is not read", path));
      continue;
    }
    if (channel.sampler < 0 || channel.sampler >= static_cast<int>(animation.samplers.size())) {
      fail("it has a channel without a sampler");
      continue;
    }
    const tinygltf::AnimationSampler& sampler = animation.samplers[static_cast<size_t>(channel.sampler)];
    KeyTrack track;
    track.width = path == "rotation" ? 4 : 3;
    if (sampler.interpolation == "STEP") {
      track.rule = KeyTrack::Rule::kStep;
    } else if (sampler.interpolation == "CUBICSPLINE") {
      track.rule = KeyTrack::Rule::kCubic;
    } else if (sampler.interpolation != "LINEAR" && !sampler.interpolation.empty()) {
      fail(fmt::format("unknown interpolation '{}'", sampler.interpolation));
      continue;
    }
    auto times = accessor_values(model, sampler.input, 1, file);
    if (!times) {
      fail(times.error().message);
      continue;
    }
    auto values = accessor_values(model, sampler.output, track.width, file);
    if (!values) {
      fail(values.error().message);
      continue;
    }
    track.times = std::move(*times);
    track.values = std::move(*values);
    const size_t keys = track.times.size();
    const size_t per_key = (track.rule == KeyTrack::Rule::kCubic ? 3 : 1) * static_cast<size_t>(track.width);
    if (keys == 0 || track.values.size() != keys * per_key) {
      fail(fmt::format("the {} of {} has {} keys and {} values", path, node_label(model, channel.target_node), keys,
                       track.values.size() / static_cast<size_t>(track.width)));
      continue;
    }
    if (!std::is_sorted(track.times.begin(), track.times.end())) {
      fail(fmt::format("the key times of the {} of {} are not in order", path, node_label(model, channel.target_node)));
      continue;
    }
    const TrackPath which = path == "translation" ? TrackPath::kTranslation
                            : path == "rotation"  ? TrackPath::kRotation
                                                  : TrackPath::kScale;
    out.tracks[{channel.target_node, which}] = std::move(track);
  }
}

// A .gltf's external buffer, read as the project reads every file (io/file): a folder or a file
// that cannot be read is an error saying so. tinygltf's own reader sized a folder as the largest
// file there is, and the run ended "out of memory".
bool read_external_file(std::vector<unsigned char>* out, std::string* error, const std::string& path, void*) {
  auto bytes = FileBytes::open(path);
  if (!bytes) {
    if (error != nullptr) *error += bytes.error().message;
    return false;
  }
  out->assign(bytes->bytes().begin(), bytes->bytes().end());
  return true;
}

Result<tinygltf::Model> parse(std::string_view bytes, const std::string& file, const std::string& base_dir) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(
      tinygltf::FsCallbacks{&tinygltf::FileExists, &tinygltf::ExpandFilePath, &read_external_file, nullptr, nullptr});
  // Images are not decoded: a skeleton's motion needs none, and a texture in a format the
  // decoder does not know (KTX2, WebP) would fail the file.
  loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                           void*) { return true; },
                        nullptr);
  std::string error, warning;
  bool ok = false;
  if (bytes.size() >= 4 && bytes.substr(0, 4) == "glTF") {
    if (bytes.size() >= 8) {
      uint32_t version = 0;
      std::memcpy(&version, bytes.data() + 4, sizeof version);  // little-endian, as GLB is
      if (version != 2) return Error{file, 0, fmt::format("GLB version {}: only glTF 2.0 is read", version)};
    }
    ok = loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                     static_cast<unsigned>(bytes.size()), base_dir);
  } else {
    ok = loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(), static_cast<unsigned>(bytes.size()),
                                    base_dir);
  }
  if (!ok) {
    std::string first = error.substr(0, error.find('\n'));
    if (first.empty()) first = "not a glTF 2.0 file";
    return Error{file, 0, fmt::format("cannot read glTF: {}", first)};
  }
  return model;
}

// The file as a scene of nodes: their rests (an error kept for a node whose matrix is no
// rotation and scale, said only if the skeleton uses it), skins and animations.
NodeScene scene_of(const tinygltf::Model& model, const std::string& file) {
  NodeScene scene;
  scene.format = "glTF";
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    SceneNode node;
    node.name = model.nodes[n].name;
    node.children = model.nodes[n].children;
    node.content = model.nodes[n].mesh >= 0 || model.nodes[n].camera >= 0 ||
                   model.nodes[n].extensions.count("KHR_lights_punctual") > 0;
    if (auto trs = node_trs(model, static_cast<int>(n), file)) {
      node.rest = *trs;
    } else {
      node.rest_error = "has a matrix that is not a rotation and a positive scale";
    }
    scene.nodes.push_back(std::move(node));
  }
  for (const tinygltf::Skin& skin : model.skins) scene.skins.push_back(skin.joints);
  for (const tinygltf::Animation& animation : model.animations) {
    SceneAnimation out;
    out.name = animation.name;
    read_tracks(model, animation, out, file);
    scene.animations.push_back(std::move(out));
  }
  return scene;
}

}  // namespace

Result<std::vector<std::string>> gltf_animation_names(std::string_view bytes, const std::string& file,
                                                      const std::string& base_dir) {
  auto model = parse(bytes, file, base_dir);
  if (!model) return model.error();
  return scene_clip_names(scene_of(*model, file), file);
}

Result<std::vector<Clip>> clips_from_gltf(std::string_view bytes, const std::string& file,
                                          const GltfImportSettings& settings) {
  if (auto s = settings.validate(); !s) return Error{file, 0, s.error().message};
  auto model = parse(bytes, file, settings.base_dir);
  if (!model) return model.error();
  return clips_from_scene(scene_of(*model, file), file, settings);
}

}  // namespace mg
