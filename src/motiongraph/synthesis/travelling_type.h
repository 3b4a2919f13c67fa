// The motion type a steering session asked for none starts in (controller.h
// controller_start_node): a character steered with no type asked walks where the graph walks,
// rather than start among the type most nodes carry (CMU 49's dance, where it stood for 29 of
// its 30 s). A path asked for none starts where its first search costs least, as before: a start
// among the walks alone kept a path asked to hurry from running, and a short path ending at rest
// from starting at a clip that stops.
//
// Of the motion types (graph_from_candidates.h: not a modifier such as turn) whose clip pieces
// in the graph travel kTravellingMps or faster on average (each piece's root from its first frame
// to its last, as EdgeTracks play them, over the pieces' frames), the one of the most frames:
// walking beside running and jumping, running where the graph holds more of it.
#pragma once

#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

// Slow walks (CMU's "slow walk": 0.8 m/s) travel; forward jumps (subject 16: 0.48 m/s, a jump
// and a landing) and dance on the spot do not.
inline constexpr double kTravellingMps = 0.7;

// 0 when no type travels so fast (or the graph carries none).
TagMask travelling_type(const SynthesisContext& context);

}  // namespace mg
