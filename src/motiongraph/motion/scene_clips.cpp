#include "motiongraph/motion/scene_clips.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "motiongraph/core/text.h"
#include "motiongraph/core/unique_name.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/length_unit.h"
#include "motiongraph/motion/trajectory_joint.h"
#include "motiongraph/motion/up_axis.h"

namespace mg {

Status SceneClipSettings::validate() const {
  if (!(fps_override >= 0.0) || !std::isfinite(fps_override)) {
    return Error{"", 0, "the frame rate to sample animations at must be 0 (the keys') or more"};
  }
  if (!(max_joint_poses > 0.0)) return Error{"", 0, "the most joint poses to read must be positive"};
  return Ok{};
}

KeyTrack::Value KeyTrack::at_key(size_t key, int part) const {
  const size_t per_key = rule == Rule::kCubic ? 3 * static_cast<size_t>(width) : static_cast<size_t>(width);
  const double* v = values.data() + key * per_key + static_cast<size_t>(part * width);
  return Value(v[0], v[1], v[2], width == 4 ? v[3] : 0.0);
}

KeyTrack::Value KeyTrack::value(size_t key) const { return at_key(key, rule == Rule::kCubic ? 1 : 0); }

KeyTrack::Value KeyTrack::sample(double t) const {
  const size_t n = times.size();
  if (n == 1 || t <= times.front()) return value(0);
  if (t >= times.back()) return value(n - 1);
  // A time on a key, to two float32 roundings of the key times, is that key's: a frame sampled
  // at the keys' own rate takes each key's value as it is.
  const double on_key = 1e-6 + 2.4e-7 * std::abs(t);
  const size_t k = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t + on_key) - times.begin()) - 1;
  if (k >= n - 1) return value(n - 1);
  if (std::abs(t - times[k]) <= on_key) return value(k);
  const double dt = times[k + 1] - times[k];
  const double s = dt > 0.0 ? std::clamp((t - times[k]) / dt, 0.0, 1.0) : 0.0;
  switch (rule) {
    case Rule::kStep:
      return value(k);
    case Rule::kCubic: {
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * value(k) + (s3 - 2 * s2 + s) * dt * at_key(k, 2) +
             (-2 * s3 + 3 * s2) * value(k + 1) + (s3 - s2) * dt * at_key(k + 1, 0);
    }
    case Rule::kLinear:
      break;
  }
  if (width == 4) {
    const Value a = value(k), b = value(k + 1);
    const Quat q = Quat(a[3], a[0], a[1], a[2]).normalized().slerp(s, Quat(b[3], b[0], b[1], b[2]).normalized());
    return Value(q.x(), q.y(), q.z(), q.w());
  }
  return (1 - s) * value(k) + s * value(k + 1);
}

namespace {

// A scale within this of 1 is no scale (exporters write 0.99999994).
constexpr double kUnitScale = 1e-4;

// The most frames an animation is sampled to (9 hours at 30 fps): key times far apart, or a
// rate far above the keys', would otherwise ask for more memory than a machine has.
constexpr int kMaxFrames = 1'000'000;

std::string node_label(const NodeScene& scene, int node) {
  if (node < 0 || node >= static_cast<int>(scene.nodes.size())) return fmt::format("node {}", node);
  const std::string& name = scene.nodes[static_cast<size_t>(node)].name;
  return name.empty() ? fmt::format("node {}", node) : fmt::format("node '{}'", name);
}

Result<NodeTrs> rest_of(const NodeScene& scene, int node, const std::string& file) {
  const SceneNode& n = scene.nodes[static_cast<size_t>(node)];
  if (!n.rest_error.empty()) return Error{file, 0, fmt::format("{} {}", node_label(scene, node), n.rest_error)};
  return n.rest;
}

bool is_uniform(const Vec3& scale) {
  return scale.minCoeff() > 0.0 && scale.maxCoeff() - scale.minCoeff() <= kUnitScale * scale.maxCoeff();
}

Quat as_quat(const KeyTrack::Value& v) {
  const Quat q(v[3], v[0], v[1], v[2]);
  return q.norm() > 0.0 ? q.normalized() : Quat::Identity();
}
Vec3 as_vec3(const KeyTrack::Value& v) { return Vec3(v[0], v[1], v[2]); }

using Tracks = std::map<std::pair<int, TrackPath>, KeyTrack>;

// The step between a track's keys when they are evenly spaced (to a quarter of it), else 0: from
// its first and last key, which float32's rounding of long or late times does not upset.
double even_step(const std::vector<double>& times) {
  if (times.size() < 2) return 0.0;
  const double step = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  if (!(step > 1e-6)) return 0.0;
  for (size_t k = 1; k + 1 < times.size(); ++k) {
    if (std::abs(times[k] - (times.front() + static_cast<double>(k) * step)) > 0.25 * step) return 0.0;
  }
  return step;
}

// The fastest keys read as frames (build's --fps's most).
constexpr double kMaxKeyRate = 1000.0;

// The rate the tracks are sampled at, and the time between two samples.
struct KeyRate {
  double fps = 30.0;
  double step = 1.0 / 30.0;  // 1 / fps, unless the keys lie on a grid a little off it
};

// That of their keys (the step of the evenly keyed tracks, or the most common step between two
// keys, to 10 microseconds, snapped to a whole rate), sampled on the keys themselves where they
// lie a little off the snapped rate's frames (Blender's FBX keys 30.0003 a second); keys off any
// such grid (tracks keyed at different times) or slower than 24 a second (keys far apart, a curve
// between them) are sampled at 30 fps or their rate, whichever is higher, unless the file
// declares that rate (`declared_fps`, FBX's; 0: none) and they lie on its frames.
KeyRate key_rate(const std::vector<const KeyTrack*>& tracks, double declared_fps) {
  std::map<long long, std::vector<double>> steps;
  for (const KeyTrack* track : tracks) {
    if (const double step = even_step(track->times); step > 0.0) {
      steps[std::llround(step * 1e5)].push_back(step);
      continue;
    }
    for (size_t k = 1; k < track->times.size(); ++k) {
      const double step = track->times[k] - track->times[k - 1];
      if (step > 1e-6) steps[std::llround(step * 1e5)].push_back(step);
    }
  }
  if (steps.empty()) return {};
  const auto most = std::max_element(steps.begin(), steps.end(),
                                     [](const auto& a, const auto& b) { return a.second.size() < b.second.size(); });
  std::vector<double>& bin = most->second;
  std::nth_element(bin.begin(), bin.begin() + static_cast<long>(bin.size() / 2), bin.end());
  const double median = bin[bin.size() / 2];
  const double fps = fps_from_frame_time(median);
  double first = std::numeric_limits<double>::infinity(), last = -first;
  for (const KeyTrack* track : tracks) {
    first = std::min(first, track->times.front());
    last = std::max(last, track->times.back());
  }
  const auto on_grid = [&](double step) {
    for (const KeyTrack* track : tracks) {
      for (double t : track->times) {
        const double frame = (t - first) / step;
        if (std::abs(frame - std::round(frame)) > 1e-3 + 1e-6 * std::abs(frame)) return false;
      }
    }
    return true;
  };
  // Keys every frame of the rate the file declares are read at it however slow (but for a rate
  // under 5 a second: no frame rate; assimp gives 1 for FBX's default time mode).
  const bool declared = declared_fps >= 5.0 && std::abs(fps - declared_fps) < 1e-3 * declared_fps &&
                        on_grid(1.0 / declared_fps);
  if (fps < 24.0 && !declared) return {};
  // Keys closer than a millisecond are no capture's frames: a reader's own (assimp splits a
  // rotation key of a million degrees into thousands, 6 microseconds apart); the file's rate,
  // else 30 fps, samples the curve.
  if (fps > kMaxKeyRate) {
    if (declared_fps >= 5.0 && declared_fps <= kMaxKeyRate) return {declared_fps, 1.0 / declared_fps};
    return {};
  }
  if (on_grid(1.0 / fps)) return {fps, 1.0 / fps};
  // The keys' own step, from their whole span (exact where the median of float keys is not).
  const double span = last - first;
  const double own = span > 0.0 ? span / std::max(1.0, std::round(span / median)) : median;
  if (on_grid(own)) return {fps, own};
  const double rate = std::max(fps, 30.0);
  return {rate, 1.0 / rate};
}

// The nodes from the scene's top down to `node`, top first.
std::vector<int> path_to(const std::vector<int>& parent, int node) {
  std::vector<int> path;
  for (int n = node; n >= 0; n = parent[static_cast<size_t>(n)]) path.push_back(n);
  std::reverse(path.begin(), path.end());
  return path;
}

// The animations' names as the clips take them: their own, "animation_N" without one, a name
// repeated made unique.
std::vector<std::string> clip_names(const NodeScene& scene) {
  std::vector<std::string> names;
  for (size_t a = 0; a < scene.animations.size(); ++a) {
    const std::string& name = scene.animations[a].name;
    names.push_back(unique_name(name.empty() ? fmt::format("animation_{}", a + 1) : name, [&](const std::string& n) {
      return std::find(names.begin(), names.end(), n) != names.end();
    }));
  }
  return names;
}

// Whether a track's keys take its part of a node's transform off `rest` (by more than float32's
// rounding).
bool leaves_rest(const KeyTrack& track, TrackPath path, const NodeTrs& rest) {
  for (size_t k = 0; k < track.times.size(); ++k) {
    const KeyTrack::Value v = track.value(k);
    switch (path) {
      case TrackPath::kTranslation:
        if ((as_vec3(v) - rest.translation).norm() > 1e-5 * (1.0 + rest.translation.norm())) return true;
        break;
      case TrackPath::kRotation:
        if (as_quat(v).angularDistance(rest.rotation) > 1e-5) return true;
        break;
      case TrackPath::kScale:
        if ((as_vec3(v) - rest.scale).norm() > 1e-5 * rest.scale.norm()) return true;
        break;
    }
  }
  return false;
}

// Whether an animation's keys take a node off its rest.
bool moves(const NodeScene& scene, const SceneAnimation& animation, int node) {
  const NodeTrs& rest = scene.nodes[static_cast<size_t>(node)].rest;
  for (const TrackPath path : {TrackPath::kTranslation, TrackPath::kRotation, TrackPath::kScale}) {
    const auto it = animation.tracks.find({node, path});
    if (it != animation.tracks.end() && leaves_rest(it->second, path, rest)) return true;
  }
  return false;
}

// Whether a joint's name marks the end of a chain: it ends in "end" or "nub", in any case.
bool names_an_end(const std::string& name) {
  const std::string lower = ascii_lower(name);
  return lower.ends_with("end") || lower.ends_with("nub");
}

// Which nodes make the skeleton, and which animations move it.
struct Layout {
  std::vector<int> parent;          // per node, -1 at a scene's top
  std::vector<int> above;           // the nodes above the root, top first
  std::vector<int> order;           // the skeleton's nodes, parents first; order[0] the root
  std::map<int, int> joint_of;      // node -> joint
  std::vector<std::string> names;   // every animation's clip name
  std::vector<size_t> moving;       // the animations that move a joint or a node above them
};

Result<Layout> layout_of(const NodeScene& scene, const std::string& file) {
  Layout out;
  const int node_count = static_cast<int>(scene.nodes.size());
  out.parent.assign(static_cast<size_t>(node_count), -1);
  for (int n = 0; n < node_count; ++n) {
    for (int child : scene.nodes[static_cast<size_t>(n)].children) {
      if (child < 0 || child >= node_count || child == n || out.parent[static_cast<size_t>(child)] >= 0) {
        return Error{file, 0, fmt::format("{} has a child that is not a node of one parent", node_label(scene, n))};
      }
      out.parent[static_cast<size_t>(child)] = n;
    }
  }
  // Every node reaches a top within as many steps as there are nodes, or the hierarchy is a cycle.
  for (int n = 0; n < node_count; ++n) {
    int steps = 0;
    for (int m = n; m >= 0; m = out.parent[static_cast<size_t>(m)]) {
      if (++steps > node_count) return Error{file, 0, fmt::format("the nodes above {} form a cycle", node_label(scene, n))};
    }
  }
  const auto is_node = [&](int n) { return n >= 0 && n < node_count; };
  // The nodes the skeleton must hold: every skin's joints, or without a skin the nodes moved,
  // those of the tree most of them are in (a camera's or a prop's are left out).
  std::set<int> wanted;
  for (const std::vector<int>& skin : scene.skins) wanted.insert(skin.begin(), skin.end());
  for (int n : wanted) {
    if (!is_node(n)) return Error{file, 0, fmt::format("a skin's joint {} is not a node", n)};
  }
  if (wanted.empty()) {
    // The nodes whose keys move them off their rest (an armature keyed where it stands is no
    // joint: it is composed in above the skeleton), or, when none does, every node keyed.
    std::map<int, std::set<int>> by_top;
    for (const bool moved_only : {true, false}) {
      for (const SceneAnimation& animation : scene.animations) {
        for (int node : animation.targets) {
          if (is_node(node) && (!moved_only || moves(scene, animation, node))) {
            by_top[path_to(out.parent, node).front()].insert(node);
          }
        }
      }
      if (!by_top.empty()) break;
    }
    const auto most = std::max_element(by_top.begin(), by_top.end(),
                                       [](const auto& a, const auto& b) { return a.second.size() < b.second.size(); });
    if (most != by_top.end()) wanted = most->second;
  }
  if (wanted.empty()) return Error{file, 0, fmt::format("the {} file has no skin and no animated node", scene.format)};
  // The root: the lowest node above (or among) them all.
  std::vector<int> common = path_to(out.parent, *wanted.begin());
  for (int n : wanted) {
    const std::vector<int> path = path_to(out.parent, n);
    size_t same = 0;
    while (same < common.size() && same < path.size() && common[same] == path[same]) ++same;
    common.resize(same);
  }
  if (common.empty()) return Error{file, 0, "the skeleton's joints are in separate trees of nodes"};
  const int root = common.back();
  out.above.assign(common.begin(), common.end() - 1);
  std::set<int> in_skeleton;
  for (int n : wanted) {
    for (int m = n; m != out.parent[static_cast<size_t>(root)]; m = out.parent[static_cast<size_t>(m)]) in_skeleton.insert(m);
  }
  // The bones no key moves (without a skin) or no skin lists (an FBX skin's bones are the joints
  // a vertex hangs from: end bones and unskinned fingers are not among them), below the root, but
  // no mesh, camera or light.
  {
    std::vector<int> below{root};
    while (!below.empty()) {
      const int n = below.back();
      below.pop_back();
      in_skeleton.insert(n);
      for (int child : scene.nodes[static_cast<size_t>(n)].children) {
        if (child >= 0 && child < node_count && !scene.nodes[static_cast<size_t>(child)].content) below.push_back(child);
      }
    }
  }
  std::vector<int> stack{root};
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    out.order.push_back(n);
    const auto& children = scene.nodes[static_cast<size_t>(n)].children;
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      if (in_skeleton.count(*it)) stack.push_back(*it);
    }
  }
  for (size_t j = 0; j < out.order.size(); ++j) out.joint_of[out.order[j]] = static_cast<int>(j);
  out.names = clip_names(scene);
  const std::set<int> above(out.above.begin(), out.above.end());
  for (size_t a = 0; a < scene.animations.size(); ++a) {
    for (int node : scene.animations[a].targets) {
      if (out.joint_of.count(node) || above.count(node)) {
        out.moving.push_back(a);
        break;
      }
    }
  }
  return out;
}

}  // namespace

Result<std::vector<std::string>> scene_clip_names(const NodeScene& scene, const std::string& file) {
  if (scene.animations.empty()) return std::vector<std::string>();
  auto layout = layout_of(scene, file);
  if (!layout) return layout.error();
  std::vector<std::string> names;
  for (size_t a : layout->moving) names.push_back(layout->names[a]);
  return names;
}

Result<std::vector<Clip>> clips_from_scene(const NodeScene& scene, const std::string& file,
                                           const SceneClipSettings& settings) {
  if (auto s = settings.validate(); !s) return Error{file, 0, s.error().message};
  if (!(scene.metres_per_unit > 0.0) || !std::isfinite(scene.metres_per_unit)) {
    return Error{file, 0, fmt::format("the {} file's unit is not a positive length", scene.format)};
  }
  if (scene.animations.empty()) return Error{file, 0, fmt::format("the {} file has no animation", scene.format)};
  auto laid = layout_of(scene, file);
  if (!laid) return laid.error();
  Layout& layout = *laid;  // its joint order settled below (end sites last)
  if (layout.moving.empty()) {
    return Error{file, 0, fmt::format("no animation of the {} file moves its skeleton", scene.format)};
  }
  const std::vector<int>& order = layout.order;
  const int root = order.front();

  // The nodes above the root at rest: composed, with a uniform scale; with the file's unit and
  // the root's own (uniform, constant) scale, the scale of every length below it.
  std::vector<NodeTrs> above_rest;
  for (int n : layout.above) {
    auto trs = rest_of(scene, n, file);
    if (!trs) return trs.error();
    if (!is_uniform(trs->scale)) {
      return Error{file, 0, fmt::format("{} above the skeleton scales unevenly", node_label(scene, n))};
    }
    above_rest.push_back(*trs);
  }
  double above_scale = scene.metres_per_unit;
  for (const NodeTrs& trs : above_rest) above_scale *= trs.scale.x();
  // The nodes above composed, each with its own translation and rotation (its rest, or sampled).
  const auto compose_above = [&](const std::vector<Vec3>& t, const std::vector<Quat>& r, Vec3& translation,
                                 Quat& rotation) {
    translation = Vec3::Zero();
    rotation = scene.turn;
    double scale = scene.metres_per_unit;
    for (size_t i = 0; i < above_rest.size(); ++i) {
      translation += rotation * (scale * t[i]);
      rotation = (rotation * r[i]).normalized();
      scale *= above_rest[i].scale.x();
    }
  };
  std::vector<Vec3> above_t;
  std::vector<Quat> above_r;
  for (const NodeTrs& trs : above_rest) {
    above_t.push_back(trs.translation);
    above_r.push_back(trs.rotation);
  }
  Vec3 above_translation;
  Quat above_rotation;
  compose_above(above_t, above_r, above_translation, above_rotation);

  const int joints = static_cast<int>(order.size());
  std::vector<NodeTrs> rest(static_cast<size_t>(joints));
  for (int j = 0; j < joints; ++j) {
    auto trs = rest_of(scene, order[static_cast<size_t>(j)], file);
    if (!trs) return trs.error();
    rest[static_cast<size_t>(j)] = *trs;
  }
  const double root_scale = rest[0].scale.x();
  if (!is_uniform(rest[0].scale)) {
    return Error{file, 0, fmt::format("the root {} scales unevenly", node_label(scene, root))};
  }
  for (int j = 1; j < joints; ++j) {
    if ((rest[static_cast<size_t>(j)].scale - Vec3::Ones()).cwiseAbs().maxCoeff() > kUnitScale) {
      return Error{file, 0, fmt::format("{} is scaled; only the skeleton's root and the nodes above it may be",
                                        node_label(scene, order[static_cast<size_t>(j)]))};
    }
  }
  const double length_scale = above_scale * root_scale;  // of every offset below the root

  // The moving animations' tracks, their scale tracks checked (a joint's or a node above's
  // scale may not change).
  std::map<int, Vec3> rest_scale;
  for (size_t i = 0; i < layout.above.size(); ++i) rest_scale[layout.above[i]] = above_rest[i].scale;
  for (int j = 0; j < joints; ++j) rest_scale[order[static_cast<size_t>(j)]] = j == 0 ? rest[0].scale : Vec3::Ones();
  std::vector<const Tracks*> animations;
  double poses = 0.0;
  for (size_t a : layout.moving) {
    const SceneAnimation& animation = scene.animations[a];
    if (!animation.error.empty()) {
      return Error{file, 0, fmt::format("animation '{}': {}", layout.names[a], animation.error)};
    }
    for (const auto& [target, track] : animation.tracks) {
      const auto at_rest = rest_scale.find(target.first);
      if (target.second != TrackPath::kScale || at_rest == rest_scale.end()) continue;
      for (size_t k = 0; k < track.values.size(); k += 3) {
        const Vec3 s(track.values[k], track.values[k + 1], track.values[k + 2]);
        if ((s - at_rest->second).cwiseAbs().maxCoeff() > kUnitScale * at_rest->second.cwiseAbs().maxCoeff()) {
          return Error{file, 0, fmt::format("animation '{}' scales {}; the project reads rigid skeletons",
                                            layout.names[a], node_label(scene, target.first))};
        }
      }
    }
    animations.push_back(&animation.tracks);
  }

  // Rest world rotations (the frames each joint is re-expressed in) and the skeleton: offsets in
  // the world's axes, position channels where an animation moves a joint's translation.
  std::vector<Quat> rest_world(static_cast<size_t>(joints));
  std::vector<JointDef> defs(static_cast<size_t>(joints));
  // A joint's translation keys move it when they leave its rest by more than float32's rounding
  // of the bones' lengths (Blender's FBX keys every bone's translation, 1e-6 of a bone off rest).
  double longest_bone = 0.0;
  for (int j = 1; j < joints; ++j) longest_bone = std::max(longest_bone, rest[static_cast<size_t>(j)].translation.norm());
  const double still = 1e-6 + 1e-5 * longest_bone * length_scale;
  std::set<std::string> names;
  for (int j = 0; j < joints; ++j) {
    const int node = order[static_cast<size_t>(j)];
    JointDef& def = defs[static_cast<size_t>(j)];
    const std::string& name = scene.nodes[static_cast<size_t>(node)].name;
    def.name = unique_name(name.empty() ? fmt::format("joint_{}", j) : name,
                           [&](const std::string& n) { return names.count(n) > 0; });
    names.insert(def.name);
    def.parent = j == 0 ? -1 : layout.joint_of.at(layout.parent[static_cast<size_t>(node)]);
    const Quat parent_world = j == 0 ? above_rotation : rest_world[static_cast<size_t>(def.parent)];
    rest_world[static_cast<size_t>(j)] = (parent_world * rest[static_cast<size_t>(j)].rotation).normalized();
    def.rest_offset_m = j == 0 ? Vec3(above_translation + above_scale * (above_rotation * rest[0].translation))
                               : Vec3(length_scale * (parent_world * rest[static_cast<size_t>(j)].translation));
    def.animated_translation = j == 0;
    for (const Tracks* tracks : animations) {
      const auto it = tracks->find({node, TrackPath::kTranslation});
      if (it == tracks->end() || def.animated_translation) continue;
      for (size_t k = 0; k < it->second.values.size() && !def.animated_translation; k += 3) {
        const Vec3 t(it->second.values[k], it->second.values[k + 1], it->second.values[k + 2]);
        def.animated_translation = (t - rest[static_cast<size_t>(j)].translation).norm() * length_scale > still;
      }
    }
  }
  // A leaf named as a marker ("ltoes_end", "HeadTop_End", "Bip01 L Toe0Nub") that no animation
  // moves is an end site, as BVH's End Site is: the project's own files write theirs so, and a
  // file read back (or beside BVH files of its rig) keeps its joints.
  std::vector<int> children(static_cast<size_t>(joints), 0);
  for (int j = 1; j < joints; ++j) ++children[static_cast<size_t>(defs[static_cast<size_t>(j)].parent)];
  for (int j = 1; j < joints; ++j) {
    JointDef& def = defs[static_cast<size_t>(j)];
    if (children[static_cast<size_t>(j)] > 0 || def.animated_translation || !names_an_end(def.name)) continue;
    const int node = order[static_cast<size_t>(j)];
    def.end_site = std::none_of(animations.begin(), animations.end(), [&](const Tracks* tracks) {
      const auto it = tracks->find({node, TrackPath::kRotation});
      return it != tracks->end() && leaves_rest(it->second, TrackPath::kRotation, rest[static_cast<size_t>(j)]);
    });
  }
  // End sites after the joints, as a BVH file's are read (bvh_import.h), so that one rig read
  // from both has its joints in one order (rig_matching.h compares hierarchies joint by joint).
  std::vector<int> moved;  // new index -> old
  for (const bool ends : {false, true}) {
    for (int j = 0; j < joints; ++j) {
      if (defs[static_cast<size_t>(j)].end_site == ends) moved.push_back(j);
    }
  }
  if (!std::is_sorted(moved.begin(), moved.end())) {
    std::vector<int> new_index(static_cast<size_t>(joints));
    for (int n = 0; n < joints; ++n) new_index[static_cast<size_t>(moved[static_cast<size_t>(n)])] = n;
    const std::vector<JointDef> old_defs = defs;
    const std::vector<NodeTrs> old_rest = rest;
    const std::vector<Quat> old_rest_world = rest_world;
    const std::vector<int> old_order = layout.order;
    for (int n = 0; n < joints; ++n) {
      const size_t old = static_cast<size_t>(moved[static_cast<size_t>(n)]);
      defs[static_cast<size_t>(n)] = old_defs[old];
      const int parent = old_defs[old].parent;
      defs[static_cast<size_t>(n)].parent = parent < 0 ? -1 : new_index[static_cast<size_t>(parent)];
      rest[static_cast<size_t>(n)] = old_rest[old];
      rest_world[static_cast<size_t>(n)] = old_rest_world[old];
      layout.order[static_cast<size_t>(n)] = old_order[old];
      layout.joint_of[old_order[old]] = n;
    }
  }
  const Skeleton skeleton(defs);

  // Each animation's tracks, span and rate, all checked against the limits before any is sampled.
  struct Plan {
    std::vector<const KeyTrack*> rotation, translation, above_rotation, above_translation;
    double first = 0.0, fps = 30.0, step = 1.0 / 30.0;
    int frames = 1;
  };
  std::vector<Plan> plans;
  for (size_t i = 0; i < animations.size(); ++i) {
    const Tracks& tracks = *animations[i];
    const std::string& clip_name = layout.names[layout.moving[i]];
    // The tracks that move the skeleton: its joints' and the nodes' above it.
    std::vector<const KeyTrack*> moving;
    const auto track_of = [&](int node, TrackPath path) -> const KeyTrack* {
      const auto it = tracks.find({node, path});
      return it == tracks.end() ? nullptr : &it->second;
    };
    std::vector<const KeyTrack*> rotation(static_cast<size_t>(joints)), translation(static_cast<size_t>(joints));
    for (int j = 0; j < joints; ++j) {
      rotation[static_cast<size_t>(j)] = track_of(order[static_cast<size_t>(j)], TrackPath::kRotation);
      translation[static_cast<size_t>(j)] = track_of(order[static_cast<size_t>(j)], TrackPath::kTranslation);
    }
    std::vector<const KeyTrack*> above_rotation_tracks, above_translation_tracks;
    for (int n : layout.above) {
      above_rotation_tracks.push_back(track_of(n, TrackPath::kRotation));
      above_translation_tracks.push_back(track_of(n, TrackPath::kTranslation));
    }
    for (const auto* list : {&rotation, &translation, &above_rotation_tracks, &above_translation_tracks}) {
      for (const KeyTrack* track : *list) {
        if (track) moving.push_back(track);
      }
    }
    double first = std::numeric_limits<double>::infinity(), last = -std::numeric_limits<double>::infinity();
    for (const KeyTrack* track : moving) {
      first = std::min(first, track->times.front());
      last = std::max(last, track->times.back());
    }
    if (!std::isfinite(first)) first = last = 0.0;
    const KeyRate rate = settings.fps_override > 0.0
                             ? KeyRate{settings.fps_override, 1.0 / settings.fps_override}
                             : key_rate(moving, scene.animations[layout.moving[i]].declared_fps);
    const double fps = rate.fps;
    const double span = (last - first) / rate.step;
    poses += (span + 1) * joints;
    if (!(span < kMaxFrames) || poses > settings.max_joint_poses) {
      return Error{file, 0, fmt::format("animation '{}' would be {:.0f} frames of {} joints ({:g} s at {:g} fps), more "
                                        "than motiongraph reads ({} frames, {:g} joint poses in a file)",
                                        clip_name, span + 1, joints, last - first, fps, kMaxFrames,
                                        settings.max_joint_poses)};
    }
    plans.push_back({std::move(rotation), std::move(translation), std::move(above_rotation_tracks),
                     std::move(above_translation_tracks), first, fps, rate.step,
                     static_cast<int>(std::llround(span)) + 1});
  }
  std::vector<Clip> clips;
  for (size_t i = 0; i < plans.size(); ++i) {
    const Plan& plan = plans[i];
    const std::vector<const KeyTrack*>& rotation = plan.rotation;
    const std::vector<const KeyTrack*>& translation = plan.translation;
    const std::vector<const KeyTrack*>& above_rotation_tracks = plan.above_rotation;
    const std::vector<const KeyTrack*>& above_translation_tracks = plan.above_translation;
    const double first = plan.first, fps = plan.fps, step = plan.step;
    const int frames = plan.frames;
    Clip clip;
    clip.name = layout.names[layout.moving[i]];
    clip.skeleton = skeleton;
    clip.motion = Motion(skeleton, frames, fps);
    for (int f = 0; f < frames; ++f) {
      const double time = first + f * step;
      // The nodes above the root at this time (their rest where not animated).
      for (size_t a = 0; a < layout.above.size(); ++a) {
        above_t[a] = above_translation_tracks[a] ? as_vec3(above_translation_tracks[a]->sample(time))
                                                 : above_rest[a].translation;
        above_r[a] = above_rotation_tracks[a] ? as_quat(above_rotation_tracks[a]->sample(time)) : above_rest[a].rotation;
      }
      Vec3 frame_translation;
      Quat frame_rotation;
      compose_above(above_t, above_r, frame_translation, frame_rotation);
      auto rotations = clip.motion.rotations(f);
      auto translations = clip.motion.translations(f);
      for (int j = 0; j < joints; ++j) {
        const size_t js = static_cast<size_t>(j);
        const Quat local = rotation[js] ? as_quat(rotation[js]->sample(time)) : rest[js].rotation;
        const Quat parent_world = j == 0 ? frame_rotation : rest_world[static_cast<size_t>(defs[js].parent)];
        rotations[js] = (parent_world * local * rest_world[js].conjugate()).normalized();
        const int slot = skeleton.translation_slot(j);
        if (slot < 0) continue;
        const Vec3 t = translation[js] ? as_vec3(translation[js]->sample(time)) : rest[js].translation;
        translations[static_cast<size_t>(slot)] =
            j == 0 ? Vec3(frame_translation + above_scale * (frame_rotation * t)) : Vec3(length_scale * (parent_world * t));
      }
    }
    clips.push_back(std::move(clip));
  }
  // A static root above the hips, folded where the hips travel; then every clip of the file
  // folded as the first that was, so that they share a skeleton (a held pose's hips never travel).
  if (settings.fold_static_root) {
    const Clip* folded = nullptr;
    for (Clip& clip : clips) {
      const double size = figure_size(clip.skeleton, clip.motion);
      if (auto joint = find_trajectory_joint(clip.skeleton, clip.motion, kStaticRootFraction * size)) {
        clip = fold_static_root(clip, *joint);
        if (!folded) folded = &clip;
      }
    }
    if (folded) {
      const Skeleton reference = folded->skeleton;
      for (Clip& clip : clips) clip = fold_as(clip, reference);
    }
  }
  // The scene's up axis is +y; a file says otherwise only through the user (or its reader).
  for (Clip& clip : clips) {
    if (settings.up_axis && *settings.up_axis != UpAxis::kY) stand_up(clip, settings.up_axis);
  }
  return clips;
}

}  // namespace mg
