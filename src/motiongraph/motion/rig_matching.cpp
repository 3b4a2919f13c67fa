#include "motiongraph/motion/rig_matching.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "motiongraph/core/text.h"

namespace mg {

namespace {

constexpr double kBoneMinM = 0.01;  // shorter bones have no direction worth comparing

// Words a side letter may come before in lower-case names (CMU's lfemur, Daz's lShldr folded).
constexpr std::array<std::string_view, 26> kLimbWords = {
    "hip",    "femur", "tibia",  "foot",    "toe",   "clavicle", "humerus", "radius", "wrist",
    "hand",   "finger", "thumb", "knee",    "ankle", "shoulder", "elbow",   "collar", "shldr",
    "forearm", "shin",  "thigh", "buttock", "arm",   "leg",      "upleg",   "eye"};

std::string_view side_name(JointSide side) { return side == JointSide::kLeft ? "left" : "right"; }

}  // namespace

JointSide joint_side(std::string_view name) {
  const std::string folded = ascii_lower(name);
  const bool left = folded.find("left") != std::string::npos;
  const bool right = folded.find("right") != std::string::npos;
  if (left != right) return left ? JointSide::kLeft : JointSide::kRight;
  if (left) return JointSide::kNone;
  const auto letter_side = [](char c) {
    return c == 'l' ? JointSide::kLeft : c == 'r' ? JointSide::kRight : JointSide::kNone;
  };
  // A side letter standing alone between separators: Bip01 L Thigh, Bip01_R_Calf, hand.L.001.
  JointSide alone = JointSide::kNone;
  for (size_t begin = 0; begin < folded.size();) {
    size_t end = begin;
    while (end < folded.size() && std::isalnum(static_cast<unsigned char>(folded[end])) != 0) ++end;
    if (end == begin + 1 && letter_side(folded[begin]) != JointSide::kNone) {
      if (alone != JointSide::kNone && alone != letter_side(folded[begin])) return JointSide::kNone;
      alone = letter_side(folded[begin]);
    }
    begin = end + 1;
  }
  if (alone != JointSide::kNone) return alone;
  if (folded.size() < 3) return JointSide::kNone;
  const JointSide first = letter_side(folded.front());
  if (first == JointSide::kNone) return JointSide::kNone;
  // LHipJoint, rCollar: the side letter, then a capital starting a word (not ROOT, RIBS).
  if (is_ascii_upper(name[1]) && is_ascii_lower(name[2])) return first;
  const std::string_view rest = std::string_view(folded).substr(1);
  for (std::string_view word : kLimbWords) {
    if (rest.starts_with(word)) return first;
  }
  return JointSide::kNone;
}

std::optional<std::string> hierarchy_mismatch(const Skeleton& reference, const Skeleton& other) {
  if (reference.joint_count() != other.joint_count()) {
    return fmt::format("{} joints there, {} here", reference.joint_count(), other.joint_count());
  }
  for (int j = 0; j < reference.joint_count(); ++j) {
    const JointDef& a = reference.joint(j);
    const JointDef& b = other.joint(j);
    if (a.parent != b.parent) {
      return fmt::format("joint {} ('{}' there, '{}' here) hangs from joint {} there, {} here", j, a.name, b.name,
                         a.parent, b.parent);
    }
    if (a.end_site != b.end_site) {
      return fmt::format("joint {} is {} there ('{}'), {} here ('{}')", j, a.end_site ? "an end site" : "a joint",
                         a.name, b.end_site ? "an end site" : "a joint", b.name);
    }
    const JointSide side_a = joint_side(a.name);
    const JointSide side_b = joint_side(b.name);
    if (side_a != JointSide::kNone && side_b != JointSide::kNone && side_a != side_b) {
      return fmt::format("joint {} is '{}' ({}) there and '{}' ({}) here", j, a.name, side_name(side_a), b.name,
                         side_name(side_b));
    }
  }
  return std::nullopt;
}

std::optional<std::string> rig_difference(const Skeleton& reference, const Skeleton& other) {
  if (auto why = hierarchy_mismatch(reference, other)) return why;
  constexpr double kSameOffsetM = 1e-4;
  for (int j = 0; j < reference.joint_count(); ++j) {
    const JointDef& a = reference.joint(j);
    const JointDef& b = other.joint(j);
    if (a.name != b.name) return fmt::format("joint {} is '{}' there, '{}' here", j, a.name, b.name);
    if (a.animated_translation != b.animated_translation) {
      return fmt::format("'{}' has position channels {}", a.name, a.animated_translation ? "there only" : "here only");
    }
    const double apart = (a.rest_offset_m - b.rest_offset_m).norm();
    if (!a.animated_translation && !(apart <= kSameOffsetM)) {
      return fmt::format("the bone to '{}' is {:.2f} cm from where it is there", a.name, 100.0 * apart);
    }
  }
  const auto ancestors_a = reference.static_ancestors();
  const auto ancestors_b = other.static_ancestors();
  if (ancestors_a.size() != ancestors_b.size()) {
    return fmt::format("{} static joint(s) above the root there, {} here", ancestors_a.size(), ancestors_b.size());
  }
  for (size_t i = 0; i < ancestors_a.size(); ++i) {
    const StaticAncestor& a = ancestors_a[i];
    const StaticAncestor& b = ancestors_b[i];
    if (a.name != b.name) return fmt::format("the static joint above the root is '{}' there, '{}' here", a.name, b.name);
    // A static root is folded where it moves less than about 3 mm and 0.5 degrees over a clip,
    // keeping its first frame: two clips' folds of one rig differ by as much.
    if (!((a.translation_m - b.translation_m).norm() <= 0.005) || a.rotation.angularDistance(b.rotation) > 0.02) {
      return fmt::format("the static joint '{}' above the root stands elsewhere", a.name);
    }
  }
  return std::nullopt;
}

Clip renamed_as(const Clip& clip, const Skeleton& reference) {
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  for (size_t j = 0; j < joints.size(); ++j) joints[j].name = reference.joint(static_cast<int>(j)).name;
  const auto ancestors = clip.skeleton.static_ancestors();
  Clip out = clip;
  out.skeleton = Skeleton(std::move(joints), std::vector<StaticAncestor>(ancestors.begin(), ancestors.end()));
  return out;
}

RestPoseDifference rest_pose_difference(const Skeleton& reference, const Skeleton& other) {
  RestPoseDifference worst;
  const int joints = std::min(reference.joint_count(), other.joint_count());
  for (int j = 1; j < joints; ++j) {
    const Vec3& a = reference.joint(j).rest_offset_m;
    const Vec3& b = other.joint(j).rest_offset_m;
    if (a.norm() < kBoneMinM || b.norm() < kBoneMinM) continue;
    const double cosine = std::clamp(a.dot(b) / (a.norm() * b.norm()), -1.0, 1.0);
    const double angle = std::acos(cosine) * 180.0 / std::numbers::pi;
    if (angle > worst.angle_deg) worst = {angle, reference.joint(j).name};
  }
  return worst;
}

Clip on_rest_pose_of(const Clip& clip, const Skeleton& reference) {
  const Skeleton& skeleton = clip.skeleton;
  const int joints = skeleton.joint_count();
  // turn[j] takes the reference's rest directions in joint j's frame to the clip's: the
  // re-expressed joint's world rotation is the clip's times turn[j].
  std::vector<Quat> turn(static_cast<size_t>(joints), Quat::Identity());
  std::vector<int> bone_child(static_cast<size_t>(joints), -1);  // the single bone of 1 cm+, or -1
  std::vector<int> bones(static_cast<size_t>(joints), 0);
  for (int c = 1; c < joints && c < reference.joint_count(); ++c) {
    if (skeleton.joint(c).rest_offset_m.norm() < kBoneMinM || reference.joint(c).rest_offset_m.norm() < kBoneMinM) {
      continue;
    }
    const auto p = static_cast<size_t>(skeleton.parent(c));
    bone_child[p] = c;
    ++bones[p];
  }
  for (int j = 0; j < joints; ++j) {
    const auto jj = static_cast<size_t>(j);
    const Quat inherited = j == 0 ? Quat::Identity() : turn[static_cast<size_t>(skeleton.parent(j))];
    turn[jj] = inherited;
    if (bones[jj] != 1) continue;
    const int c = bone_child[jj];
    const Vec3 wanted = inherited * reference.joint(c).rest_offset_m.normalized();
    const Vec3 has = skeleton.joint(c).rest_offset_m.normalized();
    turn[jj] = (Quat::FromTwoVectors(wanted, has) * inherited).normalized();
  }

  // Offsets seen from the turned parent frames; the root's translation is its parent's (world).
  std::vector<JointDef> defs(skeleton.joints().begin(), skeleton.joints().end());
  for (int c = 1; c < joints; ++c) {
    defs[static_cast<size_t>(c)].rest_offset_m =
        turn[static_cast<size_t>(skeleton.parent(c))].conjugate() * defs[static_cast<size_t>(c)].rest_offset_m;
  }
  const auto ancestors = skeleton.static_ancestors();
  Clip out = clip;
  out.skeleton = Skeleton(std::move(defs), std::vector<StaticAncestor>(ancestors.begin(), ancestors.end()));
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    const auto rotations = out.motion.rotations(f);
    const auto translations = out.motion.translations(f);
    for (int j = 0; j < joints; ++j) {
      const auto jj = static_cast<size_t>(j);
      const Quat parent_turn = j == 0 ? Quat::Identity() : turn[static_cast<size_t>(skeleton.parent(j))];
      rotations[jj] = (parent_turn.conjugate() * rotations[jj] * turn[jj]).normalized();
      const int slot = skeleton.translation_slot(j);
      if (j > 0 && slot >= 0) {
        Vec3& translation = translations[static_cast<size_t>(slot)];
        translation = parent_turn.conjugate() * translation;
      }
    }
  }
  return out;
}

}  // namespace mg
