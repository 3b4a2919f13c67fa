#include "motiongraph/synthesis/rest_starts.h"

#include <algorithm>
#include <cmath>

#include "motiongraph/metric/reference_distance.h"
#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

namespace {

// The joints' positions of database frames [first, first + count) as the assembler plays them with
// no placement: frame-major, joint_count each.
std::vector<Vec3> played_joints(const MotionAssembler& assembler, int first, int count) {
  Motion motion = assembler.empty_motion();
  const PreparedFloorTransform none{FloorTransform{}};
  for (int f = first; f < first + count; ++f) assembler.append_frame(f, none, motion);
  return world_positions(assembler.skeleton(), motion);
}

}  // namespace

std::vector<RestStart> find_rest_starts(const MotionDatabase& db, const MotionGraph& graph,
                                        const MotionAssembler& assembler, int held_frame) {
  return find_starts_from(db, graph, assembler, std::span<const int>(&held_frame, 1));
}

std::vector<RestStart> find_starts_from(const MotionDatabase& db, const MotionGraph& graph,
                                        const MotionAssembler& assembler, std::span<const int> coming,
                                        double going_mps) {
  if (coming.empty()) return {};
  const double fps = db.fps;
  const int stride = std::max(1, static_cast<int>(std::lround(fps / 30.0)));
  const int blend = std::max(2, static_cast<int>(std::lround(kStartBlendS * fps)));
  const int max_lead = std::max(blend, static_cast<int>(std::lround(kMaxStartLeadS * fps)));
  const int samples = std::max(2, (blend + stride - 1) / stride);  // the window's frames: f, f + stride, ...
  const int travel_frames = std::max(1, static_cast<int>(std::lround(kStartTravelS * fps)));
  const int joints = assembler.skeleton().joint_count();
  const std::vector<double> weights(static_cast<size_t>(joints), 1.0), taper(static_cast<size_t>(samples), 1.0);
  // The clouds the reference compares: the coming frames' joints sampled as the lead-ins' are (one
  // frame held: `samples` times, standing still), then the lead-in's sampled frames.
  std::vector<Vec3> clouds(static_cast<size_t>(2 * samples * joints));
  for (int t = 0; t < samples; ++t) {
    const size_t i = std::min(static_cast<size_t>(t * stride), coming.size() - 1);
    const std::vector<Vec3> frame = played_joints(assembler, coming[i], 1);
    std::copy(frame.begin(), frame.end(), clouds.begin() + t * joints);
  }
  const double norm = static_cast<double>(samples) * joints;
  std::vector<RestStart> best;  // per clip the graph goes on from, its best start
  for (int first_node = 0; first_node < graph.node_count();) {
    const int c = graph.nodes[first_node].clip;
    int end_node = first_node;
    while (end_node < graph.node_count() && graph.nodes[end_node].clip == c) ++end_node;
    const DatabaseClip& clip = db.clips[c];
    // The clip's frames up to its last node, once.
    const int last = graph.nodes[end_node - 1].frame;
    const std::vector<Vec3> positions = played_joints(assembler, clip.first_frame, last - clip.first_frame + 1);
    // Whether the motion at a node travels: its root's floor speed over the kStartTravelS after it
    // (as far as the clip goes).
    const int clip_last = clip.first_frame + clip.frame_count - 1;
    auto travels = [&](int n) {
      const int from = graph.nodes[n].frame, to = std::min(clip_last, from + travel_frames);
      const Vec3 a = assembler.root_position(from, {}), b = assembler.root_position(to, {});
      return to > from && std::hypot(b.x() - a.x(), b.z() - a.z()) >= kStartTravelMps * (to - from) / fps;
    };
    // Per frame of the clip, the last frame up to it from which its root travels slower than
    // kStartTravelMps over kGoingS (clip.first_frame - 1: none): a lead-in gets going after the
    // last such frame before its node.
    std::vector<int> slow_until(static_cast<size_t>(clip.frame_count), clip.first_frame - 1);
    if (going_mps > 0.0) {
      const int window = std::max(1, static_cast<int>(std::lround(kGoingS * fps)));
      for (int f = clip.first_frame; f <= clip_last; ++f) {
        const Vec3 a = assembler.root_position(f, {}), b = assembler.root_position(std::min(f + window, clip_last), {});
        const bool slow = std::hypot(b.x() - a.x(), b.z() - a.z()) < kStartTravelMps * window / fps;
        slow_until[static_cast<size_t>(f - clip.first_frame)] =
            slow ? f : f > clip.first_frame ? slow_until[static_cast<size_t>(f - 1 - clip.first_frame)] : f - 1;
      }
    }
    int node = first_node;
    int judged = -1;  // the node whether it travels was last judged for
    bool moving = false;
    RestStart kept;
    kept.node = -1;
    for (int f = clip.first_frame; f + blend <= last; f += stride) {
      // The first node after the blend's last frame (f + blend - 1).
      while (graph.nodes[node].frame < f + blend) ++node;
      if (graph.nodes[node].frame - f > max_lead) continue;
      if (judged != node) {
        judged = node;
        moving = travels(node);
      }
      if (!moving) continue;
      for (int t = 0; t < samples; ++t) {
        const int frame = std::min(f + t * stride, last);
        const auto from = positions.begin() + static_cast<long>(frame - clip.first_frame) * joints;
        std::copy(from, from + joints, clouds.begin() + (samples + t) * joints);
      }
      const ReferenceDistance d = reference_distance(clouds, joints, weights, taper, 0, 2 * samples - 1);
      const double rms = std::sqrt(d.distance / norm);
      const int slow = slow_until[static_cast<size_t>(graph.nodes[node].frame - 1 - clip.first_frame)];
      const double rank = rms + kStartWaitMps * (graph.nodes[node].frame - f) / fps +
                          going_mps * std::max(0, slow + 1 - f) / fps;
      if (kept.node < 0 || rank < kept.rank_m) {
        kept = {f, node, blend, {d.alignment.yaw_rad, d.alignment.x_m, d.alignment.z_m}, rms, rank};
      }
    }
    if (kept.node >= 0) best.push_back(kept);
    first_node = end_node;
  }
  const size_t keep = std::min(best.size(), static_cast<size_t>(kStartChoices));
  std::partial_sort(best.begin(), best.begin() + static_cast<long>(keep), best.end(),
                    [](const RestStart& a, const RestStart& b) {
                      return a.rank_m != b.rank_m ? a.rank_m < b.rank_m : a.first_frame < b.first_frame;
                    });
  best.resize(keep);
  return best;
}

}  // namespace mg
