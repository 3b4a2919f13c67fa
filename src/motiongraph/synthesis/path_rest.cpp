#include "motiongraph/synthesis/path_rest.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace mg {

namespace {

// The length of a root track in chords of `chord_frames` frames, carried on from `sample` (the last
// chord's end) and `since` (frames since it).
double track_length(std::span<const RootPose> track, int chord_frames, Vec2& sample, int& since) {
  double metres = 0.0;
  for (const RootPose& r : track) {
    if (++since < chord_frames) continue;
    const Vec2 p(r.position.x(), r.position.z());
    metres += (p - sample).norm();
    sample = p;
    since = 0;
  }
  return metres;
}

int chord_frames(const SynthesisContext& context) {
  return std::max(1, static_cast<int>(std::lround(kRestChordS * context.db->fps)));
}

}  // namespace

std::vector<double> rest_ending_travel(const SynthesisContext& context) {
  const MotionGraph& graph = *context.graph;
  const RestEndings& rest = context.rest();
  std::vector<double> travel(rest.endings.size(), 0.0);
  for (size_t i = 0; i < travel.size(); ++i) {
    const RestEnding& ending = rest.endings[i];
    std::vector<RootPose> track;
    for (int f = graph.nodes[static_cast<size_t>(ending.node)].frame; f <= ending.rest_frame; ++f) {
      track.push_back(context.assembler.root_pose(f, FloorTransform{}));
    }
    if (track.empty()) continue;  // (its node stands already)
    Vec2 sample(track.front().position.x(), track.front().position.z());
    int since = 0;
    travel[i] = track_length(track, chord_frames(context), sample, since);
    const Vec2 still(track.back().position.x(), track.back().position.z());
    if (since > 0) travel[i] += (still - sample).norm();
  }
  return travel;
}

PathRestWay nearest_rest_way(const SynthesisContext& context, const FloorPath& path, const Walk& walk,
                             const FloorTransform& start, std::span<const Vec2> edited_roots,
                             std::span<const double> ending_travel) {
  const MotionGraph& graph = *context.graph;
  const RestEndings& rest = context.rest();
  // The walk's roots as played, each node's frame among them and its placement.
  FloorTransform at = start;
  std::vector<RootPose> played;
  std::vector<size_t> node_frame{0};
  std::vector<FloorTransform> node_placement{at};
  for (int e : walk.edges) {
    context.assembler.append_edge_roots(e, at, played);
    node_frame.push_back(played.size());
    node_placement.push_back(at);
  }
  std::vector<Vec2> roots;
  for (const RootPose& r : played) roots.emplace_back(r.position.x(), r.position.z());
  const Vec3 last = context.assembler.root_position(graph.nodes[walk.end_node(graph)].frame, at);
  roots.emplace_back(last.x(), last.z());
  const std::vector<double> arcs = path.followed_arcs(roots);  // how far along the path each frame is
  // How far along the path each node of the walk stands in the motion as edited (the search's
  // result: its roots, edited, up to the frame that reached the end; past it, as played on from there).
  const std::vector<double> edited_arcs = path.followed_arcs(edited_roots);
  auto progress_at = [&](size_t frame) {
    if (edited_arcs.empty()) return arcs[frame];
    const size_t last_edited = edited_arcs.size() - 1;
    return frame <= last_edited ? edited_arcs[frame] : edited_arcs[last_edited] + arcs[frame] - arcs[last_edited];
  };
  // The edit bends the way to rest onto the path keeping its own length: the way's travel is its
  // root's track measured in chords of kRestChordS (a stride's sway left out).
  const double length = path.length_m();
  const int chords = chord_frames(context);
  // From each node the walk reaches within kRestSearchM of the end, last first, every way on that
  // stands within kRestSearchS seconds (kRestExpansions edges tried from each; no bridge, no leap) to
  // a node of a clip that ends at rest, and that clip on: the one whose character stands nearest the
  // end, a transition on the way counting kRestTransitionM more.
  PathRestWay best;
  double best_score = std::numeric_limits<double>::infinity();
  const int max_frames = static_cast<int>(std::lround(kRestSearchS * context.db->fps));
  // The fewest frames from each node until the character stands: a way that cannot stand within
  // max_frames is not followed.
  const std::vector<double> fewest = cost_to_rest(graph, rest, 0.0, 0.0, /*penalties=*/false);
  long long expansions = 0;
  std::vector<int> way;
  std::vector<RootPose> scratch;
  struct At {
    int node = 0;
    FloorTransform placement;
    int frames = 0, transitions = 0;
    double along = 0.0;  // how far along the path, as the edit will put it
    Vec2 sample = Vec2::Zero();
    int since = 0;
  };
  std::function<void(size_t, const At&)> visit = [&](size_t kept, const At& at_node) {
    if (const RestEnding* ending = rest.at(at_node.node); ending != nullptr) {
      const Vec3 first = context.assembler.root_position(graph.nodes[static_cast<size_t>(at_node.node)].frame,
                                                         at_node.placement);
      const double along = at_node.along + (Vec2(first.x(), first.z()) - at_node.sample).norm() +
                           ending_travel[static_cast<size_t>(ending - rest.endings.data())];
      const double score = std::abs(along - length) + kRestTransitionM * at_node.transitions +
                           (ending->penalty_frames > 0 ? kRestLandingM : 0.0);
      if (score < best_score) {
        best = {kept, way, ending};
        best_score = score;
      }
    }
    for (int e = graph.edge_offsets[at_node.node]; e < graph.edge_offsets[at_node.node + 1]; ++e) {
      const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      const double to = fewest[static_cast<size_t>(edge.to_node)];
      if (edge.bridge || rest.leap(e) || to < 0.0 || at_node.frames + edge.frame_count + to > max_frames) {
        continue;
      }
      if (++expansions > kRestExpansions) return;
      At next = at_node;
      next.node = edge.to_node;
      next.frames += edge.frame_count;
      next.transitions += edge.transition ? 1 : 0;
      scratch.clear();
      context.assembler.append_edge_roots(e, next.placement, scratch);
      next.along += track_length(scratch, chords, next.sample, next.since);
      if (next.along - length > kRestOvershootM) continue;  // gone well past the end
      way.push_back(e);
      visit(kept, next);
      way.pop_back();
    }
  };
  for (size_t k = walk.edges.size() + 1; k-- > 0 && progress_at(node_frame[k]) >= length - kRestSearchM;) {
    expansions = 0;  // each node its own budget
    const int node = k == 0 ? walk.start_node : graph.edges[static_cast<size_t>(walk.edges[k - 1])].to_node;
    const Vec3 here = context.assembler.root_position(graph.nodes[static_cast<size_t>(node)].frame, node_placement[k]);
    visit(k, At{node, node_placement[k], 0, 0, progress_at(node_frame[k]), Vec2(here.x(), here.z()), 0});
  }
  if (best.ending == nullptr) {  // none near the end: the cheapest way to rest from where the walk ends
    // (frames until the character stands, a frame's worth per transition, a bridge 30: as steering's
    // defaults price it, controller.h).
    constexpr double kTransitionFrames = 1.0, kBridgeFrames = 30.0;
    const std::vector<double> costs = cost_to_rest(graph, rest, kTransitionFrames, kBridgeFrames);
    const RestRoute cheapest = rest_route(graph, rest, costs, walk.end_node(graph), kTransitionFrames,
                                          kBridgeFrames, std::numeric_limits<int>::max());
    best = {walk.edges.size(), cheapest.edges, cheapest.ending};
  }
  return best;
}

}  // namespace mg
