// How long a clip's walking strides take for their length, and so whether its clock is the
// capture's where it has no flights to judge it by (flight_fall.h). People walk at a nearly
// constant "walk ratio": step length grows with cadence, so that a stride's length times its
// duration hardly changes with speed (Sekiya & Nagasaki, Gait & Posture 1998: about 0.0065 m per
// step a minute in young adults, within a tenth or so between them). Made free of the figure's
// size by the pendulum's scale (a leg swings in about sqrt(H / g)), the walk ratio of a stride L
// long taking T seconds, for a figure H tall (length_unit.h figure_size), is
// (L / H) * T * sqrt(g / H); a clip read k times slow shows k times it.
//
// Judged on a walk's strides only, found without the clock: a stride is the frames from one plant
// of an ankle (its ankle contact: a toe stays low through the swing, and read slow, slow enough
// to count as planted) to the next of the same ankle, with exactly one plant of the other ankle
// in between, within kMaxPhaseOffset of its middle. It counts when
//  - it is long: the ankle's plants (their median floor positions) lie at least
//    kMinStrideFigures figure sizes apart;
//  - the body travels steadily: the mean of the joints moves along the floor in each eighth of
//    the stride at least kMinSteadiness of its mean pace, and at least kMinStraightness of its
//    path's length in a straight line;
//  - it is a walk, not a run or a leap: the body is highest where the feet pass each other (a
//    walk vaults over a stiff leg; a run sinks into a bent one), the feet's distance on the
//    floor and the mean joint height correlating at -kMinVault or less;
//  - a stride next to it (of the other ankle, before or after it) passes the rules above too, and
//    their lengths and durations lie within 1 + kMaxStrideChange of each other.
// A clip's walk ratio is the median over its strides when there are kMinWalkStrides or more.
// Boxing's footwork, karate's stances, a dancer's steps, a turn on the spot and starting or
// stopping fail one rule or another. The rules compare lengths with lengths and frame counts with
// frame counts, so they keep the same strides read at any rate, but for the contacts (found from
// speeds): a clip read 4x slow has the same strides, 4x longer.
//
// Measured so, at their own clocks, of the 170 clips of CMU subjects 3, 5, 14, 16, 17, 29, 49 and
// 135 and the 5 BVH files of data/bvh, 13 walks are judged (03_03, 03_04, 29_01, 111_36.bvh and 9
// of subject 16), with walk ratios of 1.70-2.57 (uneven terrain the lowest), centred on
// kWalkRatio; no other clip has three strides of a walk. Read 2x slow, 11 are judged, at
// 3.45-5.15; 2x fast, 14, at 0.89-1.33; 4x slow, 8, at 7.1-10.3; 4x fast, 1 (the contacts, found
// at the wrong speeds, keep fewer strides). Resampled to 30 fps, as a library is, none of the 8
// subjects' clips is doubted.
#pragma once

#include <span>

#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/skeleton/foot_joints.h"
#include "motiongraph/skeleton/rotation.h"

namespace mg {

inline constexpr double kWalkRatio = 2.1;
inline constexpr int kMinWalkStrides = 3;
inline constexpr double kMinStrideFigures = 0.3;
inline constexpr double kMinSteadiness = 0.5;
inline constexpr double kMinStraightness = 0.8;
inline constexpr double kMinVault = 0.3;
inline constexpr double kMaxStrideChange = 0.2;
inline constexpr double kMaxPhaseOffset = 0.15;

struct WalkPace {
  int strides = 0;          // walking strides judged (see above)
  double stride_m = 0.0;    // their median length
  double stride_s = 0.0;    // their median duration
  double walk_ratio = 0.0;  // the median of their walk ratios; 0 when not measured
  double figure_m = 0.0;    // the figure's size the ratios are taken with (length_unit.h)

  bool measured() const { return walk_ratio > 0.0; }
  // How many times slower than it was captured the clip plays: walk_ratio / kWalkRatio; 0 when
  // not measured.
  double slowdown() const;
  // How long people take over a stride of stride_m, a figure of figure_m: the duration whose walk
  // ratio is kWalkRatio; 0 when not measured.
  double usual_stride_s() const;
};

// world_positions_m: frames x joint_count, frame-major, at `fps`; contacts: one mask per frame
// (empty: not measured); feet: the joints whose ankle bits the contacts hold (not measured
// without both ankles among the joint_count).
WalkPace measure_walk_pace(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                           std::span<const ContactMask> contacts, const FootJoints& feet);

}  // namespace mg
