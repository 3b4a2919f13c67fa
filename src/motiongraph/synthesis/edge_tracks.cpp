#include "motiongraph/synthesis/edge_tracks.h"

#include <algorithm>
#include <cassert>
#include <vector>

#include "motiongraph/core/huge_pages.h"
#include "motiongraph/core/parallel_for.h"

namespace mg {

EdgeTracks compute_edge_tracks(const MotionAssembler& assembler, const MotionGraph& graph,
                               std::span<const TagMask> frame_tags, const Vec3& forward_axis,
                               const Vec3& travel_axis, std::span<const float> travel_turns) {
  EdgeTracks tracks;
  tracks.forward_axis = forward_axis;
  tracks.travel_axis = travel_axis;
  auto tag_of = [&](int frame) { return frame_tags.empty() ? TagMask{0} : frame_tags[frame]; };
  // Each edge's place in the flat arrays is known from the frame counts: the edges are then
  // filled on all cores (a whole library's graph has 10^5 and more).
  const int edge_count = graph.edge_count();
  reserve_huge(tracks.edges, static_cast<size_t>(edge_count));
  tracks.edges.resize(static_cast<size_t>(edge_count));
  size_t total = 0;
  for (int e = 0; e < edge_count; ++e) {
    tracks.edges[static_cast<size_t>(e)].first = static_cast<int>(total);
    tracks.edges[static_cast<size_t>(e)].count = graph.edges[e].frame_count;
    total += static_cast<size_t>(graph.edges[e].frame_count);
  }
  // Tens of MB on a whole library's graph, written once by the workers below.
  reserve_huge(tracks.roots, total);
  reserve_huge(tracks.facings, total);
  reserve_huge(tracks.tags, total);
  tracks.roots.resize(total);
  tracks.facings.resize(total);
  const bool headings = !travel_turns.empty();
  if (headings) {
    reserve_huge(tracks.headings, total);
    tracks.headings.resize(total);
  }
  tracks.tags.resize(total);
  // Per worker: a buffer for an edge's roots and the longest step it saw (combined below; a
  // maximum does not depend on the order).
  const int workers = worker_threads(0);
  std::vector<std::vector<RootPose>> buffers(static_cast<size_t>(workers));
  std::vector<double> max_steps(static_cast<size_t>(workers), 0.0);
  parallel_for(edge_count, workers, 256, [&](int worker, long long index) {
    const int e = static_cast<int>(index);
    std::vector<RootPose>& roots = buffers[static_cast<size_t>(worker)];
    double& max_step = max_steps[static_cast<size_t>(worker)];
    const GraphEdge& edge = graph.edges[e];
    EdgeTrack& track = tracks.edges[static_cast<size_t>(e)];
    roots.clear();
    FloorTransform placement;
    assembler.append_edge_roots(e, placement, roots);
    assert(static_cast<int>(roots.size()) == track.count);
    track.change = placement;
    if (!roots.empty()) track.first_heading = facing_on_floor(roots.front().rotation, travel_axis);
    const auto first = static_cast<size_t>(track.first);
    for (size_t p = 0; p < roots.size(); ++p) {
      tracks.roots[first + p] = Vec2(roots[p].position.x(), roots[p].position.z());
      const Vec2 facing = facing_on_floor(roots[p].rotation, forward_axis);
      tracks.facings[first + p] = facing;
      double turn_rad = 0.0;
      if (!edge.transition) {
        const int frame = graph.nodes[edge.from_node].frame + static_cast<int>(p);
        tracks.tags[first + p] = tag_of(frame);
        if (headings) turn_rad = travel_turns[static_cast<size_t>(frame)];
      } else {
        const Transition& t = graph.transitions[edge.transition_index];
        const int k = blend_frames(edge);
        const int q = static_cast<int>(p);
        const double w = blend_weight(q, k);
        const int departure = t.from_frame + q, arrival = t.to_frame - k + 1 + q;
        tracks.tags[first + p] = w >= 0.5 ? tag_of(departure) : tag_of(arrival);
        if (headings) {
          turn_rad = w * travel_turns[static_cast<size_t>(departure)] + (1.0 - w) * travel_turns[static_cast<size_t>(arrival)];
        }
      }
      if (headings) tracks.headings[first + p] = turn(FloorTransform{turn_rad, 0.0, 0.0}, facing);
    }
    // Steps inside the edge and on to its node's own frame (the first of a clip piece leaving it).
    const Vec3 next = assembler.root_position(graph.nodes[edge.to_node].frame, placement);
    Vec2 last(next.x(), next.z());
    for (int p = track.count; p-- > 0;) {
      const Vec2& root = tracks.roots[first + static_cast<size_t>(p)];
      max_step = std::max(max_step, (last - root).norm());
      last = root;
    }
  });
  for (double step : max_steps) tracks.max_root_step_m = std::max(tracks.max_root_step_m, step);
  // And on to the first frame of a transition leaving that node: already blended, a few
  // millimetres from the node's own.
  for (int e = 0; e < edge_count; ++e) {
    const EdgeTrack& track = tracks.edges[static_cast<size_t>(e)];
    if (track.count == 0) continue;
    const Vec2& last = tracks.roots[static_cast<size_t>(track.first + track.count - 1)];
    const int to = graph.edges[e].to_node;
    for (int f = graph.edge_offsets[to]; f < graph.edge_offsets[to + 1]; ++f) {
      const EdgeTrack& next = tracks.edges[static_cast<size_t>(f)];
      if (!graph.edges[f].transition || next.count == 0) continue;
      const Vec2& first = tracks.roots[static_cast<size_t>(next.first)];
      const Vec3 placed = track.change.apply(Vec3(first.x(), 0.0, first.y()));
      tracks.max_root_step_m = std::max(tracks.max_root_step_m, (Vec2(placed.x(), placed.z()) - last).norm());
    }
  }
  return tracks;
}

}  // namespace mg
