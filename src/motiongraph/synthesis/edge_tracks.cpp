#include "motiongraph/synthesis/edge_tracks.h"

#include <algorithm>

namespace mg {

EdgeTracks compute_edge_tracks(const MotionAssembler& assembler, const MotionGraph& graph,
                               std::span<const TagMask> frame_tags, const Vec3& forward_axis) {
  EdgeTracks tracks;
  tracks.forward_axis = forward_axis;
  auto tag_of = [&](int frame) { return frame_tags.empty() ? TagMask{0} : frame_tags[frame]; };
  for (int e = 0; e < graph.edge_count(); ++e) {
    const GraphEdge& edge = graph.edges[e];
    EdgeTrack track;
    track.first = static_cast<int>(tracks.roots.size());
    track.count = edge.frame_count;
    std::vector<RootPose> roots;
    FloorTransform placement;
    assembler.append_edge_roots(e, placement, roots);
    track.change = placement;
    for (size_t p = 0; p < roots.size(); ++p) {
      tracks.roots.emplace_back(roots[p].position.x(), roots[p].position.z());
      tracks.facings.push_back(facing_on_floor(roots[p].rotation, forward_axis));
      if (!edge.transition) {
        tracks.tags.push_back(tag_of(graph.nodes[edge.from_node].frame + static_cast<int>(p)));
      } else {
        const Transition& t = graph.transitions[edge.transition_index];
        const int k = blend_frames(edge);
        const int q = static_cast<int>(p);
        tracks.tags.push_back(blend_weight(q, k) >= 0.5 ? tag_of(t.from_frame + q) : tag_of(t.to_frame - k + 1 + q));
      }
    }
    // Steps inside the edge and on to the first frame of whatever edge follows.
    const Vec3 next = assembler.root_position(graph.nodes[edge.to_node].frame, placement);
    Vec2 last(next.x(), next.z());
    for (int p = track.count; p-- > 0;) {
      const Vec2& root = tracks.roots[static_cast<size_t>(track.first) + static_cast<size_t>(p)];
      tracks.max_root_step_m = std::max(tracks.max_root_step_m, (last - root).norm());
      last = root;
    }
    tracks.edges.push_back(track);
  }
  return tracks;
}

}  // namespace mg
