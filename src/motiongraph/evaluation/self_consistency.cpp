// The seed's self-consistency measure: facing against travel.
#include "motiongraph/evaluation/self_consistency.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace mg {

double ConsistencySum::rms_deg() const {
  return frames > 0 ? std::sqrt(squared_deg / static_cast<double>(frames)) : std::numeric_limits<double>::quiet_NaN();
}

ConsistencySum consistency_over(std::span<const Quat> root_rotations, const std::vector<Vec2>& roots,
                                const Vec3& forward_axis, double fps, int first, int last) {
  ConsistencySum sum;
  const int n = static_cast<int>(std::min(root_rotations.size(), roots.size()));
  for (int i = std::max(0, first); i <= last && i < n; ++i) {
    const Vec2 travel = travel_direction(roots, i, kTravelLookaheadFrames, fps, kMovingSpeedMps);
    const Vec2 facing = facing_on_floor(root_rotations[i], forward_axis);
    if (travel.isZero() || facing.isZero()) continue;
    const double angle_deg = std::acos(std::clamp(travel.dot(facing), -1.0, 1.0)) * 180.0 / std::numbers::pi;
    sum.squared_deg += angle_deg * angle_deg;
    ++sum.frames;
  }
  return sum;
}

namespace {

// The root's world rotations and floor positions of a motion.
void root_tracks(const Motion& motion, std::vector<Quat>& rotations, std::vector<Vec2>& roots) {
  rotations.clear();
  roots.clear();
  for (int f = 0; f < motion.frame_count; ++f) {
    rotations.push_back(motion.rotations(f)[0]);
    const Vec3& p = motion.translations(f)[0];
    roots.emplace_back(p.x(), p.z());
  }
}

}  // namespace

ConsistencySum database_consistency(const MotionDatabase& db, std::span<const Vec3> forward_axes) {
  ConsistencySum sum;
  std::vector<Quat> rotations;
  std::vector<Vec2> roots;
  for (const DatabaseClip& clip : db.clips) {
    root_tracks(clip.motion, rotations, roots);
    sum.add(consistency_over(rotations, roots, forward_axes[clip.skeleton], db.fps, 0, clip.frame_count - 1));
  }
  return sum;
}

ConsistencySum transition_consistency(const MotionDatabase& db, const MotionGraph& graph,
                                      const MotionAssembler& assembler, const Vec3& forward_axis) {
  constexpr int kLook = kTravelLookaheadFrames;
  ConsistencySum sum;
  std::vector<Quat> rotations;
  std::vector<Vec2> roots;
  for (int e = 0; e < graph.edge_count(); ++e) {
    const GraphEdge& edge = graph.edges[e];
    if (!edge.transition) continue;
    const Transition& t = graph.transitions[edge.transition_index];
    const DatabaseClip& leave = db.clips[db.clip_of(t.from_frame)];
    const DatabaseClip& arrive = db.clips[db.clip_of(t.to_frame)];
    Motion motion = assembler.empty_motion();
    FloorTransform placement;
    for (int f = std::max(leave.first_frame, t.from_frame - kLook); f < t.from_frame; ++f) {
      assembler.append_frame(f, placement, motion);
    }
    const int blend_first = motion.frame_count;
    assembler.append_edge(e, placement, motion);
    const int blend_last = motion.frame_count - 1;
    const int arrive_end = arrive.first_frame + arrive.frame_count;
    for (int f = t.to_frame; f < arrive_end && f <= t.to_frame + kLook; ++f) assembler.append_frame(f, placement, motion);
    root_tracks(motion, rotations, roots);
    sum.add(consistency_over(rotations, roots, forward_axis, db.fps, blend_first - kLook, blend_last));
  }
  return sum;
}

}  // namespace mg
