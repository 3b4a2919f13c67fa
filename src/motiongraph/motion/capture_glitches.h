// Capture glitches: a joint that jumps between two frames while the motion either side is calm.
// Marker-based captures do it where the solver loses a limb for a frame, or settles a limb's
// twist the other way: CMU 05's dances turn the right thigh about itself by 180 degrees in one
// frame and back a few frames later, swinging the ankle 0.3 m at 35-45 m/s (05_05 ten times in
// 0.56 s); 14_10 moves the right hand 0.27 m in a frame and back 17 frames later; 03_02 both
// arms 0.9 m. A graph that plays such a frame pops, and a transition into the frames between
// two of them plays a limb the capture lost.
//
// The test, on world positions: a step of some joint between two frames is a glitch when it is
// at least `kGlitchJumpM` (0.2 m) and `kGlitchSpeedMps` (20 m/s: faster than a fist or a kicking
// foot, about as fast as a pitcher's hand at release; at 120 fps the 0.2 m says more), and when
// every joint's largest step in the frames on either side of it (the step before, the one after;
// none at the clip's ends) is under a third of it (`kGlitchCalmShare`): motion speeds up and
// slows down over frames, a glitch in one. A limb lost for one frame only steps out and back:
// two steps of 0.2 m or more in a row, the frames either side calm, and no joint further from
// where it was two frames before than two calm steps take it, are both glitches, at any rate (no
// limb swings so far and back within a frame: none in the 8 subjects read at 30 or 120 fps,
// three of CMU 05's thigh turns at 60). Fast but smooth motion (CMU 135's karate kicks,
// 49's acrobatics) has none; CMU 05's thigh turns step 3.4-10 times as far as the frames either
// side (a fifth, the share first used, missed 12 of them; 25 m/s, the speed first used, three of
// 0.20-0.21 m at 120 fps). A file captured at 30 fps shows a jump that stays four times slower:
// only those of 0.67 m or more are judged there (an animator's snap may be 0.3 m in a frame).
//
// A clip read into a library is cut at its glitches into the parts between them; parts shorter
// than `kGlitchFreeSeconds` are dropped (the frames between glitches a few frames apart are the
// limb the capture lost), and when none is that long the longer of the first and the last part
// is kept (the clip's own ends, not a limb lost between two glitches; in a manifest's range, an
// end with a glitch beyond it is not one), else the longest. The glitches are found on
// the file as read, all its joints; the first and last quarter second are glitched_ends.h's,
// which works on the file before a manifest's frame range is cut out of it.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "motiongraph/motion/motion.h"

namespace mg {

inline constexpr double kGlitchJumpM = 0.2;
inline constexpr double kGlitchSpeedMps = 20.0;
inline constexpr double kGlitchCalmShare = 1.0 / 3.0;
inline constexpr double kGlitchFreeSeconds = 0.25;

// The largest step of any joint from one frame to the next, and from one frame to the one after
// next (a limb out and back within a frame).
struct JointStep {
  double largest_m = 0.0;
  int joint = -1;           // the joint that steps it
  double over_two_m = 0.0;  // the largest step of any joint from this frame to the one after next
};

// Fills steps[f] for f in [first, last) with the step from frame f to f + 1 (metres, world
// positions), and over_two_m for f in [first, last - 1); `steps` must hold
// motion.frame_count - 1 values. Forward kinematics on frames first..last only.
void measure_joint_steps(const Skeleton& skeleton, const Motion& motion, int first, int last,
                         std::span<JointStep> steps);

// Whether the step from frame f to f + 1 is a glitch (the test above); the steps two either side
// of it, and over_two_m of f - 1 and f, must have been measured.
bool is_glitch_step(std::span<const JointStep> steps, int f, double fps);

struct CaptureGlitch {
  int frame = 0;        // the step from this frame to the next
  double jump_m = 0.0;  // the largest joint step there
  std::string joint;    // the joint that steps it
};

// A glitch where its file has it: the file's frame (1-based) after which a joint jumps, and the
// time it lands, in seconds from the file's start.
struct FileGlitch {
  int frame = 0;
  double seconds = 0.0;
  std::string joint;
  double jump_m = 0.0;
};

// `glitches` of a motion at `fps` whose first frame is the file's frame `first_file_frame`
// (1-based: after the frames the reader dropped, and where a manifest's range starts).
std::vector<FileGlitch> in_file_frames(std::span<const CaptureGlitch> glitches, int first_file_frame, double fps);

// `glitches` of a clip as its reader gave it (of its motion, at its rate), placed in its file:
// its first frame is the file's first after the rest and glitched frames the reader dropped.
std::vector<FileGlitch> in_file_frames(const Clip& clip, std::span<const CaptureGlitch> glitches);

// Every glitch in `motion`, in frame order (none in motions shorter than 4 frames or of no rate).
std::vector<CaptureGlitch> find_capture_glitches(const Skeleton& skeleton, const Motion& motion);

struct GlitchFreeParts {
  std::vector<CaptureGlitch> glitches;     // within the frames judged, numbered from their first
  std::vector<std::pair<int, int>> parts;  // kept: (first frame, frame count), numbered likewise

  // Frames in no part kept.
  int dropped_frames(int frame_count) const;
};

// The parts kept of frames [first, first + count) of a motion at `fps` whose glitches are
// `glitches` (find_capture_glitches): those steps that lie within the frames cut them. No
// glitch there: one part, all of them.
GlitchFreeParts glitch_free_parts(std::span<const CaptureGlitch> glitches, int first, int count, double fps);

// The same for a whole motion.
GlitchFreeParts glitch_free_parts(const Skeleton& skeleton, const Motion& motion);

}  // namespace mg
