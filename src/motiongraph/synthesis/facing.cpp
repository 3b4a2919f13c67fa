#include "motiongraph/synthesis/facing.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "motiongraph/skeleton/foot_joints.h"
#include "motiongraph/synthesis/floor_transform.h"

namespace mg {

Vec2 travel_direction(const std::vector<Vec2>& roots, int i, int lookahead, double fps, double min_speed_mps) {
  if (i + lookahead >= static_cast<int>(roots.size())) return Vec2::Zero();
  const Vec2 d = roots[i + lookahead] - roots[i];
  const double n = d.norm();
  if (n * fps / lookahead < min_speed_mps || n == 0.0) return Vec2::Zero();
  return d / n;
}

namespace {

// A joint's rest offset shorter than this does not set it off from its parent (ASF's
// hipjoint starts where the root is).
constexpr double kSetOffM = 0.01;

// The root's floor positions over a clip.
std::vector<Vec2> floor_roots(const Motion& motion) {
  std::vector<Vec2> roots(static_cast<size_t>(motion.frame_count));
  for (int f = 0; f < motion.frame_count; ++f) {
    const Vec3& p = motion.translations(f)[0];
    roots[static_cast<size_t>(f)] = Vec2(p.x(), p.z());
  }
  return roots;
}

// The joints from the root down to `joint`, root first.
std::vector<int> chain_to(const Skeleton& skeleton, int joint) {
  std::vector<int> chain;
  for (int j = joint; j >= 0; j = skeleton.joint(j).parent) chain.push_back(j);
  std::reverse(chain.begin(), chain.end());
  return chain;
}

// The left and right hips: below the joint where the chains to the two ankles part, the first
// joint of each chain set off from its parent; nullopt when a chain has none.
std::optional<std::pair<int, int>> find_hips(const Skeleton& skeleton, const FootJoints& feet) {
  const std::vector<int> left = chain_to(skeleton, feet.left.ankle);
  const std::vector<int> right = chain_to(skeleton, feet.right.ankle);
  size_t common = 0;
  while (common < left.size() && common < right.size() && left[common] == right[common]) ++common;
  auto hip = [&](const std::vector<int>& chain) -> int {
    for (size_t i = common; i < chain.size(); ++i) {
      if (skeleton.joint(chain[i]).rest_offset_m.norm() > kSetOffM) return chain[i];
    }
    return -1;
  };
  const int l = hip(left), r = hip(right);
  if (l < 0 || r < 0) return std::nullopt;
  return std::pair(l, r);
}

// A joint's position in the root's frame (the root's own rotation and translation left out).
Vec3 in_root_frame(const Skeleton& skeleton, const Motion& motion, int frame, int joint) {
  const auto rotations = motion.rotations(frame);
  const auto translations = motion.translations(frame);
  Vec3 p = Vec3::Zero();
  for (int j = joint; skeleton.joint(j).parent >= 0; j = skeleton.joint(j).parent) {
    const int slot = skeleton.translation_slot(j);
    p = rotations[j] * p + (slot >= 0 ? translations[slot] : skeleton.joint(j).rest_offset_m);
  }
  return p;
}

// Below this mean cosine between the hips' facing and the travel over the moving frames, the
// travel does not say which way is forward (a library of sidesteps, or of turns on the spot):
// the hips' own sign, up x (right - left), stands.
constexpr double kTravelSignMargin = 0.2;

// Where the hips of skeleton `s` face, in its root's frame, into *choice (axis, hips,
// turned_about); false (choice->why_not_hips said) without feet, hips or a frame whose hips lie
// apart on the floor. Each frame weighs as far as its hips lie apart on the floor (a figure lying
// on its side, hips one above the other, says little).
bool hips_axis(const MotionDatabase& db, int s, ForwardAxisChoice* choice) {
  const Skeleton& skeleton = db.skeletons[static_cast<size_t>(s)];
  const auto feet = find_foot_joints(skeleton, db.foot_names);
  if (!feet) {
    choice->why_not_hips = "no feet: " + feet.error().message;
    return false;
  }
  const auto hips = find_hips(skeleton, *feet);
  if (!hips) {
    choice->why_not_hips = "no hip joint set off on the chains from where the legs part to the ankles";
    return false;
  }
  Vec3 sum = Vec3::Zero();
  double along_travel = 0.0;
  long long moving = 0;
  for (const DatabaseClip& clip : db.clips) {
    if (clip.skeleton != s) continue;
    const std::vector<Vec2> roots = floor_roots(clip.motion);
    for (int f = 0; f < clip.frame_count; ++f) {
      const Quat& root = clip.motion.rotations(f)[0];
      const Vec3 across =
          root * (in_root_frame(skeleton, clip.motion, f, hips->second) - in_root_frame(skeleton, clip.motion, f, hips->first));
      const Vec2 facing(across.z(), -across.x());  // up x across, on the floor
      const double n = facing.norm();
      if (n < 1e-6) continue;
      sum += root.conjugate() * Vec3(facing.x(), 0.0, facing.y());
      const Vec2 d = travel_direction(roots, f, kTravelLookaheadFrames, db.fps, kMovingSpeedMps);
      if (d.isZero()) continue;
      along_travel += d.dot(facing) / n;
      ++moving;
    }
  }
  if (sum.norm() < 1e-9) {
    choice->why_not_hips = "the hips never lie apart on the floor";
    return false;
  }
  const bool backwards = moving > 0 && along_travel < -kTravelSignMargin * static_cast<double>(moving);
  choice->axis = (backwards ? -sum : sum).normalized();
  choice->left_hip = hips->first;
  choice->right_hip = hips->second;
  choice->turned_about = backwards;
  return true;
}

}  // namespace

std::vector<Vec3> learn_travel_axes(const MotionDatabase& db) {
  std::vector<Vec3> sums(db.skeletons.size(), Vec3::Zero());
  for (const DatabaseClip& clip : db.clips) {
    const std::vector<Vec2> roots = floor_roots(clip.motion);
    for (int f = 0; f < clip.frame_count; ++f) {
      const Vec2 d = travel_direction(roots, f, kTravelLookaheadFrames, db.fps, kMovingSpeedMps);
      if (d.isZero()) continue;
      sums[clip.skeleton] += clip.motion.rotations(f)[0].conjugate() * Vec3(d.x(), 0.0, d.y());
    }
  }
  std::vector<Vec3> axes;
  axes.reserve(sums.size());
  for (const Vec3& s : sums) axes.push_back(s.norm() > 0.0 ? Vec3(s.normalized()) : Vec3(Vec3::UnitZ()));
  return axes;
}

ForwardAxisChoice choose_forward_axis(const MotionDatabase& db, int skeleton, const Vec3& travel_axis) {
  ForwardAxisChoice choice;
  choice.travel_axis = travel_axis;
  if (!hips_axis(db, skeleton, &choice)) choice.axis = travel_axis;
  return choice;
}

Vec3 learn_forward_axis(const MotionDatabase& db, int skeleton, const Vec3& travel_axis) {
  return choose_forward_axis(db, skeleton, travel_axis).axis;
}

std::vector<Vec3> learn_forward_axes(const MotionDatabase& db) {
  std::vector<Vec3> axes = learn_travel_axes(db);
  for (size_t s = 0; s < axes.size(); ++s) axes[s] = learn_forward_axis(db, static_cast<int>(s), axes[s]);
  return axes;
}

Vec3 learn_clip_forward_axis(const Skeleton& skeleton, const Motion& motion, const FootJointNames& feet) {
  if (skeleton.translation_slot(0) != 0) return Vec3::UnitZ();
  MotionDatabase db;
  db.fps = motion.fps;
  db.foot_names = feet;
  db.skeletons.push_back(skeleton);
  db.skeleton_names.emplace_back();
  db.clips.push_back(DatabaseClip{"clip", "", 0, 0, motion.frame_count, motion});
  const ForwardAxisChoice choice = choose_forward_axis(db, 0, learn_travel_axes(db)[0]);
  if (choice.left_hip < 0) return choice.axis;
  Vec3 axis = choice.turned_about ? Vec3(-choice.axis) : choice.axis;  // the hips' own sign
  const auto found = find_foot_joints(skeleton, feet);
  if (!found) return axis;
  double along = 0.0;
  for (int f = 0; f < motion.frame_count; ++f) {
    for (const Foot& foot : {found->left, found->right}) {
      if (foot.toe < 0) continue;
      along += (in_root_frame(skeleton, motion, f, foot.toe) - in_root_frame(skeleton, motion, f, foot.ankle)).dot(axis);
    }
  }
  return along < 0.0 ? Vec3(-axis) : axis;
}

Vec2 facing_on_floor(const Quat& root_world_rotation, const Vec3& forward_axis) {
  const Vec3 f = root_world_rotation * forward_axis;
  const Vec2 d(f.x(), f.z());
  const double n = d.norm();
  return n > 1e-9 ? Vec2(d / n) : Vec2(Vec2::Zero());
}

double facing_off_deg(const Quat& root_world_rotation, const Vec3& forward_axis, const Vec2& direction) {
  return std::abs(yaw_between(direction, facing_on_floor(root_world_rotation, forward_axis))) * 180.0 /
         std::numbers::pi;
}

}  // namespace mg
