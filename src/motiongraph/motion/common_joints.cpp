#include "motiongraph/motion/common_joints.h"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "motiongraph/motion/trajectory_joint.h"

namespace mg {

namespace {

// The parent's name of each joint by its name ("" for the root).
std::map<std::string, std::string> parent_names(const Skeleton& skeleton) {
  std::map<std::string, std::string> parents;
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    const int parent = skeleton.parent(j);
    parents[skeleton.joint(j).name] = parent < 0 ? std::string() : skeleton.joint(parent).name;
  }
  return parents;
}

}  // namespace

std::vector<std::string> common_joints(std::span<const Skeleton> skeletons) {
  if (skeletons.empty() || skeletons.front().joint_count() == 0) return {};
  std::vector<std::map<std::string, std::string>> others;
  for (const Skeleton& skeleton : skeletons.subspan(1)) others.push_back(parent_names(skeleton));
  const Skeleton& first = skeletons.front();
  std::vector<bool> kept(static_cast<size_t>(first.joint_count()), false);
  std::vector<std::string> names;
  for (int j = 0; j < first.joint_count(); ++j) {
    const int parent = first.parent(j);
    if (parent >= 0 && !kept[static_cast<size_t>(parent)]) continue;  // below a dropped joint
    const std::string& name = first.joint(j).name;
    const std::string parent_name = parent < 0 ? std::string() : first.joint(parent).name;
    bool everywhere = true;
    for (const auto& other : others) {
      const auto it = other.find(name);
      everywhere = everywhere && it != other.end() && it->second == parent_name;
    }
    if (!everywhere) {
      if (j == 0) return {};
      continue;
    }
    kept[static_cast<size_t>(j)] = true;
    names.push_back(name);
  }
  return names;
}

std::string shared_root(std::span<const Skeleton> skeletons) {
  std::string deepest;
  int deepest_depth = -1;
  for (const Skeleton& candidate : skeletons) {
    if (candidate.joint_count() == 0) return {};
    const std::string& name = candidate.joint(0).name;
    int depth = -1;  // in the skeletons where it lies deepest below their root
    for (const Skeleton& skeleton : skeletons) {
      const std::optional<int> j = skeleton.find(name);
      if (!j) {
        depth = -1;
        break;
      }
      int d = 0;
      for (int a = *j; skeleton.parent(a) >= 0; a = skeleton.parent(a)) ++d;
      depth = std::max(depth, d);
    }
    if (depth > deepest_depth) {
      deepest = name;
      deepest_depth = depth;
    }
  }
  return deepest_depth > 0 ? deepest : std::string();
}

Result<Clip> reroot_at(const Clip& clip, const std::string& root_name, const Skeleton* above_as) {
  const std::optional<int> root = clip.skeleton.find(root_name);
  if (!root) return Error{"", 0, fmt::format("the skeleton has no joint '{}'", root_name)};
  if (*root == 0) return clip;
  // The joints above: written back as `above_as` has them, or gone.
  return fold_static_root(clip, *root, above_as ? above_as->static_ancestors() : std::span<const StaticAncestor>());
}

Result<Clip> keep_joints(const Clip& clip, std::span<const std::string> names) {
  const Skeleton& skeleton = clip.skeleton;
  std::vector<int> source;          // kept joint -> its index in the clip's skeleton
  std::map<int, int> kept_index;    // the clip's index -> kept joint
  std::vector<JointDef> joints;
  for (const std::string& name : names) {
    const std::optional<int> j = skeleton.find(name);
    if (!j) return Error{"", 0, fmt::format("the skeleton has no joint '{}'", name)};
    JointDef def = skeleton.joint(*j);
    if (joints.empty()) {
      if (*j != 0) return Error{"", 0, fmt::format("'{}' is not the skeleton's root", name)};
    } else {
      const auto parent = kept_index.find(skeleton.parent(*j));
      if (parent == kept_index.end()) {
        return Error{"", 0, fmt::format("the parent of '{}' is not among the joints kept before it", name)};
      }
      def.parent = parent->second;
    }
    kept_index[*j] = static_cast<int>(joints.size());
    source.push_back(*j);
    joints.push_back(std::move(def));
  }
  const std::vector<StaticAncestor> ancestors(skeleton.static_ancestors().begin(), skeleton.static_ancestors().end());
  Clip out;
  out.name = clip.name;
  out.skeleton = Skeleton(std::move(joints), ancestors);
  out.motion = Motion(out.skeleton, clip.motion.frame_count, clip.motion.fps);
  out.dropped_leading_frames = clip.dropped_leading_frames;
  out.glitched_leading_frames = clip.glitched_leading_frames;
  out.glitched_trailing_frames = clip.glitched_trailing_frames;
  out.detected_unit = clip.detected_unit;
  out.detected_up_axis = clip.detected_up_axis;
  out.in_place = clip.in_place;
  out.dropped_at_fold = clip.dropped_at_fold;
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    const auto rotations = clip.motion.rotations(f);
    const auto translations = clip.motion.translations(f);
    auto kept_rotations = out.motion.rotations(f);
    auto kept_translations = out.motion.translations(f);
    for (size_t k = 0; k < source.size(); ++k) {
      kept_rotations[k] = rotations[static_cast<size_t>(source[k])];
      const int slot = out.skeleton.translation_slot(static_cast<int>(k));
      if (slot >= 0) kept_translations[slot] = translations[skeleton.translation_slot(source[k])];
    }
  }
  return out;
}

}  // namespace mg
