// How far a motion tag lies from each node of a graph, in frames: the fewest frames any walk from
// the node plays before it plays a frame carrying the tag (0 where the node's own first frame
// carries it). A search that sees only its horizon finds every walk within it as far from a tag
// it cannot reach in time: asked to run, a character walking far from any way into running
// would walk on. Priced per frame as the frames within the horizon are, this distance is what
// any continuation beyond the horizon must still pay, a cost-to-go (controller.h).
//
// Each edge's frames are its track's (EdgeTracks::tags_of: a transition's blended frames carry
// both sides' tags); from node u by edge e to node v, the distance is e's frames before its
// first tagged one, or all of e's frames and then v's distance. Dijkstra over the reversed edges.
#pragma once

#include <vector>

#include "motiongraph/synthesis/edge_tracks.h"

namespace mg {

// Per node of `graph`, the frames to the first frame carrying any tag of `tag`; -1 where no walk
// reaches one (every node, in a strongly connected graph without the tag).
std::vector<int> frames_to_tag(const MotionGraph& graph, const EdgeTracks& tracks, TagMask tag);

}  // namespace mg
