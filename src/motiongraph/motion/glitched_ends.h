// Frames cut off from the rest of a clip by a capture glitch at its start or end. Some CMU takes
// open with a frame or two whose arm is elsewhere (16_15: the left hand 0.92 m from where the
// next frame has it, 111 m/s; 16_23, 16_28 likewise), so that a walk that plays the clip from
// its start, or a transition landing there, pops; and the capture's own measure (the largest
// step of any joint in a frame, evaluation/foot_slide.h) is that jump, not the motion's.
//
// The test is capture_glitches.h's. The frames before the last glitch among the first quarter
// second (at most) are dropped, and those after the first glitch among the last quarter second,
// as long as two frames are left. Glitches within a clip are capture_glitches.h's to cut.
#pragma once

#include <string>

#include "motiongraph/motion/capture_glitches.h"
#include "motiongraph/motion/motion.h"

namespace mg {

inline constexpr double kGlitchEndSeconds = 0.25;

struct GlitchedEnds {
  int leading = 0;   // frames before a glitch at the start
  int trailing = 0;  // frames after one at the end
  double leading_jump_m = 0.0;   // the glitch's largest joint step
  double trailing_jump_m = 0.0;
  std::string leading_joint;     // the joint that steps it
  std::string trailing_joint;
};

// The glitches at `motion`'s ends on `skeleton` (metres; see above).
GlitchedEnds find_glitched_ends(const Skeleton& skeleton, const Motion& motion);

// The clip without the frames find_glitched_ends() finds, found again on what is left until none
// is (so that a clip read, written and read again loses nothing more); its glitched_* fields say
// how many (added to any it had). Returns what was found: the frames of every cut, the largest
// jump at each end. (A capture glitching every quarter second throughout is cut down to its
// last three frames: there is nothing of it to keep.)
GlitchedEnds drop_glitched_ends(Clip& clip);

}  // namespace mg
