// Path synthesis (Kovar et al. 2002, section 5): a walk whose root follows a path on the
// floor. The cost of a frame is the squared floor distance between the root and the path's
// point at the same arc length (arc length the root has covered), plus a penalty for each
// frame not carrying the motion tag the path asks for there, plus a penalty for falling
// behind a slowest speed (see min_speed_mps), plus for a walk that reaches its horizon the way
// still to go to the tag asked for there (tag_lookahead; path_cost.h). The search is
// incremental: the best walk of about horizon_s seconds by branch and bound (horizon_search.h),
// keep its first commit_s seconds (whole edges), search again from there.
//
// The walk is complete when its motion reaches the path's end: when the point of the path
// nearest its root, followed along the path (FloorPath::followed_arcs), gets there. The root's
// arc length is not that: sway, shuffling on the spot and steps aside add to it and not to the
// way along the path (a library whose walking starts and stops, or boxing footwork, travels
// twice the path's length to cover half of it), and the edit follows the motion's smoothed
// path. So wherever the root has travelled the path's length, the walk so far is played (and
// edited) and, short of the end, the search goes on from the arc its motion reached, comparing
// its roots with the path where the edit puts them.
//
// The motion starts at the path's first point facing along it, from the start node whose
// first search costs least among about `start_candidates` nodes spread over the graph and over
// its sets of tags, at least one node of each (nodes carrying the tag asked for at the start
// when there is one).
//
// A walk that does not reach the path's end before giving up (the motion would average under
// 0.2 m/s: the search dawdled, as on a library of dance and karate whose few walking clips turn
// little), or reaches it with a segment (or the stretches no segment holds) taking longer than
// slowest_seconds gives (looping in place beside the path, its edit following it, where the type
// asked for would take it off the path within the horizon),
// or follows the path more than retry_deviation_m off on average, or misses the motion type a
// segment asks for (retry_tag_match), is searched again up
// to progress_retries times, each looking retry_horizon_s ahead: first as it was; then with its
// arc corrected at each commit (anchor_arc); then the behind penalty 4x higher; when the motion
// is edited, then with the edit in the search (edit_in_search) at the penalty given and at 4x;
// then at 16x, 64x, ... (each with and without the edit in the search); where a missed type is
// all that is wrong with the best so far, the retry has the tag penalty 4x the last raised one
// (retry_tag_match). The first to reach the end without dawdling within retry_deviation_m,
// missing no type, is kept, or else the one reaching it (without dawdling if any does; then
// within retry_deviation_m, and among those missing the fewest types) with the least deviation,
// or else the one that got furthest along. A segment asking for a type the graph plays in no
// frame asks the search for nothing.
//
// The walk's motion is then edited onto the path (path_edit.h: Gleicher's motion path editing,
// within a limit on the turning it adds) unless edit_path is false; the result gives the
// deviation of both, the walk as the graph played it and the motion edited.
//
// Asked to come to rest at the end (rest_at_end), the character stands still there: the walk is
// searched as above, cut where its way to rest stands nearest the end (path_rest.h), that way and
// the clip that ends standing still played on, and the whole motion edited onto the path.
#pragma once

#include <functional>
#include <stop_token>

#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/horizon_search.h"
#include "motiongraph/synthesis/path_edit.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

struct PathSynthesisSettings {
  double horizon_s = 3.0;
  double commit_s = 1.0;
  double tag_penalty_m2 = 1.0;         // per frame without the tag asked for
  // A walk that reaches the horizon in a segment asking for a tag also costs tag_lookahead times
  // what any walk from where it ends must still pay before that tag (tag_distance.h: the tag
  // penalty for each frame without it, the transition and bridge penalties on the way): a
  // segment's motion type that no walk within the horizon reaches is headed for (0: the horizon
  // only; at most 1).
  double tag_lookahead = 0.5;
  // Kovar's cost compares the root with the path at equal arc length, which a root that
  // stays put (standing, sitting, dancing on the spot) matches perfectly: with many such clips
  // the walk dawdles. Each frame also costs behind_penalty_m times the metres the root is
  // behind covering the path at min_speed_mps since the search began (0: Kovar's cost alone).
  double min_speed_mps = 0.5;
  double behind_penalty_m = 1.0;
  // Searches again, pushing on (see above), when the walk does not reach the end, dawdles in a
  // segment (slowest_seconds), or follows the path more than retry_deviation_m off on average
  // (0: not for the deviation) (no retries: 0; nor when behind_penalty_m is 0).
  int progress_retries = 4;
  double retry_deviation_m = 0.1;
  // A segment of at least kTagMissMinSeconds of motion, asking for a motion type the graph plays
  // (not a modifier tag such as stop or turn), whose frames carry it less than this share of
  // them missed it (the 8 subjects' circle of 5 m asked to walk then run walked on: a run leaves
  // the circle within the horizon, at a tag penalty each frame walking stays under): the walk is
  // searched again. Where a missed type is all that is wrong with the best so far (the end
  // reached without dawdling, within retry_deviation_m), the retry prices the tag 4x higher than
  // the last time (0, or tag_penalty_m2 0: not for a missed type).
  double retry_tag_match = 0.5;
  // The retries' horizon (0: horizon_s). At a sharp corner a library with little turning in its
  // walking may find nothing within horizon_s that beats shuffling on the spot; a longer look
  // finds the turn that pays off later. Only for the retries: on a large library's dense graph
  // every search costs about twice as much at 5 s (the 8-subject library's search fell from
  // about 180x real time to about 100x), and its first search rarely needs a retry.
  double retry_horizon_s = 5.0;
  // Each transition taken costs this (m^2: as many frames' squared deviation). Kovar's cost
  // alone takes a transition wherever it follows the path a little better, and output then
  // blends almost all the time (0: Kovar's cost alone). 0.8 takes a tenth fewer transitions
  // than 0.2 at the same deviation as delivered (the path edit bends the walk the rest of the
  // way) and the same share of the types asked for (docs/performance.md).
  double transition_penalty_m2 = 0.8;
  // Each bridge (GraphEdge::bridge: a blend between motion types far above the threshold) taken
  // costs this more (m^2) unless it leads into the motion type a segment asks for there (its
  // target node's frame carries the tag). Bridges are there to change motion type when asked;
  // unasked, a library whose walking follows the path would otherwise wander into running or
  // jumping and back through visible blends (three game cycles: feet slid 7x the source's), and
  // a walk asked to run would go by way of a jump. A bridge into the asked type costs as any
  // transition and the tag penalty decides (0: bridges cost as any transition everywhere).
  double bridge_penalty_m2 = 100.0;
  long long max_expansions = 20000;    // per search
  int beam_width = 64;                 // HorizonSettings::beam_width (0: none)
  int start_candidates = 16;
  int start_node = -1;                 // >= 0: start there instead
  // The two things that make the search fast; off, it is the plain depth-first branch and
  // bound (benchmarks compare the two).
  bool lower_bound = true;             // bound the frames still to come (PathCost)
  bool warm_start = true;              // try the rest of the previous search's walk first
  // Come to rest at the path's end (see above): the graph must have a clip that ends standing
  // still (SynthesisContext::rest()), else synthesize_path fails.
  bool rest_at_end = false;
  // Bend the walk's motion onto the path (path_edit.h). The build's path check judges the
  // graph, and turns it off.
  bool edit_path = true;
  PathEditSettings path_edit;
  // The search compares the walk with the path where the edit puts it: after each commit the
  // walk so far is edited (path_edit.h) and the next search's roots are moved as its last frame
  // was. The search then leaves the turning to the edit more: the first retry's way on (see
  // above), not the default (on subject 16 the graph's own turns then go unused).
  bool edit_in_search = false;
  // Each search starts from the way along the path the walk has come (its roots, as the search
  // views them, followed along the path), not from the distance its root travelled. A walk that
  // shuffles or steps aside is then not taken for further along than it is; but where the walk
  // runs wide of a tight turn the search, seeing itself level with the path, may stop pushing
  // on (subject 16's figure 8 run: 0.04 m off becomes 1.0 m): the first retry's way, not the
  // default.
  bool anchor_arc = false;
  // Asks the synthesis to stop (core/stop.h): before each search, synthesize_path fails with
  // stopped_error() once it does.
  std::stop_token stop;
  // Told after each search how far along the path the walk has come (metres) and which search
  // of the whole path it is (1, then each retry), for progress (Python's path(progress=)).
  std::function<void(double arc_m, int attempt)> searched;

  Status validate() const;
};

constexpr double kProgressRetryFactor = 4.0;  // the behind and tag penalties' step between attempts
// A segment shorter than this (in the motion's frames) is not judged by its type: changing
// type takes a blend and a step or two.
constexpr double kTagMissMinSeconds = 2.0;
// The motion has reached the path's end when it gets this close to it along the path (a step:
// the walk is made of whole edges, and the edit moves its end as the walk grows), and a frame
// that far along stands within kEndReachedDistanceM of the path's last point or, further, within
// kEndReachedShare of the path's length of it: a walk that only goes straight may end metres to
// the side of a curve it followed as well as it could (its deviation says how far), but on a
// path that turns back on itself more tightly than the motion can follow, the way along it a
// frame is given may lie tens of metres from where the frame stands.
constexpr double kEndReachedM = 0.5;
constexpr double kEndReachedDistanceM = 1.0;
constexpr double kEndReachedShare = 0.25;

struct PathSynthesisResult {
  Walk walk;
  FloorTransform start;
  Motion motion;                      // edited; trimmed at the frame that reaches the end when reached_end
  std::vector<Vec2> roots;            // the motion's root floor positions
  std::vector<TagMask> frame_tags;    // tags of each frame of motion
  double path_length_m = 0.0;
  double arc_covered_m = 0.0;         // how far along the path the motion got (followed_arcs)
  double end_distance_m = 0.0;        // from the motion's last root to the path's last point
  double mean_deviation_m = 0.0;      // root's distance to the nearest point of the path
  double max_deviation_m = 0.0;
  // The same of the walk as the graph plays it, before the edit (equal when there is none).
  double graph_mean_deviation_m = 0.0;
  double graph_max_deviation_m = 0.0;
  PathEditStats edit;                 // edit.edited false: not edited
  // The edit was made and taken back: it left the motion further from the path, on average, than
  // the graph played it (a path that turns back on itself within a step or two); edit is then
  // that of no edit.
  bool edit_undone = false;
  double tag_match = 1.0;             // fraction of frames inside a segment that carry its tag
  // Per segment of the path, in order: the frames of the motion whose arc along the path it asks
  // for (the last segment given that holds the arc; none for one the motion did not reach or
  // later segments cover), and how many of them carry its tag.
  struct SegmentTagMatch {
    int frames = 0;
    int matched = 0;
  };
  std::vector<SegmentTagMatch> segment_tag_matches;
  // A frame gets within kEndReachedM of the path's length along it and near its last point (see
  // kEndReachedShare); the motion ends at the first such frame furthest along.
  bool reached_end = false;
  // How the attempt kept falls short of what the retries look for (beside reached_end and
  // mean_deviation_m against retry_deviation_m): the first span it dawdled in (a segment's index;
  // segments().size(): the stretches no segment holds; -1: it did not), the seconds it took there
  // and the most it could take (slowest_seconds); and the segments whose motion type it missed
  // (their frames carry it less than retry_tag_match of the time).
  int dawdled_in = -1;
  double dawdled_s = 0.0;
  double dawdle_limit_s = 0.0;
  std::vector<int> missed_segments;
  int searches = 0;
  long long expansions = 0;
  int budget_exhausted = 0;           // searches that ran out of budget
  // Whole-path attempts made (searches, expansions and budget_exhausted count them all), and
  // the behind penalty and horizon of the one kept, whether its search saw the edit and corrected
  // its arc.
  int attempts = 1;
  double behind_penalty_m = 0.0;
  double tag_penalty_m2 = 0.0;        // the kept attempt's
  double horizon_s = 0.0;             // the kept attempt's horizon
  bool edit_in_search = false;
  bool anchor_arc = false;            // the kept attempt's PathSynthesisSettings::anchor_arc
  // With rest_at_end: the ending the motion comes to rest on (its clip played from its node's
  // frame to its last; null without) and the frame of the motion from which the character stands.
  const RestEnding* rest = nullptr;
  int rest_frame = -1;
};

// How many frames of the graph's clip pieces carry one of `mask`'s tags (0: a segment asking for
// it cannot be followed; the pruning may have left none of the clips' frames of a type).
int graph_frames_with(const SynthesisContext& context, TagMask mask);

// Fails on a segment asking for a tag the graph does not know, blaming the path: its file
// (`path_file`) or, without one, the segment as --segment gives it ("--segment swim:0-5: ...").
Status check_segment_tags(const SynthesisContext& context, const FloorPath& path, const std::string& path_file);

// The median speed (m/s) of the root over the frames of the graph's clip pieces that carry one
// of `mask`'s tags (each frame's floor step to the next frame of its clip: within its piece, or
// the first of the piece leaving the node the piece reaches); 0 when none does.
double typical_speed_mps(const SynthesisContext& context, TagMask mask);

// The longest a walk may spend in each of the path's segments (the frames FloorPath::segment_at
// gives it), and last in the stretches no segment holds, without dawdling: at min_speed_mps, or
// where a segment asks for a motion type whose typical speed is lower (a dance on the spot), at
// that speed; plus a second each, for a start or a change of type. Segments asking for a tag the
// graph does not know count at min_speed_mps; min_speed_mps must be > 0.
std::vector<double> slowest_seconds(const SynthesisContext& context, const FloorPath& path, double min_speed_mps);

Result<PathSynthesisResult> synthesize_path(const SynthesisContext& context, const FloorPath& path,
                                            const PathSynthesisSettings& settings = {});

}  // namespace mg
