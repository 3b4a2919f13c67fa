// Footskate clean-up: targets from the contacts, the root's drop, two-bone IK, the toe's turn.
#include "motiongraph/synthesis/foot_cleanup.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/skeleton/two_bone_ik.h"

namespace mg {

namespace {

constexpr int kFree = 0, kAnklePlanted = 1, kToePlanted = 2;
constexpr int kLongAgo = 1 << 30;
constexpr double kMinBone = 0.01;  // m: shorter "bones" are not a thigh or a shank
const double kMaxToeTurn = 30.0 * std::numbers::pi / 180.0;  // the foot turned onto its toe's plant at most
const double kHingeSin = std::sin(15.0 * std::numbers::pi / 180.0);  // a knee bent this much shows its hinge

// How far the root must come down (>= 0) so that a leg from `hip` spans to `target` within
// `reach`; the full drop needed to put the hip above the target when no drop reaches.
double drop_to_reach(const Vec3& hip, const Vec3& target, double reach) {
  const Vec3 v = target - hip;
  const double across = v.x() * v.x() + v.z() * v.z();
  if (across >= reach * reach) return std::max(0.0, -v.y());
  return std::max(0.0, -v.y() - std::sqrt(reach * reach - across));
}

}  // namespace

Status FootCleanupSettings::validate() const {
  if (!(ease_s >= 0.0) || !std::isfinite(ease_s)) return Error{"", 0, "the clean-up's easing time must be finite and >= 0 s"};
  if (!(max_extension > 0.5 && max_extension < 1.0)) {
    return Error{"", 0, "the clean-up's leg extension must be within 0.5..1 (a share of the leg's length)"};
  }
  if (!(max_root_drop_m >= 0.0) || !std::isfinite(max_root_drop_m)) {
    return Error{"", 0, "the clean-up's root drop must be finite and >= 0 m"};
  }
  if (!(root_speed_mps > 0.0) || !std::isfinite(root_speed_mps)) {
    return Error{"", 0, "the clean-up's root speed must be finite and > 0 m/s"};
  }
  if (!(step_height_m >= 0.0) || !std::isfinite(step_height_m)) {
    return Error{"", 0, "the clean-up's step height must be finite and >= 0 m"};
  }
  if (!(max_hold_m > 0.0) || !std::isfinite(max_hold_m)) {
    return Error{"", 0, "the clean-up's longest hold must be finite and > 0 m"};
  }
  return Ok{};
}

FootCleanup::FootCleanup(const Skeleton& skeleton, double fps, const FootCleanupSettings& settings)
    : skeleton_(&skeleton), settings_(settings) {
  ease_frames_ = std::max(1, static_cast<int>(std::lround(settings.ease_s * fps)));
  root_step_m_ = settings.root_speed_mps / fps;
}

Result<FootCleanup> FootCleanup::create(const Skeleton& skeleton, const FootJoints& feet, double fps,
                                        const FootCleanupSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  if (!(fps > 0.0)) return Error{"", 0, "the clean-up needs a frame rate > 0"};
  FootCleanup cleanup(skeleton, fps, settings);
  const std::array<std::pair<Foot, FootSide>, 2> sides{std::pair{feet.left, FootSide::kLeft},
                                                        std::pair{feet.right, FootSide::kRight}};
  for (int side = 0; side < 2; ++side) {
    const auto& [foot, foot_side] = sides[side];
    Leg& leg = cleanup.legs_[side];
    if (foot.ankle <= 0 || foot.ankle >= skeleton.joint_count()) {
      return Error{"", 0, "the clean-up needs both ankles below the root"};
    }
    leg.ankle = foot.ankle;
    leg.knee = skeleton.parent(leg.ankle);
    leg.hip = leg.knee > 0 ? skeleton.parent(leg.knee) : -1;
    if (leg.hip < 0 || skeleton.joint(leg.ankle).rest_offset_m.norm() < kMinBone ||
        skeleton.joint(leg.knee).rest_offset_m.norm() < kMinBone) {
      return Error{"", 0, fmt::format("the clean-up needs a knee and a hip above ankle '{}' (its parent and "
                                      "grandparent, each at least {} m from the joint below)",
                                      skeleton.joint(leg.ankle).name, kMinBone)};
    }
    leg.toe = foot.toe;
    leg.ankle_bit = contact_bit(foot_side, FootPart::kAnkle);
    leg.toe_bit = foot.toe >= 0 ? contact_bit(foot_side, FootPart::kToe) : 0;
  }
  return cleanup;
}

double FootCleanup::ease_weight(int frames_since) const {
  if (frames_since >= ease_frames_) return 0.0;
  const double u = static_cast<double>(frames_since) / ease_frames_;
  return 1.0 - u * u * (3.0 - 2.0 * u);
}

Status FootCleanup::clean(Motion& motion, int first, std::span<const ContactMask> contacts) {
  const int count = motion.frame_count - first;
  if (first < 0 || count < 0 || static_cast<int>(contacts.size()) != count) {
    return Error{"", 0, fmt::format("{} contact masks for {} frames", contacts.size(), std::max(count, 0))};
  }
  if (motion.joint_count != skeleton_->joint_count()) return Error{"", 0, "the motion is not on the clean-up's skeleton"};
  const Skeleton& skeleton = *skeleton_;
  const size_t joints = static_cast<size_t>(skeleton.joint_count());
  std::vector<Vec3> positions(joints);
  std::vector<Quat> world(joints);

  // Step 1: targets, from the motion as it was played.
  std::vector<FrameTargets> targets(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    forward_kinematics(skeleton, motion, first + i, positions, world);
    FrameTargets& frame = targets[i];
    for (int side = 0; side < 2; ++side) {
      Leg& leg = legs_[side];
      const Vec3& ankle = positions[leg.ankle];
      const Vec3 toe = leg.toe >= 0 ? positions[leg.toe] : ankle;
      const bool ankle_on = (contacts[i] & leg.ankle_bit) != 0;
      const bool toe_on = (contacts[i] & leg.toe_bit) != 0;
      const bool toe_starts = toe_on && !leg.toe_was_planted;
      if (toe_starts) leg.toe_plant = toe + leg.offset;
      leg.toe_was_planted = toe_on;
      // A planted toe governs: a heel rising within its contact pivots about the toe.
      const int mode = toe_on ? kToePlanted : (ankle_on ? kAnklePlanted : kFree);
      if (mode != leg.mode) {
        if (mode == kAnklePlanted) {
          leg.ankle_plant = ankle + leg.offset;  // continues the offset: no blend needed
          leg.since_switch = kLongAgo;
        } else if (mode == kToePlanted && toe_starts) {
          leg.since_switch = kLongAgo;           // the toe's plant continues the offset
        } else {
          leg.switch_offset = leg.offset;
          leg.since_switch = 0;
        }
        if (leg.stepping) {  // a step cut short: what is left of its lift eases out
          leg.stepping = false;
          leg.lift_release_m = leg.lift_m;
          leg.since_lift_release = 0;
        }
        leg.mode = mode;
      }
      Vec3 mode_offset =
          mode == kAnklePlanted ? Vec3(leg.ankle_plant - ankle) : mode == kToePlanted ? Vec3(leg.toe_plant - toe) : Vec3::Zero();
      // Held on the floor only: a foot's height is the motion's (a heel rising within its
      // contact rises as the foot rolls; a running toe's rise at toe-off is kept, which
      // holding it down would carry, eased out, into the swing, low and fast).
      mode_offset.y() = 0.0;
      // A plant the motion has left further than max_hold_m (a long contact over which the
      // placement drifted) is let go: a new one where the motion has the foot, reached by
      // easing as at any switch (a quick step instead of a leg stretched out of reach).
      // One foot steps at a time: while the other is stepping this one is held on (a plant
      // left twice as far is let go of all the same), so that both do not leave the floor.
      const Leg& other = legs_[1 - side];
      const bool other_stepping = settings_.step_height_m > 0.0 && other.stepping && other.since_switch < ease_frames_;
      const double hold = other_stepping ? 2.0 * settings_.max_hold_m : settings_.max_hold_m;
      frame.replanted[side] = mode != kFree && mode_offset.norm() > hold;
      if (frame.replanted[side]) {
        if (mode == kAnklePlanted) leg.ankle_plant = ankle;
        leg.replant_move = mode == kToePlanted ? Vec3(leg.toe_plant - toe) : Vec3::Zero();
        leg.replant_move.y() = 0.0;
        leg.toe_plant = toe;
        leg.switch_offset = leg.offset;
        leg.since_switch = 0;
        leg.lift_carry_m = leg.lift_m;  // a step made again mid-step goes on from its height
        leg.stepping = settings_.step_height_m > 0.0;
        leg.step_lift_m = std::min(settings_.step_height_m,
                                   0.5 * std::hypot(leg.switch_offset.x(), leg.switch_offset.z()));
        mode_offset = Vec3::Zero();
        ++stats_.replants;
      }
      const double w = ease_weight(leg.since_switch);
      if (leg.since_switch >= ease_frames_) leg.stepping = false;
      leg.offset = w * leg.switch_offset + (1.0 - w) * mode_offset;
      if (leg.since_switch < kLongAgo) ++leg.since_switch;
      // The step's lift, kept out of the offset (the plants continue the offset on the floor).
      leg.lift_m = leg.stepping ? std::max(leg.lift_carry_m * w, leg.step_lift_m * 4.0 * w * (1.0 - w))
                                : leg.lift_release_m * ease_weight(leg.since_lift_release);
      if (leg.since_lift_release < kLongAgo) ++leg.since_lift_release;
      frame.ankle[side] = ankle + leg.offset + Vec3(0.0, leg.lift_m, 0.0);
      if (leg.stepping) ++stats_.stepping_leg_frames;
      if (side == 1 && leg.stepping && legs_[0].stepping) ++stats_.both_stepping_frames;
      frame.toe_planted[side] = toe_on;
      frame.toe_plant[side] = leg.toe_plant;
      // A toe's plant starts only where its contact starts (the offset continued: w = 0); a
      // replant eases it on as the ankle's offset eases (w from 1 to 0).
      frame.toe_plant_lag[side] = mode == kToePlanted ? Vec3(w * leg.replant_move) : Vec3::Zero();
      stats_.planted_leg_frames += mode != kFree ? 1 : 0;
      stats_.max_correction_m = std::max(stats_.max_correction_m, leg.offset.norm());
      const Vec3& hip = positions[leg.hip];
      const Vec3 thigh = positions[leg.knee] - hip, shank = ankle - positions[leg.knee];
      const Vec3 bend = thigh.cross(shank);
      if (bend.norm() >= kHingeSin * thigh.norm() * shank.norm()) {
        leg.hinge_sum += world[leg.hip].conjugate() * bend.normalized();
      }
      const double length = (positions[leg.knee] - hip).norm() + (ankle - positions[leg.knee]).norm();
      const double reach = std::max(settings_.max_extension * length, (ankle - hip).norm());
      frame.drop_needed = std::max(frame.drop_needed, std::min(drop_to_reach(hip, frame.ankle[side], reach),
                                                               settings_.max_root_drop_m));
    }
  }

  // Step 2: the root's drop, spread at most root_step_m_ a frame (from the last frame
  // cleaned, and ahead of a need within these frames).
  std::vector<double> drop(static_cast<size_t>(count));
  double previous = root_drop_;
  for (int i = 0; i < count; ++i) previous = drop[i] = std::max(targets[i].drop_needed, previous - root_step_m_);
  for (int i = count - 2; i >= 0; --i) drop[i] = std::max(drop[i], drop[i + 1] - root_step_m_);

  // Steps 3 and 4, frame by frame.
  const int root_slot = skeleton.translation_slot(0);
  for (int i = 0; i < count; ++i) {
    const int frame = first + i;
    if (root_slot >= 0) motion.translations(frame)[root_slot].y() -= drop[i];
    forward_kinematics(skeleton, motion, frame, positions, world);
    for (int side = 0; side < 2; ++side) solve_leg(legs_[side], targets[i], side, positions, world, motion.rotations(frame));
    stats_.root_lowered_frames += drop[i] > 0.0 ? 1 : 0;
    stats_.max_root_drop_m = std::max(stats_.max_root_drop_m, drop[i]);
  }
  if (count > 0) root_drop_ = drop.back();
  stats_.frames += count;
  return Ok{};
}

void FootCleanup::solve_leg(Leg& leg, const FrameTargets& targets, int side, std::span<Vec3> positions,
                            std::span<Quat> world, std::span<Quat> local) {
  const Vec3 hip = positions[leg.hip], knee = positions[leg.knee], ankle = positions[leg.ankle];
  Vec3 target = targets.ankle[side];
  if (targets.replanted[side] && leg.toe_turning) {
    // The exact plant moves with the guessed one (the toe is turned towards it as it eases).
    leg.toe_turn_plant -= targets.toe_plant_lag[side];
  }
  if (targets.toe_planted[side] && leg.toe_turning) {
    // Step 1 followed the toe's plant as it guessed it; the toe's plant is where the toe was.
    const Vec3 exact = leg.toe_turn_plant - targets.toe_plant[side];
    target += Vec3(exact.x(), 0.0, exact.z());
  }
  Quat leg_turn = Quat::Identity();  // world rotation the IK gave the shank
  Vec3 new_ankle = ankle;
  if ((target - ankle).norm() > 1e-9) {
    const double length = (knee - hip).norm() + (ankle - knee).norm();
    const double extension = std::min(0.9999, std::max(settings_.max_extension, (ankle - hip).norm() / length));
    const Vec3 hinge = leg.hinge_sum.norm() > 1e-9 ? Vec3(world[leg.hip] * leg.hinge_sum.normalized()) : leg.bend_axis;
    const TwoBoneSolution solution = solve_two_bone(hip, knee, ankle, target, hinge, extension);
    apply_two_bone(*skeleton_, world, leg.hip, leg.knee, solution, local);
    leg_turn = solution.upper * solution.lower;
    new_ankle = solution.ankle;
    stats_.max_ankle_miss_m = std::max(stats_.max_ankle_miss_m, (solution.ankle - target).norm());
    const Vec3 axis = (solution.knee - hip).cross(solution.ankle - solution.knee);
    if (axis.norm() > 1e-9) leg.bend_axis = axis.normalized();
  } else {
    const Vec3 axis = (knee - hip).cross(ankle - knee);
    if (axis.norm() > 1e-9) leg.bend_axis = axis.normalized();
  }
  Quat toe_turn = Quat::Identity();
  if (leg.toe >= 0) {
    const Vec3 foot = positions[leg.toe] - ankle;  // ankle to toe: the foot keeps its orientation
    if (targets.toe_planted[side]) {
      if (!leg.toe_turning) {
        const Quat easing = Quat::Identity().slerp(ease_weight(leg.since_toe_release), leg.last_toe_turn);
        // Where the toe is turned to now; the plant itself where a replant eases it to.
        leg.toe_turn_plant = new_ankle + easing * foot - targets.toe_plant_lag[side];
        leg.toe_turning = true;
      }
      // Onto the plant's vertical: the height at which the foot's length reaches it, on the side
      // of the ankle the toe is (as high as the motion has it when the plant is out of reach).
      const Vec3 plant = leg.toe_turn_plant + targets.toe_plant_lag[side];
      const Vec3 across(plant.x() - new_ankle.x(), 0.0, plant.z() - new_ankle.z());
      const double rise_squared = foot.squaredNorm() - across.squaredNorm();
      const double rise = rise_squared > 0.0 ? std::copysign(std::sqrt(rise_squared), foot.y()) : foot.y();
      // At most kMaxToeTurn: a plant the foot would have to spin round to reach is let go of
      // that far (the foot turns as a foot can; a capture's pivot on the toe is not undone).
      Quat turn = Quat::FromTwoVectors(foot, across + Vec3(0.0, rise, 0.0));
      const double angle = turn.angularDistance(Quat::Identity());
      if (angle > kMaxToeTurn) turn = Quat::Identity().slerp(kMaxToeTurn / angle, turn);
      // And no faster than kMaxToeTurn over the ease: a plant the motion carries the ankle past
      // (its toe rising above the ankle, then not) swings the foot round, capped at once the
      // other way, a pop of the toe by 0.2 m in a frame; over frames, it is a turn.
      const double swing = turn.angularDistance(leg.applied_toe_turn);
      const double most = kMaxToeTurn / ease_frames_;
      if (swing > most) turn = leg.applied_toe_turn.slerp(most / swing, turn);
      leg.last_toe_turn = turn;
      toe_turn = leg.last_toe_turn;
    } else {
      if (leg.toe_turning) {
        leg.toe_turning = false;
        leg.since_toe_release = 0;
      }
      toe_turn = Quat::Identity().slerp(ease_weight(leg.since_toe_release), leg.last_toe_turn);
      if (leg.since_toe_release < kLongAgo) ++leg.since_toe_release;
    }
  }
  leg.applied_toe_turn = toe_turn;
  if (toe_turn.vec().norm() > 1e-12 || leg_turn.vec().norm() > 1e-12) {
    // The foot keeps its world orientation (turned onto the toe's plant): the ankle's world
    // rotation becomes toe_turn * W[ankle] under its parent, the knee, now at leg_turn * W[knee].
    local[leg.ankle] = ((leg_turn * world[leg.knee]).conjugate() * toe_turn * world[leg.ankle]).normalized();
  }
}

}  // namespace mg
