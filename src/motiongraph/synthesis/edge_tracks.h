// What searches need of every edge, computed once: the root's floor position, facing and heading
// (the direction a walk goes, travel_heading.h) for each frame the edge plays (and the heading
// of its first along the travel axis, for placing a path's start), as the assembler plays it
// under the identity placement; the placement change the edge makes (identity for clip pieces,
// the transition's transform for transitions); the tags of each frame (a blended frame has the
// tags of the side with the larger weight); and the root's largest step from one frame to the
// next. Under a placement W a frame's world floor position is W applied to it.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/synthesis/assembler.h"
#include "motiongraph/synthesis/facing.h"

namespace mg {

struct EdgeTrack {
  int first = 0;  // into EdgeTracks::roots / facings / headings / tags
  int count = 0;  // the edge's frame_count
  FloorTransform change;
  Vec2 first_heading = Vec2::Zero();  // the travel axis turned by its first frame's root, on the floor
};

struct EdgeTracks {
  std::vector<EdgeTrack> edges;  // one per graph edge
  std::vector<Vec2> roots;       // metres, identity placement
  std::vector<Vec2> facings;     // unit (or zero when the forward axis is vertical)
  // The facing turned by its source frame's travel turn (travel_turns(); a blended frame by
  // its two sources' turns, weighted as blended); empty when no turns were given.
  std::vector<Vec2> headings;
  std::vector<TagMask> tags;
  Vec3 forward_axis = Vec3::UnitZ();  // of the target skeleton, in the root's frame (facing.h)
  Vec3 travel_axis = Vec3::UnitZ();   // of the target skeleton, in the root's frame (facing.h)
  double max_root_step_m = 0.0;       // the longest floor step of the root between two frames
                                      // any walk plays one after the other (the bounds of path
                                      // searches rest on it: path_cost.h)

  std::span<const Vec2> roots_of(int edge) const { return std::span(roots).subspan(edges[edge].first, edges[edge].count); }
  std::span<const Vec2> facings_of(int edge) const { return std::span(facings).subspan(edges[edge].first, edges[edge].count); }
  std::span<const Vec2> headings_of(int edge) const {
    return std::span(headings).subspan(edges[edge].first, edges[edge].count);
  }
  std::span<const TagMask> tags_of(int edge) const { return std::span(tags).subspan(edges[edge].first, edges[edge].count); }
};

// frame_tags: one mask per database frame, or empty (no tags). travel_turns: one per database
// frame (travel_heading.h), or empty (no headings).
EdgeTracks compute_edge_tracks(const MotionAssembler& assembler, const MotionGraph& graph,
                               std::span<const TagMask> frame_tags, const Vec3& forward_axis,
                               const Vec3& travel_axis, std::span<const float> travel_turns = {});

}  // namespace mg
