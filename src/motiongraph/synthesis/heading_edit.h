// Steering's heading edit: the motion path editing of path_edit.h, made online for the
// interactive controller (controller.h). The graph holds a finite set of walks, and one held to
// a heading drifts and weaves about it (subject 16 walking east swung up to 33 degrees about a line
// it left at 10 degrees); a search over a second of motion sees too little of that to pay a
// transition for it. The edit turns the frames each decision commits, as they are played, by an
// added angle that keeps the character's facing on the direction asked for:
//
//  1. The direction judged at frame i: the mean of the facings (facing.h) of the frames within
//     window_s centred on it, those already played and those the decision's walk plans next,
//     all as they would play under the present placement with no turning added since. Over a
//     window as long as a stride the hips' swing from step to step averages out; the plan
//     makes it centred, so the edit does not lag the motion it corrects. With
//     HeadingEditSettings::hold_travel, where the root walks over the window roughly along that
//     facing, the direction it travels there instead: each walking clip travels a few degrees
//     off its facing, its own way, and holding the facing leaves a library's walks that far off
//     the heading, each piece differently.
//  2. The turn w_i that would put it on the direction asked for. The angle added since the last
//     decision, a, follows it: each frame moves a toward w_i by the share ds / turn_distance_m
//     of what is left, ds the root's floor step (so an error is taken out over about
//     turn_distance_m travelled), and by at most max_turn_deg_per_m per metre: the turn goes
//     with the root's travel, so a motion that does not travel (standing, a turn on the spot)
//     is not turned, and one that barely travels barely.
//  3. Frame i is moved rigidly on the floor: turned by a_i, its root's floor step from the
//     frame before turned by it too (the edited root is the last edited root plus the step
//     turned by a_i), so it travels as far, turning a_i - a_{i-1} more than the capture.
//     Heights and every joint's local values but the root's stay.
// The rigid motion of the last frame moves on the placement of what follows (the controller
// composes it onto its state), so the next decision starts where the edit left the character
// and a starts again from 0. The foot clean-up (foot_cleanup.h) holds the planted feet, as after
// the path edit. Asked for a new heading, the edit shares the turn with the walk the search
// finds (on subject 16 it adds about 60 of a 90-degree turn's degrees): it turns no faster than
// max_turn_deg_per_m, and the graph's turning steps carry the rest.
#pragma once

#include <deque>
#include <span>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/synthesis/facing.h"
#include "motiongraph/synthesis/floor_transform.h"

namespace mg {

struct HeadingEditSettings {
  // Turning the edit may add per metre travelled (0: no edit). 60: faster to each heading asked
  // than 45 on eight libraries, as sharp at the 99th percentile (docs/performance.md).
  double max_turn_deg_per_m = 60.0;
  double turn_distance_m = 0.5;      // the error is taken out over about this far travelled
  double window_s = 1.0;             // the facing judged: mean over this long, centred
  // true: where the root travels over the window at walking speed, it is the travel's direction
  // that is held (a walk travels a few degrees off its facing, each clip its own); its share of
  // the direction judged rises from 0 at travel_from_mps to 1 at travel_full_mps, and only while
  // the travel is within 45 degrees of the facing (all of it within 20): a sidestep, a backward
  // walk or a motion on the spot keeps its facing held (travel_heading.h). Held walks go
  // straighter (the 8-subject library weaved 12.7 cm about its line, 2.6 cm so), and the
  // controller's search then judges the same direction (EdgeTracks::headings, whose turns
  // use the default speeds and window); but a held walk's pieces then all aim alike, the
  // search has less reason to play one on, and three of six libraries' held walks took half
  // as many transitions again or more: off by default (docs/performance.md).
  bool hold_travel = false;
  double travel_from_mps = 0.3;
  double travel_full_mps = 0.6;

  Status validate() const;
};

// What an edit has done so far.
struct HeadingEditStats {
  long long frames = 0;          // frames edited
  double added_turn_rad = 0.0;   // the sum of |a_i - a_{i-1}|: all the turning added
  double max_rate_deg_per_m = 0.0;
  double travel_share = 0.0;     // summed over the frames edited: the travel's share of the direction judged
};

class HeadingEdit {
 public:
  HeadingEdit(const HeadingEditSettings& settings, double fps, const Vec3& forward_axis);

  // Edits frames [first, motion.frame_count) of `motion` in place (their root: translated joint
  // 0, rotation joint 0) toward `direction` (unit, on the floor). `previous_root` is the floor
  // position of the frame played before frame `first` (nullptr before the first frame): the
  // frames' steps are taken from it. `planned_facings` and `planned_roots` are the world facings
  // and floor root positions of the frames the decision's walk plays from frame `first` on,
  // unedited (walk_facings, walk_roots; the travel is judged only as far as roots are given, and
  // none are needed without hold_travel). Returns the rigid floor motion the last frame got
  // (identity when there was no frame or nothing to turn).
  FloorTransform apply(Motion& motion, int first, const Vec2* previous_root, std::span<const Vec2> planned_facings,
                       std::span<const Vec2> planned_roots, const Vec2& direction);

  int half_window_frames() const { return half_window_; }
  const HeadingEditStats& stats() const { return stats_; }

 private:
  struct PlayedFrame {
    Vec2 facing;   // as played
    Vec2 step;     // the root's floor step into it, as played
    double added;  // the turning added up to it
  };
  HeadingEditSettings settings_;
  Vec3 forward_axis_;
  double fps_ = 30.0;
  int half_window_ = 0;
  // The last half_window_ frames as played.
  std::deque<PlayedFrame> played_;
  double total_added_ = 0.0;  // the turning added since the first frame, signed
  HeadingEditStats stats_;
};

}  // namespace mg
