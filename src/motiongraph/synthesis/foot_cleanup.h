// Footskate clean-up of synthesized motion (Kovar, Schreiner & Gleicher, "Footskate Cleanup
// for Motion Capture Editing", SCA 2002; DESIGN.md section 5b): every foot contact the played
// frames carry from the clips they were cut from (MotionAssembler::append_edge_contacts) keeps
// its foot in one place, however the pieces were aligned and blended.
//
// Per leg, frame by frame, in world space:
//  1. The ankle's target. While the toe is planted, the ankle moves with the toe's plant: it
//     is the ankle plus the toe's drift on the floor from its plant, where the toe was on the
//     contact's first frame (a heel rising pivots about the toe). Heights are the motion's. While only the ankle is planted (a heel strike) it is the ankle's plant:
//     where on the floor the (corrected) ankle was on the contact's first frame, at the
//     height the motion gives it. Otherwise it is the ankle where the motion puts it. A change
//     between these is eased over ease_s (smoothstep on the offset), except the start of a
//     plant, which continues the offset it starts from: the clean-up adds no step. A plant
//     the motion's foot has left by more than max_hold_m on the floor (a long contact over
//     which the pieces' placement drifted: a dancer standing for minutes) is made again
//     where the motion has the foot, the offset eased to it like any switch (and the toe's
//     plant of step 4 with it), and the foot steps there: lifted by step_height_m (at most
//     half the step's length) times 4 w (1 - w), w the ease's weight, so that it leaves and
//     reaches the floor where the ease starts and ends, rather than slide along it (a contact
//     switch cutting the step short eases what is left of the lift out over ease_s). One foot
//     steps at a time: while the other steps, a plant is held up to twice max_hold_m.
//  2. The root is lowered (only vertically, at most max_root_drop_m) just enough that both
//     legs reach their targets with the knee bent to at most max_extension of the leg's
//     length (or as straight as the motion had it); the drop is spread over the frames around
//     it at no more than root_speed_mps, looking ahead only within the frames given at once.
//  3. Analytic two-bone IK (skeleton/two_bone_ik.h) puts the ankle on its target, the knee in
//     its plane: it bends about the knee's hinge, learnt from the frames cleaned so far where
//     the knee bends by 15 degrees or more (the bend axis in the hip joint's frame), so it
//     neither flips nor bends backwards where the capture had it straight or hyperextended.
//  4. A planted toe: the foot turns about the ankle so that the toe is on its plant (over it
//     on the floor, at the height the foot's length gives), by at most 30 degrees (a plant
//     further round is not reached: the foot is not spun); after the contact the turn is
//     eased out over ease_s.
// The foot keeps the orientation the motion gives it in the world, but for that turn.
// Only rotations of the hip and knee and ankle joints and the root's height change: bone
// lengths are kept exactly. Frames are cleaned in order and each is final once cleaned, so the
// steering controller cleans the frames of each decision as it commits them; a whole walk
// cleaned at once gives the same frames except where the root drop looks ahead across the
// controller's commits. Linear in the frames cleaned.
#pragma once

#include <array>
#include <span>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg {

struct FootCleanupSettings {
  double ease_s = 0.25;            // corrections eased in and out over this long
  double max_extension = 0.995;    // a leg is stretched to at most this share of its length
  double max_root_drop_m = 0.03;   // the root is lowered at most this far
  double root_speed_mps = 0.1;     // and moved up or down at most this fast
  // A plant that would pull the foot further than this on the floor from where the motion has
  // it is let go of, and a new one made where the foot is (see step 1).
  double max_hold_m = 0.25;
  // The foot steps to the new plant, lifted at most this high (and at most half the step's
  // length) midway; 0: it slides there on the floor.
  double step_height_m = 0.05;

  Status validate() const;
};

// What a clean-up did, over the frames it cleaned.
struct FootCleanupStats {
  long long frames = 0;
  long long planted_leg_frames = 0;  // legs held on a plant (ankle or toe), summed over frames
  long long root_lowered_frames = 0;
  double max_root_drop_m = 0.0;
  double max_ankle_miss_m = 0.0;     // the furthest an ankle stayed from its target
  double max_correction_m = 0.0;     // the furthest an ankle target was from the ankle
  long long replants = 0;            // plants let go of and made again (max_hold_m)
  long long stepping_leg_frames = 0; // legs stepping to a plant made again, summed over frames
  long long both_stepping_frames = 0;  // frames both legs were (one foot steps at a time: 0)
};

class FootCleanup {
 public:
  // Fails when a foot's ankle has no knee and hip above it (two ancestors with length).
  static Result<FootCleanup> create(const Skeleton& skeleton, const FootJoints& feet, double fps,
                                    const FootCleanupSettings& settings = {});

  // Cleans frames [first, motion.frame_count) of `motion` (on the skeleton given to create) in
  // place, as the frames that follow those cleaned before (in this motion or another: the
  // studio sends each steering step's frames on their own); contacts[i] is the contact mask of
  // frame first + i.
  Status clean(Motion& motion, int first, std::span<const ContactMask> contacts);

  const FootCleanupStats& stats() const { return stats_; }
  long long frames_cleaned() const { return stats_.frames; }

 private:
  struct Leg {
    int hip = -1, knee = -1, ankle = -1, toe = -1;
    ContactMask ankle_bit = 0, toe_bit = 0;
    // Targets (step 1).
    int mode = 0;                     // 0 free, 1 ankle planted, 2 toe planted
    Vec3 ankle_plant = Vec3::Zero();
    Vec3 toe_plant = Vec3::Zero();    // a guess (step 1); toe_turn_plant is exact
    bool toe_was_planted = false;
    Vec3 offset = Vec3::Zero();       // the last frame's ankle target minus ankle
    Vec3 switch_offset = Vec3::Zero();
    int since_switch = 1 << 30;
    Vec3 replant_move = Vec3::Zero(); // the last replant's old toe plant minus its new one
    double step_lift_m = 0.0;         // the height of the step to the last replant's plant
    bool stepping = false;            // the ease under way is a replant's step
    double lift_m = 0.0;              // the last frame's lift of the ankle's target
    double lift_release_m = 0.0;      // the lift a step cut short had, eased out
    double lift_carry_m = 0.0;        // the lift when the step under way began
    int since_lift_release = 1 << 30;
    // Solving (steps 3 and 4).
    Vec3 hinge_sum = Vec3::Zero();    // the knee's bend axis in the hip joint's frame, summed
    Vec3 bend_axis = Vec3::Zero();    // the last frame's, in the world
    bool toe_turning = false;
    Vec3 toe_turn_plant = Vec3::Zero();
    Quat last_toe_turn = Quat::Identity();
    Quat applied_toe_turn = Quat::Identity();  // the last frame's, whichever way it came
    int since_toe_release = 1 << 30;
  };
  struct FrameTargets {
    std::array<Vec3, 2> ankle;
    std::array<bool, 2> corrected;   // the target differs from the ankle or the toe turns
    std::array<bool, 2> toe_planted;
    std::array<bool, 2> replanted;   // the plant was made again this frame (max_hold_m)
    std::array<Vec3, 2> toe_plant;    // the toe's plant as step 1 guessed it
    // While a replanted toe's plant is eased to its new place: how far (on the floor) the toe
    // is still to be turned short of it, the old plant's side; zero otherwise. On the replant's
    // frame it is the whole move, by which the exact plant (step 4) moves too.
    std::array<Vec3, 2> toe_plant_lag;
    double drop_needed = 0.0;
  };

  FootCleanup(const Skeleton& skeleton, double fps, const FootCleanupSettings& settings);
  double ease_weight(int frames_since) const;
  void solve_leg(Leg& leg, const FrameTargets& targets, int side, std::span<Vec3> positions, std::span<Quat> world,
                 std::span<Quat> local);

  const Skeleton* skeleton_ = nullptr;
  FootCleanupSettings settings_;
  int ease_frames_ = 1;
  double root_step_m_ = 0.0;  // per frame
  std::array<Leg, 2> legs_;
  double root_drop_ = 0.0;    // the last frame's
  FootCleanupStats stats_;
};

}  // namespace mg
