// Small random graphs (no database behind them) for checking the searches against brute force.
#pragma once

#include <random>

#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/synthesis/edge_tracks.h"

namespace mg::test {

// A strongly connected random graph: a ring through every node plus random extra edges (a
// quarter of them transitions with a random distance), 1..max_frames frames per edge.
MotionGraph random_search_graph(std::mt19937& rng, int nodes, int extra_edges, int max_frames);

// Tracks for it: roots stepping up to 0.1 m a frame, unit facings, random tags (bits 0, 1)
// and a random placement change on transitions.
EdgeTracks random_tracks(std::mt19937& rng, const MotionGraph& graph);

}  // namespace mg::test
