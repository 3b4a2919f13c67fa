// Path synthesis (Kovar et al. 2002, section 5): a walk whose root follows a path on the
// floor. The cost of a frame is the squared floor distance between the root and the path's
// point at the same arc length (arc length the root has covered), plus a penalty for each
// frame not carrying the motion tag the path asks for there, plus a penalty for falling
// behind a slowest speed (see min_speed_mps); the walk is complete when its
// root has covered the path's length. The search is incremental: the best walk of about
// horizon_s seconds by branch and bound (horizon_search.h), keep its first commit_s seconds
// (whole edges), search again from there.
//
// The motion starts at the path's first point facing along it, from the start node whose
// first search costs least among about `start_candidates` nodes spread over the graph and over
// its sets of tags, at least one node of each (nodes carrying the tag asked for at the start
// when there is one).
//
// A walk that does not reach the path's end before giving up (the motion would average under
// 0.2 m/s: the search dawdled, as on a library of dance and karate whose few walking clips turn
// little) is searched again up to progress_retries times, pushing on harder each time: the
// behind penalty 4x higher; when the motion is edited, then with the edit in the search
// (edit_in_search) at the penalty given and at 4x; then at 16x, 64x, ... (each with and
// without the edit in the search). The first to reach the end is kept, or else the one that
// covered the most.
//
// The walk's motion is then edited onto the path (path_edit.h: Gleicher's motion path editing,
// within a limit on the turning it adds) unless edit_path is false; the result gives the
// deviation of both, the walk as the graph played it and the motion edited.
#pragma once

#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/horizon_search.h"
#include "motiongraph/synthesis/path_edit.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

struct PathSynthesisSettings {
  double horizon_s = 3.0;
  double commit_s = 1.0;
  double tag_penalty_m2 = 1.0;         // per frame without the tag asked for
  // Kovar's cost compares the root with the path at equal arc length, which a root that
  // stays put (standing, sitting, dancing on the spot) matches perfectly: with many such clips
  // the walk dawdles. Each frame also costs behind_penalty_m times the metres the root is
  // behind covering the path at min_speed_mps since the search began (0: Kovar's cost alone).
  double min_speed_mps = 0.5;
  double behind_penalty_m = 1.0;
  // Searches again, pushing on (see above), when the walk does not reach the end (0: never;
  // nor when behind_penalty_m is 0).
  int progress_retries = 3;
  // Each transition taken costs this (m^2: as many frames' squared deviation). Kovar's cost
  // alone takes a transition wherever it follows the path a little better, and output then
  // blends almost all the time (0: Kovar's cost alone).
  double transition_penalty_m2 = 0.2;
  long long max_expansions = 20000;    // per search
  int beam_width = 64;                 // HorizonSettings::beam_width (0: none)
  int start_candidates = 16;
  int start_node = -1;                 // >= 0: start there instead
  // The two things that make the search fast; off, it is the plain depth-first branch and
  // bound (benchmarks compare the two).
  bool lower_bound = true;             // bound the frames still to come (PathCost)
  bool warm_start = true;              // try the rest of the previous search's walk first
  // Bend the walk's motion onto the path (path_edit.h). The build's path check judges the
  // graph, and turns it off.
  bool edit_path = true;
  PathEditSettings path_edit;
  // The search compares the walk with the path where the edit puts it: after each commit the
  // walk so far is edited (path_edit.h) and the next search's roots are moved as its last frame
  // was. The search then leaves the turning to the edit more: the first retry's way on (see
  // above), not the default (on subject 16 the graph's own turns then go unused).
  bool edit_in_search = false;

  Status validate() const;
};

constexpr double kProgressRetryFactor = 4.0;  // the behind penalty's step between attempts

struct PathSynthesisResult {
  Walk walk;
  FloorTransform start;
  Motion motion;                      // trimmed at the frame that completes the path; edited
  std::vector<Vec2> roots;            // the motion's root floor positions
  std::vector<TagMask> frame_tags;    // tags of each frame of motion
  double path_length_m = 0.0;
  double arc_covered_m = 0.0;
  double mean_deviation_m = 0.0;      // root's distance to the nearest point of the path
  double max_deviation_m = 0.0;
  // The same of the walk as the graph plays it, before the edit (equal when there is none).
  double graph_mean_deviation_m = 0.0;
  double graph_max_deviation_m = 0.0;
  PathEditStats edit;                 // edit.edited false: not edited
  double tag_match = 1.0;             // fraction of frames inside a segment that carry its tag
  bool reached_end = false;
  int searches = 0;
  long long expansions = 0;
  int budget_exhausted = 0;           // searches that ran out of budget
  // Whole-path attempts made (searches, expansions and budget_exhausted count them all), and
  // the behind penalty of the one kept and whether its search saw the edit.
  int attempts = 1;
  double behind_penalty_m = 0.0;
  bool edit_in_search = false;
};

Result<PathSynthesisResult> synthesize_path(const SynthesisContext& context, const FloorPath& path,
                                            const PathSynthesisSettings& settings = {});

}  // namespace mg
