// Which frames of a graph's edges travel, and how far travelling frames lie from each node: what
// a steering decision asked for no motion type still pays past its horizon (steer_cost.h). Within
// the horizon it pays for each metre its root falls behind the pace asked; a decision that saw
// only that stood in loops that go nowhere (CMU 14's jumping jacks, jogging on the spot and
// squats, for all 60 s asked to walk four ways) where every way out into a walk takes longer than
// the horizon. So a walk that reaches the horizon also pays, per frame, for the frames any walk
// from there plays before one that travels (tag_distance.h's cost-to-go, the pace as the tag).
#pragma once

#include <vector>

#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

inline constexpr TagMask kTravellingMark = 1;

// Per frame of `context.tracks` (as tracks.roots holds them): kTravellingMark where the root of its
// database frame (a blended frame's weightier side's, as EdgeTracks gives the tags) covers
// `travel_mps` or more over the second around it in its clip (half a second either side, as far as
// the clip goes), and half of that pace over each half (a crouch before a leap is no travel).
std::vector<TagMask> travelling_frames(const SynthesisContext& context, double travel_mps);

struct TravelCosts {
  TagCostCache::Marks marks;      // travelling_frames'
  TagCostCache::Costs to_travel;  // per node, cost_to_mark's (-1: none reached)
};

// The costs to the frames travelling at `travel_mps` of `context`'s graph, priced `per_frame` for
// each frame that does not and the transition and bridge penalties as a search with no motion type
// asked prices them; made once per pace and prices in the context's cache (none without one).
TravelCosts searched_costs_to_travel(const SynthesisContext& context, double travel_mps, double per_frame,
                                     double transition_penalty, double bridge_penalty);

}  // namespace mg
