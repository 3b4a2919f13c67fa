// The direction a walk goes. Where the root travels at walking speed roughly along the body's
// facing (facing.h), the direction it travels is what a person asking to walk one way means:
// each walking clip travels a few degrees off its facing, its own way (subject 16's walk 3.9
// degrees left of its hips), and held by its facing a library's walk goes that far off the
// heading, each clip differently. A sidestep, a backward walk or a motion on the spot travels
// across its facing or not at all: there the facing stands.
//
// Over a window of frames (about a stride, so that the hips' swing from step to step averages
// out): the mean facing f, the root's floor travel t over it. The travel's share of the
// direction judged rises from 0 at HeadingEditSettings::travel_from_mps to 1 at
// travel_full_mps, and is none unless t lies within 45 degrees of f (all of it within 20); the
// direction judged is (1 - share) f + share t, both unit. A window cut short (a clip's or a
// plan's end) spans less than a stride: the share falls from a whole window to none at three
// quarters of one.
//
// The heading edit (heading_edit.h) judges this over the frames it plays and plans; the
// steering search (controller.h) judges every frame it plays by its facing turned by the turn
// travel_turns() gives its source frame over its own clip (EdgeTracks::headings), so that the
// walks it picks and the edit that holds them aim at the same direction.
#pragma once

#include <vector>

#include "motiongraph/synthesis/assembler.h"
#include "motiongraph/synthesis/facing.h"
#include "motiongraph/synthesis/heading_edit.h"

namespace mg {

// The travel's share of the direction judged over a window: `facing` its mean facing (any
// length), `travel` the root's floor travel over it, `seconds` the time it spans, `spanned` the
// share of a whole window it spans (1 for a whole one). 0 unless settings.hold_travel.
double travel_share(const HeadingEditSettings& settings, const Vec2& facing, const Vec2& travel, double seconds,
                    double spanned);

// For every database frame, the turn (radians, FloorTransform's yaw sense) from its facing to the
// direction judged over settings.window_s centred on it within its own clip (the root and facing
// as the assembler plays it on its target skeleton, whose forward axis is `forward_axis`) turns
// the window's mean facing onto it: 0 where the facing stands (and everywhere unless
// settings.hold_travel). The search judges frame i's own facing turned by turns[i] (the
// sway from step to step stays in it, as in the facing).
std::vector<float> travel_turns(const MotionDatabase& db, const MotionAssembler& assembler, const Vec3& forward_axis,
                                const HeadingEditSettings& settings);

}  // namespace mg
