// What every synthesis command needs of a graph, set up once: the assembler on the target
// skeleton, the learnt forward axis, per-frame tags and the edge tracks.
#pragma once

#include <string>
#include <vector>

#include "motiongraph/synthesis/edge_tracks.h"

namespace mg {

struct SynthesisContext {
  const MotionDatabase* db = nullptr;
  const MotionGraph* graph = nullptr;
  MotionAssembler assembler;
  std::vector<TagMask> frame_tags;
  EdgeTracks tracks;

  // The placement that puts node `node`'s frame with its root at `at` facing `direction`
  // (unit, on the floor).
  FloorTransform placement_facing(int node, const Vec2& at, const Vec2& direction) const;
  // The same for the first frame edge `edge` plays (a transition's first frame is already
  // blended, a few millimetres from its node's frame).
  FloorTransform placement_facing_edge(int edge, const Vec2& at, const Vec2& direction) const;
  // The tag bit of a name, or an error listing the graph's tags.
  Result<TagMask> tag_mask(const std::string& name) const;
};

// target_skeleton -1: the skeleton of the database's first clip.
Result<SynthesisContext> make_synthesis_context(const MotionDatabase& db, const MotionGraph& graph,
                                                int target_skeleton = -1);

}  // namespace mg
