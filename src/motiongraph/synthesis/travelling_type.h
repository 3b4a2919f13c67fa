// The motion type a steering session asked for none starts in (controller.h
// controller_start_node): a character steered with no type asked walks where the graph walks,
// rather than start among the type most nodes carry (CMU 49's dance, where it stood for 29 of
// its 30 s). A path asked for none starts where its first search costs least, as before: a start
// among the walks alone kept a path asked to hurry from running, and a short path ending at rest
// from starting at a clip that stops.
//
// Of the motion types (graph_from_candidates.h: not a modifier such as turn) whose clip pieces
// in the graph travel kTravellingMps or faster on average (each piece's root from its first frame
// to its last, as EdgeTracks play them, over the pieces' frames), the one of the most frames,
// each weighed by (speed / kWalkingMps)^2 up to 1: walking beside running (the 8-subject
// library's walk averages 0.62 m/s over 2379 frames, its run 2.19 over 172; with the frames
// alone at 0.7 m/s and up it ran), beside forward jumps (0.30-0.59 m/s) and dance on the spot.
#pragma once

#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

// Under this on average a type does not travel (CMU 14's jumps 0.11 m/s, its walks, reaching and
// tiptoeing, 0.13; CMU 29's playground walks 0.37 do).
inline constexpr double kTravellingMps = 0.3;
// A walking pace: frames of a type slower than this weigh less, by the square of the ratio.
inline constexpr double kWalkingMps = 1.0;

// 0 when no type travels so fast (or the graph carries none).
TagMask travelling_type(const SynthesisContext& context);

}  // namespace mg
