// The seed's self-consistency measure (its figure 3.2): the RMS angle, in degrees, between
// where the root faces and where it travels. Facing is the learnt travel axis (learn_travel_axes
// in synthesis/facing.h) turned by the root's world rotation, on the floor; travel is the floor direction from
// the root now to the root kTravelLookaheadFrames later. Frames whose root moves slower than
// kMovingSpeedMps over that span, whose lookahead runs past the motion's end, or whose forward
// axis points straight up, are left out. Each angle lies in [0, 180].
//
// Captured motion is consistent by construction of the travel axis (the mean travel direction
// in the root's frame), so the database's value is the baseline transitions are
// compared with. Around a transition the measure covers every frame whose lookahead span
// touches the blend: the kTravelLookaheadFrames frames before it (from the clip we leave),
// the k - 1 blended frames, with the frames after it (from the clip we arrive in) as the
// lookahead of the last ones.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/synthesis/assembler.h"
#include "motiongraph/synthesis/facing.h"

namespace mg {

struct ConsistencySum {
  double squared_deg = 0.0;  // sum of squared angles
  long long frames = 0;      // frames measured

  void add(const ConsistencySum& other) {
    squared_deg += other.squared_deg;
    frames += other.frames;
  }
  // The RMS angle in degrees; NaN when no frame was measured.
  double rms_deg() const;
};

// Frames first..last (clamped to the motion) of one motion: its root world rotations and root
// floor positions (metres), fps frames per second.
ConsistencySum consistency_over(std::span<const Quat> root_rotations, const std::vector<Vec2>& roots,
                                const Vec3& forward_axis, double fps, int first, int last);

// Every frame of every clip as captured; forward_axes from learn_travel_axes(db).
ConsistencySum database_consistency(const MotionDatabase& db, std::span<const Vec3> forward_axes);

// Around every transition edge of `graph`, played by `assembler` (on its target skeleton,
// whose forward axis is forward_axis).
ConsistencySum transition_consistency(const MotionDatabase& db, const MotionGraph& graph,
                                      const MotionAssembler& assembler, const Vec3& forward_axis);

}  // namespace mg
