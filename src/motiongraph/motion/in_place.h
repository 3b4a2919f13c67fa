// Clips animated in place, and their travel recovered from the planted feet.
//
// Game libraries and many exports (Mixamo's "In Place", loops made for a game engine's own root
// motion) take the root's travel over the floor out of a clip: the figure walks or runs on the
// spot, and its planted foot slides backwards at the walking speed. A graph of such clips cannot
// follow a path (path says the library hardly travels), and the foot clean-up would pin a foot
// the motion drags. A capture's planted foot stays put; so the feet say how far the root went.
//
// Judged per clip on its world positions (metres, y up) and its feet (skeleton/foot_joints.h:
// ankle and toe joints). A foot joint is low in a frame when it is within `contact_height_m` of
// its own floor level, the `floor_quantile` of its heights over the clip (so a figure read a
// little above or below y = 0, or on a toe joint that never reaches the floor, is judged alike).
// An interval between two frames is on the ground when some foot joint is low at both ends.
//   - The slide: over the ground intervals, the median speed of the stillest low joint. A
//     capture's is small (CMU's 170 clips of the 8-subject library: 0.00-0.42 m/s, the most a
//     clip hanging from ropes, then runs, whose roots move 8-16 times as fast as their feet
//     slide); in place every planted foot moves at the
//     walking speed (0.36-3.7 m/s on the 73 of those clips judged in place with their travel
//     taken out).
//   - The root's speed: its path over the floor sampled every half second, over the duration
//     (a sway of a few centimetres a step counts little).
//   - In place: a slide of at least `min_slide_speed` that is also at least `root_speed_ratio`
//     times the root's speed.
//
// Recovery: in each ground interval of a clip in place the planted joint is the low joint that
// moves furthest backwards, along the low joints' mean displacement over `direction_window_s`
// around it (a foot rolling onto its toe, or lifting, moves forwards of the planted one); in a
// clip that travels (asked for its feet all the same) it is the stillest low joint. The root
// moves by minus that joint's displacement, so the joint stays where it was. Intervals off the ground (a
// run's flight) take the displacement interpolated linearly between the ground intervals either
// side. The root's own motion (its sway) is kept, and so is every rotation: only the trajectory
// joint's (joint 0's) translation over the floor changes. Measured on those 170 clips with their
// travel taken out: walks get back a median 96 % of their travel, runs 81 % (a capture's
// planted foot slips 0.2-0.3 m/s in a run), jumps none (their travel is made in the air); feet
// moving near the floor without carrying the body (boxing, legs swung from a stool, ropes) are
// taken for steps.
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/in_place_choice.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg {

struct InPlaceSettings {
  double contact_height_m = 0.03;   // a foot joint this close to its floor level is low
  double floor_quantile = 0.05;     // a joint's floor level: this quantile of its heights
  double min_slide_speed = 0.35;    // m/s: a slower slide is a capture's
  double root_speed_ratio = 2.0;    // the slide at least this many times the root's speed
  double direction_window_s = 1.0;  // backwards: the low joints' mean displacement over this

  Status validate() const;
};

// recover_travel judges a clip on every n-th frame, n its rate over this, rounded down (every
// 4th of a capture at 120 fps); it recovers the travel at the clip's own rate.
constexpr double kJudgedFps = 30.0;

std::string_view travel_source_name(TravelSource source);  // "auto", "root", "feet"
// "auto", "root" or "feet" (either case); nullopt for anything else.
std::optional<TravelSource> parse_travel_source(std::string_view text);

// The judgement above. world_positions_m: frames x joint_count, frame-major.
InPlaceChoice judge_in_place(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                             const FootJoints& feet, const InPlaceSettings& settings = {});

// The travel recovered from the feet as above (in_place: the clip was judged in place): per
// frame, the floor displacement (y = 0) to add to the root's position, zero at frame 0.
std::vector<Vec3> travel_from_feet(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                                   const FootJoints& feet, bool in_place, const InPlaceSettings& settings = {});

// The clip's travel from `source`: kRoot leaves it; kFeet recovers it; kAuto recovers it when
// the clip is judged in place. clip.in_place keeps the judgement (kAuto, kFeet). Fails when the
// feet are not found (kFeet only: kAuto then leaves the clip) or joint 0 has no animated
// translation to carry the travel.
Status recover_travel(Clip& clip, TravelSource source, const FootJointNames& names = {},
                      const InPlaceSettings& settings = {});

}  // namespace mg
