// What looks wrong with a clip as read: a figure of no person's size (read in the wrong unit:
// `--scale 0.01` given for a file in metres), one that floats above the floor or sinks below it
// (y = 0), and feet that never rest on it. A converter that offsets or rescales the root's
// translation gives the last two (the BVH 07_12 in data/bvh: hips at -0.33..0 m, the lowest
// joint 0.57-0.90 m below the floor, feet sliding 3 m/s), and the distance metric, which compares
// heights as read, then joins such a clip to nothing. And a clock that is not the capture's: its
// flights falling much slower or faster than gravity (flight_fall.h; a Frame Time of 30 fps on
// 120 fps data, data/bvh/16_01.bvh), or, in a clip without flights, its walking strides taking
// much longer or shorter than people's of their length (walk_pace.h). Loading reports them (a
// warning per clip, or one for clips whose clock alone is off alike: clip_doubt_lines) so that
// the user checks the file before wondering about the graph.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/flight_fall.h"
#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/motion/walk_pace.h"

namespace mg {

struct ClipDoubtSettings {
  double off_floor_m = 0.25;       // the median of each frame's lowest joint height below -this, or
                                   // its 2 % quantile above this: off the floor
  double min_contactless_s = 1.0;  // a clip at least this long in which no foot joint is planted
  double min_figure_m = 0.4;       // the figure's size (its largest extent, the median over the
  double max_figure_m = 4.0;       // frames) outside these: no person's size, its unit wrong
  double max_slowdown = 1.5;       // flights falling this many times slower than the capture's
                                   // clock would (or faster, 1 / this), or walking strides taking
                                   // this many times a walk's time (or 1 / this): its clock wrong

  Status validate() const;
};

struct ClipDoubts {
  // "its figure is 48.00 m tall ...": no person's size (the file's unit, or --scale, is wrong).
  // The floor and the feet are not judged then: their limits are a person's.
  std::string size;
  // Phrases such as "its lowest joint is 0.57-0.90 m below the floor (y = 0)".
  std::vector<std::string> floor;
  // "its flights fall at 0.62 m/s^2, not 9.81: it plays 4.0x slower than it was captured ...",
  // or "its walking strides of 1.31 m take 4.60 s, where people's of that length take about
  // 1.03 s: ...".
  // Judged only where the size and the floor are right (its feet's contacts mean something): on
  // its flights where they are measured, else on its walk.
  std::string clock;
  // What the clock is judged on, doubt or not (not measured: size or floor doubts, too few
  // flights, too few strides of a walk).
  FlightFall flight_fall;
  WalkPace walk_pace;
  // How many times slower than captured the clip plays, as the clock was judged (the flights',
  // else the walk's slowdown); 0 when not judged.
  double slowdown = 0.0;

  bool empty() const { return size.empty() && floor.empty() && clock.empty(); }
  // The size's phrase, or the floor's, or the clock's.
  std::vector<std::string> phrases() const;
};

// Where a clip's clock comes from, for the clock's phrase to say what to change.
struct ClipClock {
  double read_fps = 0.0;         // the rate it was read at (its file's, or --input-fps); 0: unknown
  bool keys_in_seconds = false;  // glTF and FBX: keys timed in seconds (--input-fps only samples them)
};

// What looks wrong with a clip; empty when nothing does. world_positions_m: frames x joint_count,
// frame-major (world_positions()), at `fps`; contacts: one mask per frame (contact_mask()), empty
// when the feet are unknown (not judged then); feet: the joints the contacts are of (the walk is
// not judged without them).
ClipDoubts clip_doubts(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                       std::span<const ContactMask> contacts, const ClipDoubtSettings& settings = {},
                       const ClipClock& clock = {}, const FootJoints& feet = {});

// The same for a clip on its own: forward kinematics, and the contacts of the feet found by their
// usual names (skeleton/foot_joints.h; not judged when none are found).
ClipDoubts clip_doubts(const Skeleton& skeleton, const Motion& motion, const ClipDoubtSettings& settings = {});

// "phrase, and phrase; its root translation may be wrong", or the size's phrase, or the
// clock's: what `info` prints for a clip with doubts.
std::string clip_doubts_text(const ClipDoubts& doubts);

// "NAME: " + clip_doubts_text (+ " (...)", why a size or floor doubt matters): the one line
// loading logs for a clip with doubts.
std::string clip_doubt_line(const std::string& name, const ClipDoubts& doubts);

// A library's clips with doubts, the lines loading logs for them: one per clip, but for clips
// whose only doubt is their clock, read at one rate and playing slower (or faster) than captured:
// kGroupedClockDoubts of them or more say it in one line ("16_01, 16_05, 16_13 and 12 more: their
// flights or walking strides say they play about 4.0x slower than they were captured (3.5-4.6x);
// their frame rate as read, 30 fps, is likely about 4.0 times that (...)"; up to 4 clips named
// all, the range left out when its ends agree), as a folder a converter wrote with one wrong
// Frame Time has them. The factor is the median of the group's (of their speed-ups, for clips
// playing fast). The lines in the order of each group's first clip.
inline constexpr size_t kGroupedClockDoubts = 3;
struct DoubtedClip {
  std::string name;
  ClipDoubts doubts;
  ClipClock clock;
};
std::vector<std::string> clip_doubt_lines(std::span<const DoubtedClip> clips);

}  // namespace mg
