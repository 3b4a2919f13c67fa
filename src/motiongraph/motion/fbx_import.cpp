#include "motiongraph/motion/fbx_import.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string_view>

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

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

Result<const aiScene*> read_scene(Assimp::Importer& importer, std::string_view bytes, const std::string& file) {
  // Pivots kept as helper nodes, composed back into their nodes here (scene_of): assimp's own
  // folding leaves an animated pivot's keys on a helper it does not make.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, true);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_MATERIALS, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_TEXTURES, false);
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

// The memory a trial read may take beyond what the process holds: assimp's parse of a file is a
// few times its size.
size_t trial_memory_bytes(size_t file_bytes) { return (size_t{1} << 30) + 32 * file_bytes; }

// A trial read's time: a minute, and a second a megabyte more.
std::chrono::seconds trial_seconds(size_t file_bytes) {
  return std::chrono::seconds(60 + static_cast<long long>(file_bytes >> 20));
}

#ifndef MOTIONGRAPH_LEAK_SANITIZER  // (the sanitizer's shadow memory grows as it goes)
// In the child: its address space bounded to what it holds now and `more` bytes.
void bound_memory(size_t more) {
  long pages = 0;
  if (FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%ld", &pages) != 1) pages = 0;
    std::fclose(statm);
  }
  if (pages <= 0) return;
  const rlim_t limit = static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE)) + more;
  const rlimit bound{limit, limit};
  setrlimit(RLIMIT_AS, &bound);
}
#endif

// Debian's assimp (5.2) crashes on some malformed files (a double free as it frees the scene of a
// skinned file whose two bones share a name, an assertion on a skin's vertex index past its mesh,
// a stack overflow on a node made its own ancestor) and runs away on others (a rotation key of a
// million degrees took gigabytes a minute). So a file is read first in a child process, whose
// memory and time are bounded: what becomes of it there is the error, and the program reads the
// file itself only when the child read it and freed it. Where no child can be made, it reads the
// file as before.
Status trial_read(std::string_view bytes, const std::string& file) {
  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) return Ok{};
  const pid_t child = fork();
  if (child < 0) {
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    return Ok{};
  }
  if (child == 0) {
    close(pipe_fds[0]);
    // What the C library says of a crash (free(): double free detected) is this function's to say.
    if (const int null_fd = open("/dev/null", O_WRONLY); null_fd >= 0) dup2(null_fd, STDERR_FILENO);
#ifndef MOTIONGRAPH_LEAK_SANITIZER
    bound_memory(trial_memory_bytes(bytes.size()));
#endif
    Assimp::Importer importer;
    auto scene = read_scene(importer, bytes, file);
    if (!scene) {
      const std::string& why = scene.error().message;
      for (size_t done = 0; done < why.size();) {
        const ssize_t n = write(pipe_fds[1], why.data() + done, why.size() - done);
        if (n <= 0) break;
        done += static_cast<size_t>(n);
      }
      _exit(1);
    }
    importer.FreeScene();
    _exit(0);
  }
  close(pipe_fds[1]);
  std::string said;
  bool timed_out = false;
  const auto deadline = std::chrono::steady_clock::now() + trial_seconds(bytes.size());
  for (;;) {
    using std::chrono::milliseconds;
    const auto left = std::chrono::duration_cast<milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd wait{pipe_fds[0], POLLIN, 0};
    const int ready = poll(&wait, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    char buffer[4096];
    const ssize_t n = read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the child is done (or gone)
    if (said.size() < 65536) said.append(buffer, static_cast<size_t>(n));
  }
  close(pipe_fds[0]);
  if (timed_out) kill(child, SIGKILL);
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) {
    return Error{file, 0,
                 fmt::format("cannot read FBX: the reader (assimp) was still at it after {} s (a key of an absurd "
                             "value can make it so)",
                             trial_seconds(bytes.size()).count())};
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return Ok{};
  if (WIFEXITED(status) && WEXITSTATUS(status) == 1 && !said.empty()) {
    if (said.find("bad_alloc") != std::string::npos) {
      return Error{file, 0,
                   fmt::format("cannot read FBX: the reader (assimp) needed more than {} MB for it (a key of an "
                               "absurd value can make it so)",
                               trial_memory_bytes(bytes.size()) >> 20)};
    }
    return Error{file, 0, said};
  }
  const std::string how = WIFSIGNALED(status) ? std::string(strsignal(WTERMSIG(status)))
                                              : fmt::format("exit status {}", WEXITSTATUS(status));
  return Error{file, 0,
               fmt::format("cannot read FBX: the reader (assimp) crashed on it ({}): the file is malformed", how)};
}

Result<const aiScene*> parse(Assimp::Importer& importer, std::string_view bytes, const std::string& file) {
  if (bytes.empty()) return Error{file, 0, "the FBX file is empty"};
  if (bytes.size() >= kMaxBytes) return Error{file, 0, "the FBX file is larger than motiongraph reads (2 GB)"};
  if (auto tried = trial_read(bytes, file); !tried) return tried.error();
  return read_scene(importer, bytes, file);
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

Eigen::Matrix4d matrix_of(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out(r, c) = m[static_cast<unsigned>(r)][static_cast<unsigned>(c)];
  }
  return out;
}

Eigen::Matrix4d matrix_of(const Vec3& translation, const Quat& rotation, const Vec3& scale) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<3, 3>(0, 0) = rotation.normalized().toRotationMatrix() * scale.asDiagonal();
  m.block<3, 1>(0, 3) = translation;
  return m;
}

Result<NodeTrs> trs_of(const Eigen::Matrix4d& m) {
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

// Assimp keeps FBX's pivots as helper nodes above a node ("Knee_$AssimpFbx$_RotationPivot", ...,
// its animated parts "_Translation", "_Rotation", "_Scaling" among them) and its geometric
// transform as helpers around it ("_GeometricRotation" above, "_GeometricRotationInverse"
// below), which apply to its mesh only. The node a helper serves, and its part.
constexpr std::string_view kHelper = "_$AssimpFbx$_";

struct HelperName {
  std::string node;
  std::string part;
};

std::optional<HelperName> helper_name(const std::string& name) {
  const size_t at = name.find(kHelper);
  if (at == std::string::npos) return std::nullopt;
  return HelperName{name.substr(0, at), name.substr(at + kHelper.size())};
}

// A node of assimp's tree.
struct RawNode {
  std::string name;
  int parent = -1;  // -1: a top (below assimp's RootNode, which is left out)
  Eigen::Matrix4d matrix;
  bool content = false;  // holds a mesh, a camera or a light
};

// An animated helper or node at `time`: its keys' translation, rotation and scale (sampled
// linearly, as assimp reads them), its rest's where a part has no keys.
Eigen::Matrix4d channel_matrix(const Eigen::Matrix4d& rest, double time, const std::vector<KeyTrack>& tracks) {
  Vec3 translation = rest.block<3, 1>(0, 3);
  Eigen::Matrix3d a = rest.block<3, 3>(0, 0);
  Vec3 scale(a.col(0).norm(), a.col(1).norm(), a.col(2).norm());
  for (int i = 0; i < 3; ++i) a.col(i) /= scale[i] > 0.0 ? scale[i] : 1.0;
  Quat rotation(a);
  if (!tracks[0].times.empty()) translation = tracks[0].sample(time).head<3>();
  if (!tracks[1].times.empty()) {
    const KeyTrack::Value q = tracks[1].sample(time);
    rotation = Quat(q[3], q[0], q[1], q[2]);
  }
  if (!tracks[2].times.empty()) scale = tracks[2].sample(time).head<3>();
  return matrix_of(translation, rotation, scale);
}

// A channel's keys as three tracks (translation, rotation, scale; empty where it has none), in
// seconds; an error message when they cannot be read.
std::string channel_tracks(const aiNodeAnim& channel, double ticks, std::vector<KeyTrack>& tracks) {
  tracks.assign(3, KeyTrack{});
  const std::string name = channel.mNodeName.C_Str();
  const auto add = [&](size_t path, unsigned keys, auto&& key_of) -> std::string {
    KeyTrack& track = tracks[path];
    track.width = path == 1 ? 4 : 3;
    for (unsigned k = 0; k < keys; ++k) {
      const auto [time, value] = key_of(k);
      if (!std::isfinite(time) || !value.allFinite()) return fmt::format("a key of node '{}' is not finite", name);
      track.times.push_back(time / ticks);
      for (int i = 0; i < track.width; ++i) track.values.push_back(value[i]);
    }
    if (!std::is_sorted(track.times.begin(), track.times.end())) {
      return fmt::format("the key times of node '{}' are not in order", name);
    }
    return "";
  };
  std::string error = add(0, channel.mNumPositionKeys, [&](unsigned k) {
    const aiVectorKey& key = channel.mPositionKeys[k];
    return std::pair{key.mTime, KeyTrack::Value(key.mValue.x, key.mValue.y, key.mValue.z, 0.0)};
  });
  if (error.empty()) {
    error = add(1, channel.mNumRotationKeys, [&](unsigned k) {
      const aiQuatKey& key = channel.mRotationKeys[k];
      return std::pair{key.mTime, KeyTrack::Value(key.mValue.x, key.mValue.y, key.mValue.z, key.mValue.w)};
    });
  }
  if (error.empty()) {
    error = add(2, channel.mNumScalingKeys, [&](unsigned k) {
      const aiVectorKey& key = channel.mScalingKeys[k];
      return std::pair{key.mTime, KeyTrack::Value(key.mValue.x, key.mValue.y, key.mValue.z, 0.0)};
    });
  }
  return error;
}

// The file as a scene of nodes: assimp's tree without its RootNode, each node with its pivot helpers composed into it (at rest, and key by key where
// an animation moves any of them) and its geometric helpers left out; its meshes' bones as
// skins; its animation stacks as animations, key times in seconds.
Result<NodeScene> scene_of(const aiScene& in, const std::string& file) {
  NodeScene scene;
  scene.format = "FBX";
  // Assimp's tree, depth first, children in the file's order.
  std::set<std::string> content_names;
  for (unsigned i = 0; i < in.mNumCameras; ++i) content_names.insert(in.mCameras[i]->mName.C_Str());
  for (unsigned i = 0; i < in.mNumLights; ++i) content_names.insert(in.mLights[i]->mName.C_Str());
  std::vector<RawNode> raw;
  {
    // Assimp's RootNode stands for the file, not an object of it: left out, so that the file's
    // top objects are trees of their own (one holding the armature, one a prop), unless it
    // carries a transform (then it stays, above them all).
    std::vector<std::pair<const aiNode*, int>> stack;
    if (matrix_of(in.mRootNode->mTransformation).isIdentity(1e-12)) {
      for (unsigned c = in.mRootNode->mNumChildren; c-- > 0;) {
        if (in.mRootNode->mChildren[c]) stack.push_back({in.mRootNode->mChildren[c], -1});
      }
    } else {
      stack.push_back({in.mRootNode, -1});
    }
    while (!stack.empty()) {
      const auto [node, parent] = stack.back();
      stack.pop_back();
      if (raw.size() > 10'000'000) return Error{file, 0, "the FBX file has more nodes than motiongraph reads"};
      RawNode out;
      out.name = node->mName.C_Str();
      out.parent = parent;
      out.matrix = matrix_of(node->mTransformation);
      out.content = node->mNumMeshes > 0 || content_names.count(out.name) > 0;
      const int index = static_cast<int>(raw.size());
      raw.push_back(std::move(out));
      for (unsigned c = node->mNumChildren; c-- > 0;) {
        if (node->mChildren[c]) stack.push_back({node->mChildren[c], index});
      }
    }
  }
  // Each node's own: the node itself (not a helper), its parent the first such above it, and the
  // pivot helpers just above it that serve it (top first).
  std::vector<int> scene_index(raw.size(), -1), owner(raw.size(), -1);
  std::vector<std::vector<int>> chain;  // per scene node: its helpers, then itself
  for (size_t r = 0; r < raw.size(); ++r) {
    if (helper_name(raw[r].name)) continue;
    std::vector<int> helpers;
    int parent = raw[r].parent;
    while (parent >= 0) {
      const auto helper = helper_name(raw[static_cast<size_t>(parent)].name);
      if (!helper) break;
      if (helper->node == raw[r].name && !helper->part.starts_with("Geometric")) helpers.push_back(parent);
      parent = raw[static_cast<size_t>(parent)].parent;
    }
    std::reverse(helpers.begin(), helpers.end());
    helpers.push_back(static_cast<int>(r));
    const int index = static_cast<int>(scene.nodes.size());
    scene_index[r] = index;
    for (int h : helpers) owner[static_cast<size_t>(h)] = index;
    SceneNode node;
    node.name = raw[r].name;
    node.content = raw[r].content;
    Eigen::Matrix4d rest = Eigen::Matrix4d::Identity();
    for (int h : helpers) rest = rest * raw[static_cast<size_t>(h)].matrix;
    if (auto trs = trs_of(rest)) {
      node.rest = *trs;
    } else {
      node.rest_error = trs.error().message;
    }
    scene.nodes.push_back(std::move(node));
    chain.push_back(std::move(helpers));
    if (parent >= 0) {
      // The parent is a node of the scene (a helper's chain ends in its node, which came first).
      const int p = scene_index[static_cast<size_t>(parent)];
      if (p >= 0) scene.nodes[static_cast<size_t>(p)].children.push_back(index);
    }
  }
  // Names: a channel or a bone names its node, so a name two nodes bear is known by its first only.
  std::map<std::string, int> by_name;  // raw index
  std::set<std::string> repeated;
  for (size_t r = 0; r < raw.size(); ++r) {
    if (!by_name.emplace(raw[r].name, static_cast<int>(r)).second) repeated.insert(raw[r].name);
  }
  for (unsigned m = 0; m < in.mNumMeshes; ++m) {
    const aiMesh* mesh = in.mMeshes[m];
    if (!mesh || mesh->mNumBones == 0) continue;
    std::vector<int> joints;
    for (unsigned b = 0; b < mesh->mNumBones; ++b) {
      const auto it = by_name.find(mesh->mBones[b]->mName.C_Str());
      if (it != by_name.end() && owner[static_cast<size_t>(it->second)] >= 0) {
        joints.push_back(owner[static_cast<size_t>(it->second)]);
      }
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
    out.declared_fps = animation.mTicksPerSecond > 0.0 ? animation.mTicksPerSecond : 0.0;
    // The channels of each scene node's chain, by raw node.
    std::map<int, std::map<int, std::vector<KeyTrack>>> moved;  // scene node -> raw node -> tracks
    for (unsigned c = 0; c < animation.mNumChannels && out.error.empty(); ++c) {
      const aiNodeAnim& channel = *animation.mChannels[c];
      const std::string name = channel.mNodeName.C_Str();
      const auto it = by_name.find(name);
      if (it == by_name.end()) continue;  // a node assimp left out
      const int node = owner[static_cast<size_t>(it->second)];
      if (node < 0) continue;  // a geometric helper: the mesh's, not the skeleton's
      out.targets.push_back(node);
      if (repeated.count(name)) {
        out.error = fmt::format("it moves node '{}', a name {} nodes bear: which one cannot be told", name,
                                std::count_if(raw.begin(), raw.end(), [&](const RawNode& n) { return n.name == name; }));
        break;
      }
      out.error = channel_tracks(channel, ticks, moved[node][it->second]);
    }
    for (auto& [node, parts] : moved) {
      if (!out.error.empty()) break;
      const std::vector<int>& nodes = chain[static_cast<size_t>(node)];
      // Keys on the node itself are its whole transform, helpers and all (assimp bakes a node
      // whose animated parts are its translation, rotation and scale so, pre-rotation in).
      if (const auto own = parts.find(nodes.back()); own != parts.end()) {
        std::vector<KeyTrack>& tracks = own->second;
        for (size_t p = 0; p < 3; ++p) {
          if (!tracks[p].times.empty()) out.tracks[{node, static_cast<TrackPath>(p)}] = std::move(tracks[p]);
        }
        continue;
      }
      // Else its helpers (a pivot's parts moved) and itself composed at every key time of any of them.
      std::vector<double> times;
      for (auto& [r, tracks] : parts) {
        for (const KeyTrack& track : tracks) times.insert(times.end(), track.times.begin(), track.times.end());
      }
      std::sort(times.begin(), times.end());
      times.erase(std::unique(times.begin(), times.end()), times.end());
      KeyTrack translation, rotation, scale;
      rotation.width = 4;
      for (double t : times) {
        Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
        for (int r : nodes) {
          const auto part = parts.find(r);
          m = m * (part == parts.end() ? raw[static_cast<size_t>(r)].matrix
                                       : channel_matrix(raw[static_cast<size_t>(r)].matrix, t, part->second));
        }
        auto trs = trs_of(m);
        if (!trs) {
          out.error = fmt::format("node '{}' {}", scene.nodes[static_cast<size_t>(node)].name, trs.error().message);
          break;
        }
        for (KeyTrack* track : {&translation, &rotation, &scale}) track->times.push_back(t);
        translation.values.insert(translation.values.end(), {trs->translation.x(), trs->translation.y(), trs->translation.z()});
        rotation.values.insert(rotation.values.end(), {trs->rotation.x(), trs->rotation.y(), trs->rotation.z(), trs->rotation.w()});
        scale.values.insert(scale.values.end(), {trs->scale.x(), trs->scale.y(), trs->scale.z()});
      }
      out.tracks[{node, TrackPath::kTranslation}] = std::move(translation);
      out.tracks[{node, TrackPath::kRotation}] = std::move(rotation);
      out.tracks[{node, TrackPath::kScale}] = std::move(scale);
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

// The file's up axis as assimp reports FBX's GlobalSettings (UpAxis 0, 1, 2 and UpAxisSign).
struct FileUp {
  int axis = 1;  // x, y, z
  bool negative = false;

  std::string name() const { return fmt::format("{}{}", negative ? '-' : '+', "xyz"[axis]); }
  // The turn that takes it to +y (the shortest: the figure's heading does not matter).
  Quat turn_to_y() const {
    if (axis == 1 && negative) return Quat(Eigen::AngleAxisd(std::numbers::pi, Vec3::UnitX()));
    Vec3 up = Vec3::Zero();
    up[axis] = negative ? -1.0 : 1.0;
    return Quat::FromTwoVectors(up, Vec3::UnitY());
  }
};

FileUp up_axis_of(const aiScene& scene) {
  const double axis = metadata_number(scene, "UpAxis").value_or(1.0);
  return {axis == 0.0 ? 0 : axis == 2.0 ? 2 : 1, metadata_number(scene, "UpAxisSign").value_or(1.0) < 0.0};
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
  auto scene = scene_of(**parsed, file);
  if (!scene) return scene.error();
  const FileUp up = up_axis_of(**parsed);
  importer.FreeScene();
  // The file's up axis turned to +y, unless the user says which axis is up.
  if (!settings.up_axis) scene->turn = up.turn_to_y();
  if (facts) *facts = {scene->metres_per_unit, up.name()};
  return clips_from_scene(*scene, file, settings);
}

}  // namespace mg
