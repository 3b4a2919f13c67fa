// Motion path editing (Gleicher, "Motion Path Editing", I3D 2001): the refinement Kovar et al.
// 2002 leave to it. Path synthesis gives motion whose root follows the path only as closely as
// the graph's pieces allow (a library with few turns follows a curve metres off); the edit bends
// that motion onto the path, keeping the way it moves about its own path.
//
//  1. The motion's own path Q: the root's floor positions averaged over smooth_s (a centred
//     window, shrunk evenly at the ends so that the first and last frames keep their
//     positions), parametrised by its arc length s; frame i lies at s_i. Sway, steps and turns
//     on the spot stay in the root's offset from Q.
//  2. The edited path Q': Q turned, as it goes, by an added angle a(s) that changes by at most
//     max_turn_deg_per_m per metre travelled; Q'(0) = Q(0) and each step of Q, on a grid of
//     kStepM of arc, is turned by the angle there, so Q' keeps Q's speed and its every own turn.
//     The angle steers Q' onto the path asked for, P, as a vehicle keeps to a lane: toward
//     the direction lookahead_m t - e n, where t is P's tangent at the point of P nearest Q'
//     (the point is followed along P from the last, so a path that crosses itself is not
//     jumped across; t is reversed while the motion goes back along P: it heads against t and
//     that point has moved back, as in a step back; past a sharp corner a motion that has not
//     turned yet heads against the next leg too, but its point stays at the corner, and it is
//     steered on along P), n its normal and e
//     Q''s signed offset from P along n. Q' turns with P's own turns and comes onto P over
//     about lookahead_m. P here is the path asked for with its corners rounded
//     (round_corners, over round_corners_m): the edit turns at most max_turn_deg_per_m, so
//     where the path turns faster (a corner) it must cut it, and steering for the sharp path
//     it began turning only at the corner and overshot it; the rounded path cuts it evenly,
//     starting before it.
//  3. Frame i is moved rigidly on the floor: turned by a(s_i) and carried from Q(s_i) to
//     Q'(s_i). Only the root's floor position and its rotation about the vertical change;
//     heights, every other joint's local values and the frames' timing stay.
// Where the motion goes elsewhere than the path (a pirouette, a library without turns) the
// added turning stays at its limit and the result follows the path less closely there: the
// stats say over how much of the arc. Tangents are chords over +-tangent_m of arc. The foot
// clean-up (foot_cleanup.h) then puts the feet back on their plants: the edit turns and moves
// the whole body, planted feet too.
#pragma once

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"
#include <span>
#include <vector>

#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/floor_transform.h"

namespace mg {

struct PathEditSettings {
  static constexpr double kStepM = 0.1;  // the arc-length grid the added angle is steered on
  double smooth_s = 1.0;                 // the motion's own path: the root averaged over this long
  double tangent_m = 0.5;                // tangents: chords over +- this much arc
  double max_turn_deg_per_m = 45.0;      // turning the edit may add, per metre travelled
  double lookahead_m = 2.0;              // the edited path comes back onto P over about this much arc
  // The edit steers for the path asked for rounded over +- this much arc (round_corners; 0: as
  // asked). Measured on corner paths (docs/performance.md): 1.5 m.
  double round_corners_m = 1.5;

  Status validate() const;
};

// What an edit did.
struct PathEditStats {
  bool edited = false;              // false: the motion was left as it was (its root does not travel)
  double limited_share = 0.0;       // of the arc, where the added turning was at its limit
  double max_added_turn_deg = 0.0;  // |a|: the most a frame was turned
  double max_shift_m = 0.0;         // |Q' - Q|: the most the motion's path was moved
};

// The path with its corners rounded: its points every 5 cm averaged over +- half_window_m of arc
// (the window shrunk evenly at the ends, so that they stay), and averaged so again, twice the
// first average less the second ("twicing"): a corner is cut, while a bend wider than the window
// stays within millimetres (a single average would move a circle of radius 5 m 7 cm inward at
// 1.5 m), and within 3 cm near the ends, where the window shrinks. A straight line is left as it
// is; half_window_m 0 gives the path itself.
FloorPath round_corners(const FloorPath& path, double half_window_m);

// Edits `motion` in place (its root: translated joint 0, its rotation joint 0) onto `path`, whose
// first point the motion starts from. A motion of fewer than 2 frames, or whose root does not
// travel, is left as it is.
Result<PathEditStats> edit_onto_path(Motion& motion, const FloorPath& path, const PathEditSettings& settings = {});

// The same edit planned on root floor positions alone (at fps frames a second): moves[f] is the
// rigid floor motion frame f gets (identity everywhere when the roots do not travel). `rounded`
// is the path to steer for, already rounded: round_corners(P, settings.round_corners_m), as
// edit_onto_path makes it (a caller planning again and again, as path synthesis does after each
// commit, rounds it once).
Result<PathEditStats> plan_path_edit(std::span<const Vec2> roots, double fps, const FloorPath& rounded,
                                     const PathEditSettings& settings, std::vector<FloorTransform>& moves);

}  // namespace mg
