#include "motiongraph/synthesis/rest_endings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/graph/backward_costs.h"

namespace mg {

std::vector<int> RestEnding::frames(const MotionGraph& graph) const {
  std::vector<int> out;
  for (int f = graph.nodes[static_cast<size_t>(node)].frame; f <= last_frame; ++f) out.push_back(f);
  return out;
}

int still_from(const Skeleton& skeleton, const Motion& motion, double fps) {
  const int n = motion.frame_count;
  const int joints = skeleton.joint_count();
  if (n < 2 || joints == 0) return n;
  const std::vector<Vec3> at = world_positions(skeleton, motion);
  // Each step's fastest joint (m/s), then averaged over kStillWindowFrames centred on it.
  std::vector<double> fastest(static_cast<size_t>(n - 1), 0.0);
  for (int f = 0; f + 1 < n; ++f) {
    for (int j = 0; j < joints; ++j) {
      const size_t i = static_cast<size_t>(f) * static_cast<size_t>(joints) + static_cast<size_t>(j);
      fastest[static_cast<size_t>(f)] =
          std::max(fastest[static_cast<size_t>(f)], (at[i + static_cast<size_t>(joints)] - at[i]).norm() * fps);
    }
  }
  const int half = kStillWindowFrames / 2;
  auto averaged = [&](int f) {
    const int lo = std::max(0, f - half), hi = std::min(n - 2, f + half);
    double sum = 0.0;
    for (int g = lo; g <= hi; ++g) sum += fastest[static_cast<size_t>(g)];
    return sum / (hi - lo + 1);
  };
  int from = n - 1;
  while (from > 0 && averaged(from - 1) < kStillJointMps) --from;
  // Standing for at least kMinStillS to the end.
  return n - 1 - from >= std::max(1.0, kMinStillS * fps) ? from : n;
}

RestEndings find_rest_endings(const MotionDatabase& db, const MotionGraph& graph, const MotionAssembler& assembler,
                              std::span<const ContactMask> frame_contacts) {
  RestEndings out;
  out.of_node.assign(static_cast<size_t>(graph.node_count()), -1);
  const int max_lead = static_cast<int>(std::lround(kMaxRestLeadS * db.fps));
  // The frames of a flight longer than a running stride's, each clip's on its own.
  const int max_flight = static_cast<int>(std::lround(kMaxFlightS * db.fps));
  const int landing_penalty = static_cast<int>(std::lround(kLandingRestPenaltyS * db.fps));
  std::vector<char> leaping(frame_contacts.size(), 0);
  for (const DatabaseClip& clip : db.clips) {
    for (int f = clip.first_frame, end = clip.first_frame + clip.frame_count;
         f < end && static_cast<size_t>(f) < frame_contacts.size();) {
      int g = f;
      while (g < end && static_cast<size_t>(g) < frame_contacts.size() && frame_contacts[static_cast<size_t>(g)] == 0) {
        ++g;
      }
      if (g - f > max_flight) std::fill(leaping.begin() + f, leaping.begin() + g, 1);
      f = std::max(g, f + 1);
    }
  }
  // The edges that play one: not taken on the way to rest.
  out.leaps.assign(graph.edges.size(), 0);
  if (!frame_contacts.empty()) {
    std::vector<FrameSource> sources;
    for (int e = 0; e < graph.edge_count(); ++e) {
      sources.clear();
      assembler.append_edge_sources(e, sources);
      for (const FrameSource& source : sources) {
        if (leaping[static_cast<size_t>(source.dominant())] != 0) out.leaps[static_cast<size_t>(e)] = 1;
      }
    }
  }
  int node = 0;  // nodes are sorted by frame, so by clip
  for (int c = 0; c < static_cast<int>(db.clips.size()); ++c) {
    const DatabaseClip& clip = db.clips[static_cast<size_t>(c)];
    const int first = node;
    while (node < graph.node_count() && graph.nodes[static_cast<size_t>(node)].clip == c) ++node;
    if (first == node || clip.frame_count < 2) continue;  // no node in it, or nothing to play
    // Judged over the clip's last kMaxRestLeadS and two seconds (no node further back can rest, and
    // a long clip's every frame would cost forward kinematics at every start of a synthesis).
    const int tail = std::min(clip.frame_count, static_cast<int>(std::lround((kMaxRestLeadS + 2.0) * db.fps)));
    const int still = still_from(db.skeletons[static_cast<size_t>(clip.skeleton)],
                                 clip.motion.slice(clip.frame_count - tail, tail), db.fps);
    if (still >= tail) continue;  // it moves to its end
    const int rests_from = clip.frame_count - tail + still;
    const int rest_frame = clip.first_frame + rests_from;
    // The last frame of a leap before rest_frame: only nodes after it come to rest by slowing down.
    int after_flight = clip.first_frame - 1;
    for (int f = clip.first_frame; f < rest_frame && static_cast<size_t>(f) < leaping.size(); ++f) {
      if (leaping[static_cast<size_t>(f)] != 0) after_flight = f;
    }
    // A leap within kMaxRestLeadS before it stands: it stands from a landing.
    const bool landing = after_flight >= clip.first_frame && rest_frame - after_flight <= max_lead;
    const int penalty = landing ? landing_penalty : 0;
    for (int n = first; n < node; ++n) {
      const int frame = graph.nodes[static_cast<size_t>(n)].frame;
      if (frame <= after_flight || rest_frame - frame > max_lead) continue;
      out.of_node[static_cast<size_t>(n)] = static_cast<int>(out.endings.size());
      out.endings.push_back({n, rest_frame, clip.first_frame + clip.frame_count - 1, penalty});
    }
  }
  return out;
}

std::vector<double> cost_to_rest(const MotionGraph& graph, const RestEndings& endings, double transition_cost,
                                 double bridge_cost, bool penalties) {
  std::vector<double> at_rest(static_cast<size_t>(graph.node_count()), std::numeric_limits<double>::infinity());
  for (const RestEnding& ending : endings.endings) {
    double& c = at_rest[static_cast<size_t>(ending.node)];
    c = std::min(c, penalties ? ending.cost(graph) : static_cast<double>(ending.frames_to_rest(graph)));
  }
  return backward_costs(graph, std::move(at_rest), [&](int e) {
    return endings.leap(e) ? -1.0 : rest_edge_cost(graph.edges[static_cast<size_t>(e)], transition_cost, bridge_cost);
  });
}

RestRoute rest_route(const MotionGraph& graph, const RestEndings& endings, const std::vector<double>& costs, int node,
                     double transition_cost, double bridge_cost, int max_frames) {
  RestRoute route;
  for (int frames = 0; costs[static_cast<size_t>(node)] >= 0.0;) {
    const double target = costs[static_cast<size_t>(node)];
    const RestEnding* here = endings.at(node);
    if (here != nullptr && here->cost(graph) <= target + 1e-9) {
      route.ending = here;
      break;
    }
    if (frames >= max_frames) break;
    int best = -1;
    for (int e = graph.edge_offsets[node]; e < graph.edge_offsets[node + 1] && best < 0; ++e) {
      const GraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      const double to = costs[static_cast<size_t>(edge.to_node)];
      if (to >= 0.0 && !endings.leap(e) && rest_edge_cost(edge, transition_cost, bridge_cost) + to <= target + 1e-9) {
        best = e;
      }
    }
    if (best < 0) break;  // (cannot happen: the node's cost came from one of its edges)
    route.edges.push_back(best);
    frames += graph.edges[static_cast<size_t>(best)].frame_count;
    node = graph.edges[static_cast<size_t>(best)].to_node;
  }
  return route;
}

}  // namespace mg
