// Coming to rest. A pruned graph keeps what a walk can play forever (motion_graph.h), so where a
// library's clips stop ("slow walk, stop") but none starts from standing, the pruning leaves
// their halts as dead ends: subject 16's graph keeps 9 of its 88 stop frames, and a character
// asked to stop walked on. A clip that ends standing still is a way to rest all the same, one
// with no way back: from any graph node of such a clip, play the clip on as captured to its end,
// then hold its last frame.
//
// A clip ends at rest when its whole body stands still over its last frames: every joint slower
// than kStillJointMps (each step's fastest joint averaged over kStillWindowFrames) for at least
// kMinStillS to its end (a root that stops travelling is not enough: a jump on the spot, a dance,
// a hop stand nowhere). It rests from the first frame of that stillness. Its nodes come to rest by
// slowing down, not by a leap: a node counts when no foot is down for more than kMaxFlightS (a
// running stride's flight: subject 16 runs up to 0.29 s off the ground, jumps 0.43-0.48 s)
// between it and the rest frame, and when it is at most kMaxRestLeadS
// before it (a long dance is no way to stop); nor does the way to it leap (RestEndings::leaps).
// A clip that leaps within kMaxRestLeadS before it stands comes to rest from a landing (a high
// jump's crouch): its endings cost kLandingRestPenaltyS more, so that the way to rest takes a stop
// by slowing down where one is near (running into rest on the complete subject 16 stood in 16_04's
// landing crouch), and a landing where nothing else is.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/synthesis/assembler.h"

namespace mg {

constexpr double kStillJointMps = 0.5;
constexpr int kStillWindowFrames = 5;
constexpr double kMinStillS = 0.1;
constexpr double kMaxFlightS = 0.35;
constexpr double kMaxRestLeadS = 4.0;
constexpr double kLandingRestPenaltyS = 2.0;

struct RestEnding {
  int node = 0;        // the graph node it leaves from (its frame is the first it plays)
  int rest_frame = 0;  // global frame from which the root stands still to the clip's end
  int last_frame = 0;  // the clip's last frame (global): the frame held at rest
  int penalty_frames = 0;  // added to its cost: kLandingRestPenaltyS's frames for a rest from a landing

  // Frames played from the node's frame until the character stands still (0 from a node at rest).
  int frames_to_rest(const MotionGraph& graph) const {
    return rest_frame > graph.nodes[node].frame ? rest_frame - graph.nodes[node].frame : 0;
  }
  // What the way to rest pays for it: its frames to rest and its penalty.
  double cost(const MotionGraph& graph) const { return frames_to_rest(graph) + penalty_frames; }
  // The database frames the ending plays: the node's frame to the clip's last, in order.
  std::vector<int> frames(const MotionGraph& graph) const;
};

struct RestEndings {
  std::vector<RestEnding> endings;  // by node, one per node of a clip that ends at rest
  std::vector<int> of_node;         // per graph node: its ending's index, or -1
  // Per graph edge: it plays a leap (a flight longer than kMaxFlightS: a jump, a hop), which the
  // way to rest does not take. Empty: none known.
  std::vector<char> leaps;

  bool leap(int edge) const {
    return static_cast<size_t>(edge) < leaps.size() && leaps[static_cast<size_t>(edge)] != 0;
  }

  bool empty() const { return endings.empty(); }
  // The ending of `node`, or null (none; no ending found at all: of_node empty).
  const RestEnding* at(int node) const {
    if (static_cast<size_t>(node) >= of_node.size()) return nullptr;
    const int i = of_node[static_cast<size_t>(node)];
    return i < 0 ? nullptr : &endings[static_cast<size_t>(i)];
  }
};

// The frame of a clip's motion (on its skeleton, at `fps`) from which its whole body stands still
// to its end, as above; motion.frame_count when it does not.
int still_from(const Skeleton& skeleton, const Motion& motion, double fps);

// The endings of `graph`'s nodes and its edges that leap, the edges' frames as `assembler` plays
// them; `frame_contacts`, every database frame's foot contacts (empty: none known, no flight judged).
RestEndings find_rest_endings(const MotionDatabase& db, const MotionGraph& graph, const MotionAssembler& assembler,
                              std::span<const ContactMask> frame_contacts);

// What taking `edge` costs on the way to rest: its frames, and the transition's and bridge's costs.
inline double rest_edge_cost(const GraphEdge& edge, double transition_cost, double bridge_cost) {
  return edge.frame_count + (edge.transition ? transition_cost : 0.0) + (edge.bridge ? bridge_cost : 0.0);
}

// Per node, the least cost of coming to rest from it: frames played until the character stands
// still (1 each), plus `transition_cost` per transition and `bridge_cost` more per bridge taken on
// the way, and a landing's penalty_frames unless `penalties` is false (then: the fewest frames); -1
// where no walk reaches an ending (every node or none in a pruned graph). Dijkstra over the
// reversed edges from each ending's node.
std::vector<double> cost_to_rest(const MotionGraph& graph, const RestEndings& endings, double transition_cost,
                                 double bridge_cost, bool penalties = true);

// The way to rest from `node` down `costs` (cost_to_rest's, with the same edge costs): at each node
// its ending when that costs what the node does, else the first edge that leads as cheaply, until
// an ending or `max_frames` played (the rest of the way for a later call). No edge and no ending
// where no way to rest is (costs -1).
struct RestRoute {
  std::vector<int> edges;
  const RestEnding* ending = nullptr;  // reached at the end of `edges`; null when not (yet)
};
RestRoute rest_route(const MotionGraph& graph, const RestEndings& endings, const std::vector<double>& costs, int node,
                     double transition_cost, double bridge_cost, int max_frames);

}  // namespace mg
