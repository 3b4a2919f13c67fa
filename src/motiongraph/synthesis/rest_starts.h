// Starting off from rest. A character that came to rest (rest_endings.h) holds the last frame of
// a clip that ends standing still, and on every library tried the graph does not go on from there:
// the pruning keeps what a walk can play forever, and no clip starts from standing where the graph
// leads into it (nothing leads into a clip's first frames). A start is the counterpart of a rest
// ending: from the frame held, a blend over kStartBlendS into a lead-in, a piece of a clip that
// ends at one of the graph's nodes, then that clip on as captured to the node, from which the
// graph goes on.
//
// The lead-ins are ranked by how near they stay to the pose held: the frame distance (DESIGN.md 3)
// between the frame held repeated over the blend (standing still) and the lead-in's first frames,
// the joints for points, every joint weighing alike, the frames sampled at about 30 per second,
// the two aligned on the floor in closed form (metric/reference_distance.h), which also places the
// lead-in. A slow first step from a stance like the one held ranks before a stride under way. Each
// second of lead-in adds kStartWaitMps to the distance ranked by: a lead-in is often the capture's
// standing before it walks off, played on as captured, and a start that waits there answers a
// steering control late (subject 16's nearest stood 2 s before its node). A lead-in leads into the
// first node after its blend (the graph plays the clip on from there) and is at most
// kMaxStartLeadS long, and only into a node where the motion goes somewhere: its root travels at
// kStartTravelMps or faster over the kStartTravelS after it (a start into more standing is none:
// on libraries without motion types, CMU 29's and 49's nearest lead-ins stood on, and so did the
// character asked to move); each clip has its best one, and the kStartChoices best clips' are kept (one
// clip's standing frames would fill the list with the same start a frame apart), among which the
// controller chooses by the motion type and the heading asked (controller.h).
#pragma once

#include <span>
#include <vector>

#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/synthesis/assembler.h"
#include "motiongraph/synthesis/floor_transform.h"

namespace mg {

constexpr double kStartBlendS = 0.5;
constexpr double kMaxStartLeadS = 2.0;
constexpr int kStartChoices = 16;
constexpr double kStartWaitMps = 0.02;
constexpr double kStartTravelMps = 0.3;
constexpr double kStartTravelS = 1.0;
// A start from motion under way (find_starts_from) is ranked by how soon it gets going too: each
// second of its lead-in up to the last frame from which its root travels slower than
// kStartTravelMps over kGoingS adds kGoingMps.
constexpr double kGoingMps = 0.1;
constexpr double kGoingS = 0.25;

struct RestStart {
  int first_frame = 0;   // the lead-in's first database frame: the blend's first arrival frame
  int node = 0;          // the graph node it leads into (the node's frame follows the lead-in's last)
  int blend_frames = 0;  // frames blended from the frame held into the lead-in's first ones
  // The lead-in's frames onto the frame held, both as MotionAssembler::append_frame places them
  // with no placement (composed onto the held frame's placement, it places the lead-in).
  FloorTransform alignment;
  // The distance ranked by: the root mean square, over the window's frames and joints, of the
  // aligned joints' distances to the held frame's (metres).
  double rms_m = 0.0;
  double rank_m = 0.0;  // what it is ranked by: rms_m, and kStartWaitMps per second of the lead-in

  // The frames a start plays: blend_frames blended, then the lead-in on as captured up to the
  // node's frame (the graph's edges play it).
  int frames(const MotionGraph& graph) const { return graph.nodes[node].frame - first_frame; }
};

// The starts from database frame `held_frame`, best first, at most kStartChoices, at most one from
// each clip; empty when no clip has kStartBlendS of frames before a node of the graph where its
// motion travels.
std::vector<RestStart> find_rest_starts(const MotionDatabase& db, const MotionGraph& graph,
                                        const MotionAssembler& assembler, int held_frame);

// The starts as above from motion under way (a rest taken back while the stopping clip plays): the
// window compared with the lead-ins' first frames is `coming`, the database frames the character
// would play next (its last repeated where it has fewer than the blend's frames; one frame: held),
// and the blend's departure frames are those. `going_mps` (kGoingMps for motion under way; 0 for a
// frame held, as find_rest_starts) is added to the rank per second of a lead-in before it gets
// going: asked to go on as it slows, the nearest lead-ins slow to a standstill too, and waited there
// (on the 8-subject library, 29_01's standing start: 0.5 m covered in 1.5 s, no more than by
// standing first).
std::vector<RestStart> find_starts_from(const MotionDatabase& db, const MotionGraph& graph,
                                        const MotionAssembler& assembler, std::span<const int> coming,
                                        double going_mps = 0.0);

}  // namespace mg
