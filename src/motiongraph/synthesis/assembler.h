// Assembling motion from a walk (Kovar et al. 2002, section 3.1 and 4; DESIGN.md 5).
//
// Placement. Every edge is played under a floor transform W (database -> world). A clip edge
// keeps W; a transition edge for transition t blends the k frames t.from_frame.. (under W)
// with t.to_frame-k+1.. (under W * T, T = t's floor alignment) and leaves W * T for the next
// edge; k is the edge's blend length (the window, or more for a bridge: motion_graph.h).
// Blended frame p takes the root position as alpha(p) d + (1 - alpha(p)) a and every
// rotation (the root's in the world) as slerp(d, a, 1 - alpha(p)), with Kovar's weight
//   alpha(p) = 2((p+1)/k)^3 - 3((p+1)/k)^2 + 1   for the frame we leave;
// alpha(k-1) = 0, so the blend ends exactly on the arrival frame the next edge plays.
//
// Target skeleton. The result is on one skeleton of the database (by default the one of the
// walk's first clip). Frames of other subjects keep their joint rotations; their translations
// (root and any translated joint) are scaled by leg_length(target) / leg_length(theirs), and a
// transition between subjects A and B has its floor translation taken into that scaled space:
//   t' = s_A t + (s_A - s_B) R c_B   (c_B: the root's floor position at the arrival frame),
// which is the exact alignment when s_A = s_B and its first-order version otherwise.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/synthesis/floor_transform.h"
#include "motiongraph/synthesis/walk.h"

namespace mg {

// Kovar's blend weight on the frame we leave, p = 0..k-1.
double blend_weight(int p, int k);

// The root of one played frame: world position (metres) and world rotation.
struct RootPose {
  Vec3 position = Vec3::Zero();
  Quat rotation = Quat::Identity();
};

// Where a played frame comes from: database frame `departure` weighing `alpha` and `arrival`
// weighing 1 - alpha (a clip frame: both the same, alpha 1).
struct FrameSource {
  int departure = 0;
  int arrival = 0;
  double alpha = 1.0;

  // The frame that weighs more (the departure while alpha >= 0.5), whose contacts the frame
  // carries.
  int dominant() const { return alpha >= 0.5 ? departure : arrival; }
  bool operator==(const FrameSource&) const = default;
};

// What playing edges needs, for one target skeleton.
class MotionAssembler {
 public:
  // Fails when target_skeleton is not a skeleton of db, when the skeletons differ in joints
  // or translated joints, or when the root has no per-frame translation.
  static Result<MotionAssembler> create(const MotionDatabase& db, const MotionGraph& graph, int target_skeleton);

  const Skeleton& skeleton() const { return db_->skeletons[target_]; }
  int target_skeleton() const { return target_; }
  double scale_of(int skeleton) const { return scale_[skeleton]; }

  // An empty motion on the target skeleton at the database rate, to append frames to.
  Motion empty_motion() const;

  // The transform a transition composes onto the placement, in the target's scaled space.
  FloorTransform transition_transform(const Transition& transition) const;

  // Appends the frames edge `edge` plays, placed by `placement`, which becomes the placement
  // the next edge is played with.
  void append_edge(int edge, FloorTransform& placement, Motion& out) const;
  // Appends database frame `frame` placed by `placement`.
  void append_frame(int frame, const FloorTransform& placement, Motion& out) const {
    append_frame(frame, PreparedFloorTransform(placement), out);
  }
  void append_frame(int frame, const PreparedFloorTransform& placement, Motion& out) const;
  // Appends the blend of database frame `departure` placed by `w_departure`, weighing `alpha`, with
  // `arrival` placed by `w_arrival` (FrameSource's; a transition's frames, a start from rest's).
  void append_blend(int departure, const PreparedFloorTransform& w_departure, int arrival,
                    const PreparedFloorTransform& w_arrival, double alpha, Motion& out) const;

  // The root of database frame `frame` under `placement` (scaled to the target), without
  // building the pose.
  RootPose root_pose(int frame, const FloorTransform& placement) const {
    return root_pose(frame, PreparedFloorTransform(placement));
  }
  RootPose root_pose(int frame, const PreparedFloorTransform& placement) const;
  Vec3 root_position(int frame, const FloorTransform& placement) const { return root_pose(frame, placement).position; }
  Quat root_rotation(int frame, const FloorTransform& placement) const { return root_pose(frame, placement).rotation; }
  // The foot contacts (motion/foot_contacts.h) of the frames append_edge plays, from those of
  // the database frames (`frame_contacts`, per global frame): a clip frame has its own; a
  // blended frame those of the frame that weighs more in it (FrameSource::dominant).
  void append_edge_contacts(int edge, std::span<const ContactMask> frame_contacts,
                            std::vector<ContactMask>& out) const;
  // The database frames each frame append_edge plays is made of, in order.
  void append_edge_sources(int edge, std::vector<FrameSource>& out) const;
  // What append_edge plays, root only (what searches need; much cheaper than whole poses).
  void append_edge_roots(int edge, FloorTransform& placement, std::vector<RootPose>& out) const;

 private:
  // Calls on_frame(frame, placement) for each clip frame the edge plays, or
  // on_blend(departure, w_departure, arrival, w_arrival, alpha) for each blended frame (the
  // placements prepared once per edge), and moves the placement on.
  template <class OnFrame, class OnBlend>
  void visit_edge(int edge, FloorTransform& placement, OnFrame on_frame, OnBlend on_blend) const;
  RootPose blend_root(int departure, const PreparedFloorTransform& w_departure, int arrival,
                      const PreparedFloorTransform& w_arrival, double alpha) const;
  const DatabaseClip& clip_of(int frame, int* local) const;

  const MotionDatabase* db_ = nullptr;
  const MotionGraph* graph_ = nullptr;
  int target_ = 0;
  std::vector<double> scale_;  // per skeleton
  std::vector<int> clip_of_frame_;
};

// The walk played from `start` (applied to the database pose of its first frame): the walk's
// frames followed by the frame of its end node, so that a walk of one clip edge from f1 to
// f2 gives frames f1..f2; a walk that comes to rest plays its rest frames instead of the end
// node's frame (the first of them is it). The target skeleton is target_skeleton, or when it is -1 the
// skeleton of the start node's clip.
Result<Motion> assemble_walk(const MotionDatabase& db, const MotionGraph& graph, const Walk& walk,
                             const FloorTransform& start = {}, int target_skeleton = -1);

}  // namespace mg
