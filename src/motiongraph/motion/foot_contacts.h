// Foot contacts: per frame, whether each foot joint (ankle and toe, skeleton/foot_joints.h) is
// planted on the floor (DESIGN.md section 5b; Ikemoto, Arikan & Forsyth, "Knowing when to put
// your foot down", I3D 2006, learn the same labels; Kovar, Schreiner & Gleicher, "Footskate
// Cleanup for Motion Capture Editing", SCA 2002, need them).
//
// From world positions in metres, y up. The floor is the clip's own: for ankles, a low
// quantile (floor_quantile) of both ankles' heights over the clip, for toes the same of both
// toes' (each joint sits at its own height above the ground when planted; pooling both feet
// keeps a clip on one leg right). A joint's speed at a frame is the distance it moves over
// speed_span_s around it (central difference over +-half the span in frames, at least one),
// in m/s: the same time span at any frame rate, and a capture's one-frame jitter at 120 fps
// (heel strikes on CMU subject 16 show 1-2 m/s spikes for single frames) does not count.
//  1. A joint is planted from the frame where it is within enter_height_m of its floor and
//     slower than enter_speed_mps until it rises above leave_height_m or moves faster than
//     leave_speed_mps (hysteresis: the leave thresholds are the looser ones).
//  2. Gaps of at most max_gap_s between two contacts are filled (what jitter still splits).
//  3. Contacts shorter than min_duration_s are dropped.
// Ground that is not level (CMU subject 3 walks over obstacles up to 30 cm high: its toes rest
// 12-20 cm above the clip's floor at half their steps) leaves few frames within 3 cm of one
// floor. So, with local_window_s > 0, a joint's height is measured from its own resting height,
// the local_quantile of its heights over +-local_window_s (in a walk or run that window always
// holds a stance), and a stretch planted by the rules above counts, at most max_step_m above
// the clip's floor, where either
//  a. that resting height is within rest_tolerance_m of the lowest ground around, the same
//     quantile of both feet's heights (that part's) over the same frames (a part only one foot
//     has, a rig with one toe, takes its ankle's: its own heights are no ground), or
//  b. the foot carries the body alone: for min_duration_s in a row of the stance the other
//     foot (ankle and toe) is in no stance of its own. A step onto a stone or a stair.
// A leg held up still while the other stands (CMU 49_18's balance, its toe 31 cm up; a
// dancer's pointed foot) is neither; nor are both feet held up above max_step_m (hanging from
// a bar), nor a stair more than max_step_m above the clip's floor (a flight keeps its first
// steps only). A foot whose markers sit higher than the other's is planted where it stands
// alone (b), not while both stand (a), as on the clip's floor. With local_window_s = 0 the clip's
// floor alone, as the foot-slide measure uses it.
// Labels depend on heights and speeds only, so a clip turned about the vertical or moved on
// the floor gets the same labels.
//
// Defaults chosen on CMU subject 16 at 120 and 30 fps: walks plant each foot (ankle or toe)
// 57-68 % of a gait cycle, left and right in turn, runs 21-36 %; the labels at 30 fps agree
// with those at 120 fps on over 92 % of the time of every joint. The local floor keeps subject
// 16's labels (toes planted 55 % of its frames, 56 % with it) and plants CMU 3's toes 58 % of
// their frames instead of 6 %, CMU 49's walk 62 % instead of 40 % (docs/performance.md, "Foot
// contacts on ground that is not level").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg {

struct FootContactSettings {
  double floor_quantile = 0.02;   // the floor: this quantile of the part's heights (both feet)
  double enter_height_m = 0.03;   // planted from within this height above the floor ...
  double leave_height_m = 0.05;   // ... until above this
  double enter_speed_mps = 0.5;   // and from slower than this (infinity: height alone) ...
  double leave_speed_mps = 0.8;   // ... until faster than this
  double speed_span_s = 1.0 / 15.0;  // speeds over this time around a frame
  double max_gap_s = 0.1;         // gaps between contacts up to this long are filled (0: none)
  double min_duration_s = 0.1;    // shorter planted stretches are dropped
  // The local floor (a, b above); local_window_s = 0: the clip's floor alone.
  double local_window_s = 0.4;    // a joint's resting height over this long either side
  double local_quantile = 0.05;   // as this quantile of its heights there
  double rest_tolerance_m = 0.03; // a. resting within this of the lowest ground around
  double max_step_m = 0.5;        // a and b: resting at most this far above the clip's floor

  Status validate() const;
  // The shortest contact in frames at `fps` (at least 1).
  int min_frames(double fps) const;
  // The longest gap filled, in frames at `fps` (0: none).
  int max_gap_frames(double fps) const;
  // Half the speed span in frames at `fps` (at least 1).
  int speed_half_span_frames(double fps) const;
  // local_window_s in frames at `fps` (0: the clip's floor alone; otherwise at least 1).
  int local_window_frames(double fps) const;
};

enum class FootSide { kLeft, kRight };
enum class FootPart { kAnkle, kToe };

struct FootContactTrack {
  int joint = -1;
  FootSide side = FootSide::kLeft;
  FootPart part = FootPart::kAnkle;
  double floor_height_m = 0.0;   // the floor found for this joint's part (the clip's)
  // With the local floor, per frame the resting height the joint's height was measured from;
  // empty without it (measured from floor_height_m).
  std::vector<double> rest_height_m;
  std::vector<uint8_t> planted;  // per frame: 1 while planted
};

struct FootContacts {
  int frame_count = 0;
  // Left ankle, left toe, right ankle, right toe; a toe only when its foot has one.
  std::vector<FootContactTrack> tracks;

  // Whether the foot on `side` has its ankle or its toe planted at `frame`.
  bool foot_planted(FootSide side, int frame) const;
};

// A frame's contacts as bits, one per joint kind (left ankle, left toe, right ankle, right
// toe): what synthesis carries from the database frames into the frames it plays.
using ContactMask = uint8_t;
constexpr ContactMask contact_bit(FootSide side, FootPart part) {
  return static_cast<ContactMask>(1u << (2 * static_cast<int>(side) + static_cast<int>(part)));
}
// The bits of the tracks planted at `frame`.
ContactMask contact_mask(const FootContacts& contacts, int frame);
// Per bit, each run of at most `max_gap` unplanted frames between two planted ones planted, as the
// captured contacts' gaps are (FootContactSettings::max_gap_s): where frames blended from two
// clips take the contacts of the one weighing most, a foot planted in both can lose its contact
// for the frame the weights cross, and the clean-up plants it again a step away.
void fill_contact_gaps(std::span<ContactMask> contacts, int max_gap);

// The feet's joints with their bits, in the order left ankle, left toe, right ankle, right toe,
// a foot without a toe joint giving its ankle only: the columns of a contact table (the positions
// JSON's "contacts", Python's Motion.contacts).
struct ContactColumn {
  int joint = -1;
  ContactMask bit = 0;
};
std::vector<ContactColumn> contact_columns(const FootJoints& feet);

// A run of planted frames.
struct ContactInterval {
  int first_frame = 0;
  int frame_count = 0;
};

// The planted runs of one track, in order.
std::vector<ContactInterval> contact_intervals(std::span<const uint8_t> planted);

// Contacts from world positions, frames x joint_count, frame-major (world_positions()).
Result<FootContacts> detect_foot_contacts(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                                          const FootJoints& feet, const FootContactSettings& settings);

// The same from a skeleton and its motion (forward kinematics first).
Result<FootContacts> detect_foot_contacts(const Skeleton& skeleton, const Motion& motion, const FootJoints& feet,
                                          const FootContactSettings& settings);

}  // namespace mg
