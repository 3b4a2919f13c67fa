#include "motiongraph/synthesis/horizon_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

namespace mg {

Status check_horizon_and_commit(double horizon_s, double commit_s, const char* who) {
  if (!(horizon_s > 0.0 && horizon_s <= kMaxHorizonS)) {
    return Error{"", 0, fmt::format("{}: the horizon must be above 0 s and at most {:g} s, not {:g} s", who,
                                    kMaxHorizonS, horizon_s)};
  }
  if (!(commit_s > 0.0 && commit_s <= horizon_s)) {
    return Error{"", 0, fmt::format("{}: the commit must be above 0 s and at most the horizon ({:g} s), not {:g} s",
                                    who, horizon_s, commit_s)};
  }
  return Ok{};
}

Status HorizonSettings::validate() const {
  if (horizon_frames < 1) return Error{"", 0, "the search horizon must be at least one frame"};
  if (max_expansions < 1) return Error{"", 0, "the search needs an expansion budget of at least 1"};
  if (!(time_budget_s >= 0.0)) return Error{"", 0, "the search time budget must be >= 0"};
  if (beam_width < 0 || beam_width > kMaxBeamWidth) {
    return Error{"", 0, fmt::format("the beam width must be from 0 to {}", kMaxBeamWidth)};
  }
  return Ok{};
}

bool FrameCost::add_costs(const PlayedFrames& frames, double bound, double* total, bool* goal) const {
  return add_frame_costs(frames.roots.size(), bound, total, goal, [&](size_t p, bool* reached) {
    return cost(frames.first_frame + static_cast<int>(p), frames.roots[p],
                frames.facings.empty() ? Vec2::Zero() : frames.facings[p], frames.arcs_m[p], frames.tags[p], reached);
  });
}

namespace {

struct Child {
  int edge = 0;
  double cost = 0.0;
  double priority = 0.0;  // cost + the lower bound of what is left: what must beat the best
  bool complete = false;
  bool goal = false;
  SearchState state;
};

// Plays edge e from `state` (whose frames are counted from the search start as `played`),
// adding frame costs to `cost`. Stops early and returns false when cost reaches `bound`.
// Every edge leaving a state shares its placement: the rotation's cosine and sine are computed
// once per state (Rotation) rather than once per edge played.
struct Rotation {
  double c = 1.0, s = 0.0;
  explicit Rotation(double yaw_rad) : c(std::cos(yaw_rad)), s(std::sin(yaw_rad)) {}
};

// The world frames of the edge being played, handed to FrameCost::add_costs; grown to the
// longest edge once, then reused.
struct FrameBuffers {
  bool facings_used = true;
  bool headings = false;  // the facings handed on are the headings (FrameCost::uses_heading)
  std::vector<Vec2> roots, facings;
  std::vector<double> arcs_m;
};

bool play_edge(const MotionGraph& graph, const EdgeTracks& tracks, const FrameCost& frame_cost, int horizon,
               long long played, double bound, int e, const SearchState& from, const Rotation& rotation,
               FrameBuffers& buffers, Child& out) {
  out.edge = e;
  out.state = from;
  out.complete = false;
  out.goal = false;
  SearchState& s = out.state;
  const auto roots = tracks.roots_of(e);
  const auto facings = buffers.headings && !tracks.headings.empty() ? tracks.headings_of(e) : tracks.facings_of(e);
  const auto tags = tracks.tags_of(e);
  if (graph.edges[e].transition && played < horizon) {
    out.cost += frame_cost.transition_cost(graph.edges[e], from);
    if (out.cost >= bound) return false;
  }
  // The placement holds for the whole edge: its rotation once (FloorTransform::rotate).
  const double c = rotation.c, sn = rotation.s;
  auto turned = [&](const Vec2& v) { return Vec2(c * v.x() + sn * v.y(), -sn * v.x() + c * v.y()); };
  const Vec2 shift(s.placement.x_m, s.placement.z_m);
  const size_t count = roots.size();
  if (buffers.roots.size() < count) {
    buffers.roots.resize(count);
    buffers.arcs_m.resize(count);
    if (buffers.facings_used) buffers.facings.resize(count);
  }
  for (size_t p = 0; p < count; ++p) {
    const Vec2 root = turned(roots[p]) + shift;
    if (s.has_last) s.arc_m += (root - s.last_root).norm();
    s.last_root = root;
    s.has_last = true;
    buffers.roots[p] = root;
    buffers.arcs_m[p] = s.arc_m;
  }
  // The frames within the horizon are costed.
  const size_t costed = played >= horizon ? 0 : std::min<size_t>(count, static_cast<size_t>(horizon - played));
  if (costed > 0) {
    if (buffers.facings_used) {
      for (size_t p = 0; p < costed; ++p) buffers.facings[p] = turned(facings[p]);
    }
    const PlayedFrames frames{static_cast<int>(played), std::span(buffers.roots).first(costed),
                              buffers.facings_used ? std::span<const Vec2>(buffers.facings).first(costed)
                                                   : std::span<const Vec2>(),
                              std::span(buffers.arcs_m).first(costed), tags.first(costed)};
    bool goal = false;
    if (!frame_cost.add_costs(frames, bound, &out.cost, &goal)) return false;
    if (goal) out.complete = out.goal = true;
  }
  s.frames += static_cast<long long>(count);
  // s.placement * change, with the rotation already at hand (FloorTransform::operator*).
  const FloorTransform& change = tracks.edges[e].change;
  s.placement = FloorTransform{s.placement.yaw_rad + change.yaw_rad, c * change.x_m + sn * change.z_m + shift.x(),
                               -sn * change.x_m + c * change.z_m + shift.y()};
  s.node = graph.edges[e].to_node;
  const long long after = played + static_cast<long long>(count);
  // (An edge played past the horizon, as advance() plays them, costs nothing.)
  if (after >= horizon && !out.goal && costed > 0) {
    out.cost += frame_cost.terminal_cost(e, costed, buffers.arcs_m[costed - 1], s);
    if (out.cost >= bound) return false;
  }
  if (after >= horizon) out.complete = true;
  out.priority = out.cost;
  if (!out.complete) {
    const int frames_left = static_cast<int>(horizon - after);
    out.priority +=
        frame_cost.remaining_bound(frames_left, s.last_root, s.arc_m) + frame_cost.node_bound(s, frames_left);
    if (out.priority >= bound) return false;
  }
  return true;
}

// The beam search of HorizonSettings::beam_width: partial walks bucketed by frames played.
struct BeamResult {
  std::vector<int> edges;
  double cost = std::numeric_limits<double>::infinity();
  bool goal = false;
  long long expansions = 0;
};

BeamResult beam_search(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start,
                       const FrameCost& frame_cost, int horizon, int width, FrameBuffers& buffers) {
  struct Entry {
    int parent = -1;  // index into `walks`
    int edge = -1;
    Child child;
  };
  // Each walk once, its parent by index; buckets hold (priority, index) so that sorting them
  // reads no walk.
  std::vector<Entry> walks;
  walks.reserve(2 * static_cast<size_t>(width) * static_cast<size_t>(horizon));
  std::vector<std::vector<std::pair<double, int>>> buckets(static_cast<size_t>(horizon));
  BeamResult result;
  int best = -1;
  Entry root;
  root.child.state = start;
  walks.push_back(root);
  buckets[0].emplace_back(0.0, 0);
  std::vector<int> seen_stamp(static_cast<size_t>(graph.node_count()), -1);
  for (int t = 0; t < horizon; ++t) {
    std::vector<std::pair<double, int>>& bucket = buckets[static_cast<size_t>(t)];
    if (bucket.empty()) continue;
    std::sort(bucket.begin(), bucket.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    int kept = 0;
    for (const auto& [priority, w] : bucket) {
      if (kept >= width) break;
      const int node = walks[w].child.state.node;
      if (seen_stamp[node] == t || priority >= result.cost) continue;  // one walk per node
      seen_stamp[node] = t;
      ++kept;
      const Rotation rotation(walks[w].child.state.placement.yaw_rad);
      for (const GraphEdge& edge : graph.out_edges(node)) {
        const int e = static_cast<int>(&edge - graph.edges.data());
        Entry next;
        next.parent = w;
        next.edge = e;
        next.child.cost = walks[w].child.cost;
        ++result.expansions;
        if (!play_edge(graph, tracks, frame_cost, horizon, t, result.cost, e, walks[w].child.state, rotation, buffers,
                       next.child)) {
          continue;
        }
        const int index = static_cast<int>(walks.size());
        if (next.child.complete) {
          result.cost = next.child.cost;
          result.goal = next.child.goal;
          best = index;
        } else {
          // Not complete: it ends before the horizon (an edge plays at least one frame).
          const int arrival = t + std::max(1, graph.edges[e].frame_count);
          if (arrival >= horizon) continue;
          buckets[static_cast<size_t>(arrival)].emplace_back(next.child.priority, index);
        }
        walks.push_back(std::move(next));
      }
    }
    std::vector<std::pair<double, int>>().swap(bucket);
  }
  for (int w = best; w > 0; w = walks[w].parent) result.edges.push_back(walks[w].edge);
  std::reverse(result.edges.begin(), result.edges.end());
  return result;
}

}  // namespace

SearchState advance(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& state, int edge) {
  struct Free final : FrameCost {
    double cost(int, const Vec2&, const Vec2&, double, TagMask, bool*) const override { return 0.0; }
  } free_cost;
  Child child;
  FrameBuffers buffers;
  buffers.facings_used = false;
  play_edge(graph, tracks, free_cost, 0, 0, std::numeric_limits<double>::infinity(), edge, state,
            Rotation(state.placement.yaw_rad), buffers, child);
  return child.state;
}

namespace {

// The first `count` frames `edges` play from `state`, each of an edge's `track` values (its
// facings or roots) as `world` puts it under the edge's placement.
template <class Track, class World>
std::vector<Vec2> walk_values(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& state,
                              std::span<const int> edges, size_t count, Track&& track, World&& world) {
  std::vector<Vec2> values;
  SearchState at = state;
  for (int e : edges) {
    if (values.size() >= count) break;
    for (const Vec2& v : track(e)) {
      if (values.size() >= count) break;
      values.push_back(world(at.placement, v));
    }
    at = advance(graph, tracks, at, e);
  }
  return values;
}

}  // namespace

std::vector<Vec2> walk_facings(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& state,
                               std::span<const int> edges, size_t count) {
  return walk_values(
      graph, tracks, state, edges, count, [&](int e) { return tracks.facings_of(e); },
      [](const FloorTransform& w, const Vec2& f) { return turn(w, f); });
}

std::vector<Vec2> walk_roots(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& state,
                             std::span<const int> edges, size_t count) {
  return walk_values(
      graph, tracks, state, edges, count, [&](int e) { return tracks.roots_of(e); },
      [](const FloorTransform& w, const Vec2& r) { return place(w, r); });
}

HorizonResult horizon_search(const MotionGraph& graph, const EdgeTracks& tracks, const SearchState& start,
                             const FrameCost& frame_cost, const HorizonSettings& settings,
                             std::span<const int> hint) {
  using Clock = std::chrono::steady_clock;
  const auto deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(settings.time_budget_s));
  HorizonResult result;
  struct Level {
    std::vector<Child> children;
    size_t next = 0;
    long long played = 0;
  };
  std::vector<Level> stack;
  std::vector<int> path;
  std::vector<int> greedy;  // the deepest-first partial walk, in case nothing completes
  FrameBuffers buffers;
  buffers.facings_used = frame_cost.uses_facing();
  buffers.headings = frame_cost.uses_heading();

  auto expand = [&](const SearchState& state, double cost, long long played) {
    Level level;
    level.played = played;
    const Rotation rotation(state.placement.yaw_rad);
    for (const GraphEdge& edge : graph.out_edges(state.node)) {
      const int e = static_cast<int>(&edge - graph.edges.data());
      Child child;
      child.cost = cost;
      ++result.expansions;
      if (play_edge(graph, tracks, frame_cost, settings.horizon_frames, played, result.cost, e, state, rotation, buffers,
                    child)) {
        level.children.push_back(std::move(child));
      }
    }
    std::sort(level.children.begin(), level.children.end(),
              [](const Child& a, const Child& b) { return a.priority < b.priority; });
    // Along the hint, its edge goes first.
    const size_t depth = path.size();
    if (depth < hint.size() && std::equal(path.begin(), path.end(), hint.begin())) {
      const auto it = std::find_if(level.children.begin(), level.children.end(),
                                   [&](const Child& c) { return c.edge == hint[depth]; });
      if (it != level.children.end()) std::rotate(level.children.begin(), it, it + 1);
    }
    stack.push_back(std::move(level));
  };

  if (settings.beam_width > 0) {
    BeamResult beam = beam_search(graph, tracks, start, frame_cost, settings.horizon_frames, settings.beam_width, buffers);
    result.expansions += beam.expansions;
    if (!beam.edges.empty()) {
      result.edges = std::move(beam.edges);
      result.cost = beam.cost;
      result.goal_reached = beam.goal;
    }
  }
  expand(start, 0.0, 0);
  long long steps = 0;
  while (!stack.empty()) {
    if (result.expansions >= settings.max_expansions ||
        (settings.time_budget_s > 0.0 && (++steps & 15) == 0 && Clock::now() >= deadline)) {
      result.budget_exhausted = true;
      break;
    }
    Level& level = stack.back();
    if (level.next >= level.children.size()) {
      stack.pop_back();
      if (!path.empty()) path.pop_back();
      continue;
    }
    const Child& child = level.children[level.next++];
    if (child.priority >= result.cost) continue;
    if (child.complete) {
      result.cost = child.cost;
      result.goal_reached = child.goal;
      result.edges = path;
      result.edges.push_back(child.edge);
      continue;
    }
    path.push_back(child.edge);
    if (path.size() > greedy.size() && result.edges.empty()) greedy = path;
    const long long played = level.played + graph.edges[child.edge].frame_count;
    const SearchState state = child.state;
    const double cost = child.cost;
    expand(state, cost, played);
  }
  if (result.edges.empty()) result.edges = greedy;
  return result;
}

}  // namespace mg
