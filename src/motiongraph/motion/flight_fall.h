// How fast a clip's flights fall, and so whether its clock is the capture's. A BVH file's Frame
// Time can be wrong (amc2bvh writes 30 fps for CMU's 120 fps data: data/bvh/16_01.bvh), and the
// motion then plays 4x slow with nothing to say so. Gravity does: while no foot touches the
// floor, a body's centre of mass falls at g, 9.81 m/s^2, whatever the motion. A clip read 4x slow
// shows its jumps falling at g / 16.
//
// A flight: a run of frames (at least kMinFlightFrames) where no foot joint is planted (the
// contacts), over which the mean of the joints' heights (the centre of mass, near enough) rises
// and falls as a parabola: a least-squares quadratic in time, opening downward, its apex inside
// the run, rising at least kMinFlightRiseM above the lower of the run's ends, its RMS residual
// under kMaxFlightResidual of that rise. A foot resting on something above the floor (a stool, a
// ladder's rung, uneven ground) or hands on it (a cartwheel) leaves the feet's contacts empty
// too; the body then moves as it pleases, and of CMU's 262 k frames the residual and the rise
// keep 2 such runs of the 40-odd clips with flights. So a clip's fall is measured when it has
// two flights or more, or one that rises kMinSingleFlightRiseM (a jump); then the median of the
// flights' accelerations. Measured so, CMU's captures (subjects 16, 03, 05, 14, 17, 29, 49, 135)
// fall at 0.7-1.55 g (the mean of the joints is not quite the centre of mass), and 16_01.bvh at
// 0.063 g: read 4.0x slow. Not found as yet: a clock 3x too fast or more, where contacts detected
// at the wrong speeds stretch the runs into the take-off and landing, which then fit no parabola
// within the residual (trimming the runs' ends would be the next step).
#pragma once

#include <span>

#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/skeleton/rotation.h"

namespace mg {

inline constexpr double kGravityMps2 = 9.81;
inline constexpr int kMinFlightFrames = 5;
inline constexpr double kMinFlightRiseM = 0.02;
inline constexpr double kMaxFlightResidual = 0.03;
inline constexpr double kMinSingleFlightRiseM = 0.10;

struct FlightFall {
  int flights = 0;            // flights found (see above)
  double highest_rise_m = 0.0;
  double fall_mps2 = 0.0;     // the median of their downward accelerations; 0 when not measured

  bool measured() const { return fall_mps2 > 0.0; }
  // How many times slower than it was captured the clip plays: sqrt(g / fall); 0 when not
  // measured.
  double slowdown() const;
};

// world_positions_m: frames x joint_count, frame-major, at `fps`; contacts: one mask per frame
// (empty: not measured).
FlightFall measure_flight_fall(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                               std::span<const ContactMask> contacts);

}  // namespace mg
