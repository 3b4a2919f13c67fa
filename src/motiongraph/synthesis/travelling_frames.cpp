#include "motiongraph/synthesis/travelling_frames.h"

#include <algorithm>
#include <span>

#include "motiongraph/synthesis/tag_distance.h"

namespace mg {

namespace {

constexpr double kHalfShare = 0.5;  // of the pace, over each half second

}  // namespace

std::vector<TagMask> travelling_frames(const SynthesisContext& context, double travel_mps) {
  const MotionDatabase& db = *context.db;
  const MotionGraph& graph = *context.graph;
  const double fps = db.fps > 0.0 ? db.fps : 30.0;
  // Each database frame: whether the root covers the pace over the second around it in its clip,
  // and half of it over each half second (a crouch before a leap, or the landing after one, is no
  // travel though the leap carries the second: subject 16's forward jumps average 0.48 m/s).
  std::vector<Vec2> roots(static_cast<size_t>(db.frame_count()));
  for (int f = 0; f < db.frame_count(); ++f) {
    const Vec3 root = context.assembler.root_position(f, FloorTransform{});
    roots[static_cast<size_t>(f)] = Vec2(root.x(), root.z());
  }
  std::vector<char> travels(roots.size(), 0);
  const int half = std::max(1, static_cast<int>(0.5 * fps));
  for (const DatabaseClip& clip : db.clips) {
    const int first = clip.first_frame, last = clip.first_frame + clip.frame_count - 1;
    for (int f = first; f <= last; ++f) {
      const int a = std::max(first, f - half), b = std::min(last, f + half);
      if (b <= a) continue;
      auto covers = [&](int from, int to, double share) {
        const double covered = (roots[static_cast<size_t>(to)] - roots[static_cast<size_t>(from)]).norm();
        return to == from || covered * fps >= share * travel_mps * (to - from);
      };
      travels[static_cast<size_t>(f)] = covers(a, b, 1.0) && covers(a, f, kHalfShare) && covers(f, b, kHalfShare);
    }
  }
  // Each edge's frames: their database frame's, a blended frame its weightier side's (as
  // EdgeTracks gives the tags).
  std::vector<TagMask> marks(context.tracks.roots.size(), 0);
  std::vector<FrameSource> sources;
  for (int e = 0; e < graph.edge_count(); ++e) {
    const EdgeTrack& track = context.tracks.edges[static_cast<size_t>(e)];
    sources.clear();
    context.assembler.append_edge_sources(e, sources);
    for (size_t p = 0; p < sources.size() && p < static_cast<size_t>(track.count); ++p) {
      if (travels[static_cast<size_t>(sources[p].dominant())] != 0) {
        marks[static_cast<size_t>(track.first) + p] = kTravellingMark;
      }
    }
  }
  return marks;
}

TravelCosts searched_costs_to_travel(const SynthesisContext& context, double travel_mps, double per_frame,
                                     double transition_penalty, double bridge_penalty) {
  if (!context.tag_costs) return {};
  TravelCosts out;
  out.marks = context.tag_costs->travelling(travel_mps, [&] { return travelling_frames(context, travel_mps); });
  const std::vector<TagMask>& marks = *out.marks;
  const TagCostCache::Key key{0, per_frame, transition_penalty, bridge_penalty, travel_mps};
  out.to_travel = context.tag_costs->get(key, [&] {
    const MotionGraph& graph = *context.graph;
    auto edge_cost = [&](int e) {
      const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      return edge.transition ? transition_price(context, edge, 0, transition_penalty, bridge_penalty) : 0.0;
    };
    auto marks_of = [&](int e) {
      const EdgeTrack& t = context.tracks.edges[static_cast<size_t>(e)];
      return std::span<const TagMask>(marks).subspan(static_cast<size_t>(t.first), static_cast<size_t>(t.count));
    };
    return cost_to_mark(graph, marks_of, kTravellingMark, per_frame, edge_cost);
  });
  return out;
}

}  // namespace mg
