// Coming to rest at a path's end (PathSynthesisSettings::rest_at_end, path_synthesis.h): where a
// walk that follows the path stops and how it comes to rest. A walk can stand still only at the
// end of a clip that ends so (rest_endings.h), and the way there runs on for a metre or two past
// where it leaves the walk, so the walk is cut where its way to rest stands nearest the path's end:
// from each of its nodes within kRestSearchM of the end (along the path, where its motion as
// edited stands), every way on through the graph that stands within kRestSearchS seconds (not
// through a bridge or a leap; not more than kRestOvershootM past the end; kRestExpansions edges tried from
// each node) to a node of such a clip, and that clip on, is measured as the path edit will lay it:
// its root's track in chords of kRestChordS (a stride's sway left out) added to where the node
// stands. The one standing nearest the end is kept, a transition on the way counting
// kRestTransitionM more and a rest from a landing (rest_endings.h) kRestLandingM more; where none is
// near, the cheapest way to rest from where the walk ends.
//
// A path shorter than the way to rest from where its walk starts (a walk that starts running
// stands metres past a 1 m path's end) is started instead at a node of a clip that stops: path
// synthesis tries the kRestStarts endings whose travel to standing (rest_ending_travel) lies
// nearest the path's length when the walk's way stands further than kEndReachedM from the end.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

constexpr double kRestSearchM = 4.0;
constexpr double kRestSearchS = 3.0;
constexpr double kRestOvershootM = 1.0;
constexpr long long kRestExpansions = 2000;
constexpr double kRestTransitionM = 0.05;
constexpr double kRestChordS = 0.5;
constexpr double kRestLandingM = 0.5;
constexpr int kRestStarts = 3;

struct PathRestWay {
  size_t kept_edges = 0;               // of the walk's edges, those kept
  std::vector<int> edges;              // then these
  const RestEnding* ending = nullptr;  // then this clip on to its end; null: no way to rest
};

// Each ending's travel (rest_endings.h, by index) from its node's frame to the frame it stands at,
// its root's track in chords of kRestChordS: how far it goes wherever it is placed.
std::vector<double> rest_ending_travel(const SynthesisContext& context);

// The way to rest for `walk` (played from `start`) along `path`; `edited_roots`, the floor roots of
// its first frames as the path edit put them (PathSynthesisResult::roots); `ending_travel`,
// rest_ending_travel's (found once for the searches of one path).
PathRestWay nearest_rest_way(const SynthesisContext& context, const FloorPath& path, const Walk& walk,
                             const FloorTransform& start, std::span<const Vec2> edited_roots,
                             std::span<const double> ending_travel);

}  // namespace mg
