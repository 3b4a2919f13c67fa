#include "motiongraph/motion/trajectory_joint.h"

#include <algorithm>
#include <cassert>
#include <numbers>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg {

namespace {

constexpr double kStaticAngleRad = 0.5 * std::numbers::pi / 180.0;
// A root that travels without turning must leave its first place by this many tolerances (a
// tenth of the figure's size at kStaticRootFraction): an idle clip's sway is no travel.
constexpr double kTravelOverTolerance = 50.0;

Vec3 local_translation(const Skeleton& skeleton, const Motion& motion, int frame, int joint) {
  const int slot = skeleton.translation_slot(joint);
  return slot >= 0 ? motion.translations(frame)[slot] : skeleton.joint(joint).rest_offset_m;
}

// True when the joint's local transform stays within the tolerances of its first frame's.
bool is_static(const Skeleton& skeleton, const Motion& motion, int joint, double tolerance) {
  const Vec3 first_translation = local_translation(skeleton, motion, 0, joint);
  const Quat first_rotation = motion.rotations(0)[joint];
  for (int f = 1; f < motion.frame_count; ++f) {
    if ((local_translation(skeleton, motion, f, joint) - first_translation).lpNorm<Eigen::Infinity>() > tolerance) {
      return false;
    }
    if (motion.rotations(f)[joint].angularDistance(first_rotation) > kStaticAngleRad) return false;
  }
  return true;
}

// The joint below a root that travels without ever turning (an engine's root-motion joint that
// carries the translation alone): the root's child above both ankles, where the body hangs.
std::optional<int> body_below_unturning_root(const Skeleton& skeleton, const Motion& motion, double tolerance) {
  if (!skeleton.joint(0).animated_translation) return std::nullopt;
  const Quat first_rotation = motion.rotations(0)[0];
  const Vec3 first_translation = motion.translations(0)[skeleton.translation_slot(0)];
  bool travels = false;
  for (int f = 1; f < motion.frame_count; ++f) {
    if (motion.rotations(f)[0].angularDistance(first_rotation) > kStaticAngleRad) return std::nullopt;
    const Vec3 at = motion.translations(f)[skeleton.translation_slot(0)];
    const Vec3 moved = first_rotation.conjugate() * (at - first_translation);
    travels = travels || moved.lpNorm<Eigen::Infinity>() > kTravelOverTolerance * tolerance;
  }
  if (!travels) return std::nullopt;  // jitter, or an idle clip's sway, is no travel
  const auto feet = find_foot_joints(skeleton);
  if (!feet) return std::nullopt;
  std::optional<int> body;
  for (const int ankle : {feet->left.ankle, feet->right.ankle}) {
    int child = ankle;
    while (skeleton.parent(child) > 0) child = skeleton.parent(child);
    if (child <= 0 || (body && *body != child)) return std::nullopt;  // an ankle at the root, or the legs part there
    body = child;
  }
  return body;
}

}  // namespace

std::optional<int> find_trajectory_joint(const Skeleton& skeleton, const Motion& motion, double tolerance) {
  if (motion.frame_count < 2 || skeleton.joint_count() < 2) return std::nullopt;
  std::vector<int> child_count(static_cast<size_t>(skeleton.joint_count()), 0);
  std::vector<int> only_child(static_cast<size_t>(skeleton.joint_count()), -1);
  for (int j = 1; j < skeleton.joint_count(); ++j) {
    ++child_count[skeleton.parent(j)];
    only_child[skeleton.parent(j)] = j;
  }
  // Down the chain from the root to the first joint with animated translation.
  int joint = 0;
  do {
    if (child_count[joint] != 1 || !is_static(skeleton, motion, joint, tolerance)) {
      return joint == 0 ? body_below_unturning_root(skeleton, motion, tolerance) : std::nullopt;
    }
    joint = only_child[joint];
    if (skeleton.joint(joint).end_site) return std::nullopt;
  } while (!skeleton.joint(joint).animated_translation);
  // It must travel: its world position leaves the tolerance of its first frame's.
  const size_t joints = static_cast<size_t>(skeleton.joint_count());
  std::vector<Vec3> positions(joints);
  std::vector<Quat> rotations(joints);
  forward_kinematics(skeleton, motion, 0, positions, rotations);
  const Vec3 first = positions[joint];
  for (int f = 1; f < motion.frame_count; ++f) {
    forward_kinematics(skeleton, motion, f, positions, rotations);
    if ((positions[joint] - first).lpNorm<Eigen::Infinity>() > tolerance) return joint;
  }
  return std::nullopt;
}

Clip fold_as(const Clip& clip, const Skeleton& folded) {
  const auto have = clip.skeleton.static_ancestors();
  const auto want = folded.static_ancestors();
  if (have.size() >= want.size()) return clip;
  const std::optional<int> joint = clip.skeleton.find(folded.joint(0).name);
  if (!joint || *joint == 0) return clip;
  // The joints above it, root first, after the clip's own ancestors: the ones `folded` has.
  std::vector<std::string> above;
  for (const StaticAncestor& a : have) above.push_back(a.name);
  const size_t own = above.size();
  for (int a = clip.skeleton.parent(*joint); a >= 0; a = clip.skeleton.parent(a)) {
    above.insert(above.begin() + static_cast<long>(own), clip.skeleton.joint(a).name);
  }
  if (above.size() != want.size()) return clip;
  for (size_t i = 0; i < want.size(); ++i) {
    if (above[i] != want[i].name) return clip;
  }
  return fold_static_root(clip, *joint, want);  // the rig's ancestors, as `folded` has them
}

Clip fold_static_root(const Clip& clip, int trajectory_joint,
                      std::optional<std::span<const StaticAncestor>> write_back) {
  const Skeleton& skeleton = clip.skeleton;
  const Motion& motion = clip.motion;
  const int old_count = skeleton.joint_count();
  assert(trajectory_joint > 0 && trajectory_joint < old_count);

  // The chain above the trajectory joint, root first; it keeps its first frame's transforms.
  std::vector<StaticAncestor> ancestors(skeleton.static_ancestors().begin(), skeleton.static_ancestors().end());
  std::vector<int> chain;
  for (int j = skeleton.parent(trajectory_joint); j >= 0; j = skeleton.parent(j)) chain.push_back(j);
  std::reverse(chain.begin(), chain.end());
  for (int j : chain) {
    const JointDef& joint = skeleton.joint(j);
    // A joint that travels (a root carrying root motion) is written back at the origin, so that
    // every clip of its rig has one hierarchy; a static one where it stands.
    const Vec3 first = local_translation(skeleton, motion, 0, j);
    bool travels = false;
    for (int f = 1; f < motion.frame_count && !travels; ++f) {
      travels = (local_translation(skeleton, motion, f, j) - first).norm() > 1e-6 * (1.0 + first.norm());
    }
    ancestors.push_back(StaticAncestor{joint.name, travels ? Vec3::Zero() : first, motion.rotations(0)[j],
                                       joint.animated_translation, joint.euler_order});
  }

  // The trajectory joint and the joints below it; those hanging off the chain are dropped.
  std::vector<int> new_index(static_cast<size_t>(old_count), -1);
  std::vector<int> kept;
  std::vector<std::string> dropped;
  std::vector<JointDef> joints;
  for (int j = 0; j < old_count; ++j) {
    const int parent = skeleton.parent(j);
    const bool below = j == trajectory_joint || (j > trajectory_joint && new_index[static_cast<size_t>(parent)] >= 0);
    if (!below) {
      if (std::find(chain.begin(), chain.end(), j) == chain.end() && !skeleton.joint(j).end_site) {
        dropped.push_back(skeleton.joint(j).name);
      }
      continue;
    }
    new_index[static_cast<size_t>(j)] = static_cast<int>(joints.size());
    kept.push_back(j);
    JointDef joint = skeleton.joint(j);
    joint.parent = j == trajectory_joint ? -1 : new_index[static_cast<size_t>(parent)];
    if (j == trajectory_joint) joint.animated_translation = true;  // its world position, frame by frame
    joints.push_back(std::move(joint));
  }
  Clip folded;
  folded.name = clip.name;
  folded.dropped_leading_frames = clip.dropped_leading_frames;
  folded.glitched_leading_frames = clip.glitched_leading_frames;
  folded.glitched_trailing_frames = clip.glitched_trailing_frames;
  folded.dropped_at_fold = clip.dropped_at_fold;
  folded.dropped_at_fold.insert(folded.dropped_at_fold.end(), dropped.begin(), dropped.end());
  folded.detected_unit = clip.detected_unit;
  folded.detected_up_axis = clip.detected_up_axis;
  folded.in_place = clip.in_place;
  folded.skeleton =
      Skeleton(std::move(joints), write_back ? std::vector<StaticAncestor>(write_back->begin(), write_back->end())
                                             : std::move(ancestors));
  folded.motion = Motion(folded.skeleton, motion.frame_count, motion.fps);

  const size_t old_joints = static_cast<size_t>(old_count);
  std::vector<Vec3> positions(old_joints);
  std::vector<Quat> rotations(old_joints);
  for (int f = 0; f < motion.frame_count; ++f) {
    forward_kinematics(skeleton, motion, f, positions, rotations);
    auto out_rotations = folded.motion.rotations(f);
    auto out_translations = folded.motion.translations(f);
    const auto in_rotations = motion.rotations(f);
    const auto in_translations = motion.translations(f);
    for (size_t k = 0; k < kept.size(); ++k) {
      const int j = kept[k];
      const int target = static_cast<int>(k);
      out_rotations[target] = j == trajectory_joint ? rotations[j].normalized() : in_rotations[j];
      const int slot = folded.skeleton.translation_slot(target);
      if (slot < 0) continue;
      out_translations[slot] = j == trajectory_joint ? positions[j] : in_translations[skeleton.translation_slot(j)];
    }
  }
  return folded;
}

Clip unfold_static_root(const Clip& clip) {
  const Skeleton& skeleton = clip.skeleton;
  const auto ancestors = skeleton.static_ancestors();
  if (ancestors.empty()) return clip;
  const int added = static_cast<int>(ancestors.size());
  std::vector<JointDef> joints;
  for (int a = 0; a < added; ++a) {
    JointDef joint;
    joint.name = ancestors[a].name;
    joint.parent = a - 1;
    joint.rest_offset_m = ancestors[a].translation_m;
    joint.animated_translation = a == 0;
    joint.euler_order = ancestors[a].euler_order;
    joints.push_back(std::move(joint));
  }
  for (const JointDef& old : skeleton.joints()) {
    JointDef joint = old;
    joint.parent = old.parent < 0 ? added - 1 : old.parent + added;
    joints.push_back(std::move(joint));
  }
  Clip unfolded;
  unfolded.name = clip.name;
  unfolded.dropped_leading_frames = clip.dropped_leading_frames;
  unfolded.glitched_leading_frames = clip.glitched_leading_frames;
  unfolded.glitched_trailing_frames = clip.glitched_trailing_frames;
  unfolded.detected_unit = clip.detected_unit;
  unfolded.detected_up_axis = clip.detected_up_axis;
  unfolded.in_place = clip.in_place;
  unfolded.dropped_at_fold = clip.dropped_at_fold;  // not restored
  unfolded.skeleton = Skeleton(std::move(joints));
  const Motion& motion = clip.motion;
  unfolded.motion = Motion(unfolded.skeleton, motion.frame_count, motion.fps);
  // Joint 0's world transform W = A * L, A the ancestors composed: L = A^-1 W.
  const Quat inverse_rotation = skeleton.static_ancestor_rotation().conjugate();
  const Vec3 ancestor_translation = skeleton.static_ancestor_translation_m();
  for (int f = 0; f < motion.frame_count; ++f) {
    auto rotations = unfolded.motion.rotations(f);
    auto translations = unfolded.motion.translations(f);
    const auto in_rotations = motion.rotations(f);
    const auto in_translations = motion.translations(f);
    for (int a = 0; a < added; ++a) rotations[a] = ancestors[a].rotation;
    translations[0] = ancestors[0].translation_m;
    for (int j = 0; j < skeleton.joint_count(); ++j) {
      const int slot = skeleton.translation_slot(j);
      const int out_slot = unfolded.skeleton.translation_slot(j + added);
      if (j == 0) {
        rotations[added] = (inverse_rotation * in_rotations[0]).normalized();
        translations[out_slot] = inverse_rotation * (in_translations[slot] - ancestor_translation);
        continue;
      }
      rotations[j + added] = in_rotations[j];
      if (slot >= 0) translations[out_slot] = in_translations[slot];
    }
  }
  return unfolded;
}

}  // namespace mg
