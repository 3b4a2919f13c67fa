// Clips that loop: a game's walk or run cycle ends where it starts, so played again it goes on
// seamlessly. A motion graph blends over a window of frames inside a clip, so a cycle of one
// period could never be played round: the window that would lead from its end back to its
// start runs past the end. A clip found to loop is therefore played on after its end, its first
// frames again, the root carried on over the floor as one cycle carries it, so that the graph
// finds the transition from the end back to the start (at distance zero) like any other.
#pragma once

#include "motiongraph/motion/motion.h"

namespace mg {

struct LoopChoice {
  bool loops = false;
  bool last_repeats_first = false;  // the last frame is the first again (period frames - 1);
                                    // else the first follows the last (period frames)
  int period = 0;                   // frames of one cycle
  // How far the seam is from a loop's: with the last frame repeating the first, their
  // difference over the clip's median frame step; else the first frame's departure from the
  // cubic through the two frames either side of the seam (the last two and the next two), over
  // the clip's median departure of a frame from its neighbours' cubic.
  double seam_ratio = 0.0;
  double step_m = 0.0;  // the median step from a frame to the next (RMS over joints, in the root's floor frame)
  // For a loop, the floor transform one cycle makes (p -> turn by cycle_yaw_rad about the
  // vertical, then shift): the placement of the next cycle's start, the last frame when it
  // repeats the first, else one step on from the last as the step before it went.
  double cycle_yaw_rad = 0.0;
  Vec3 cycle_shift_m = Vec3::Zero();
};

// A clip loops when its last frame repeats the first (within a quarter of its median step), or
// when its first frame follows its last as smoothly as its frames follow each other (departure
// at most 3 times the median, the seam a step of at most twice the median). The seam is
// judged against a frame's step, the departures between poses about 1/30 s apart, whatever
// the clip's rate. CMU's 170 captures of the 8-subject library measure 4.7 departures at the
// least (at 120 fps), one cycle of a walk cut from a capture 2.4-8 at 30 fps, cycles made
// loops 1.0-2.6.
inline constexpr double kRepeatedSeamRatio = 0.25;
inline constexpr double kFollowingSeamRatio = 3.0;
inline constexpr double kFollowingStepRatio = 2.0;

// Whether the clip loops, its poses compared in the root's floor frame (the joints' positions
// about the root's floor point, turned by its heading: the yaw of the root's x or z axis,
// whichever lies more level at the first frame), so a cycle that travels or turns loops too.
// Clips of fewer than 8 steps of about 1/30 s, or that hardly move (median step of 1/30 s
// under 2 mm), do not.
LoopChoice find_loop(const Skeleton& skeleton, const Motion& motion);

// The loop (find_loop's choice for this motion) with `extra_frames` more frames (at most one
// period): its frames from the start of the cycle again, placed by the cycle's floor transform,
// so the motion goes on across the seam as played round. Only the root's rotation and
// translation change in the frames added; the clip's own frames are unchanged.
Motion unrolled_loop(const Skeleton& skeleton, const Motion& motion, const LoopChoice& loop, int extra_frames);

}  // namespace mg
