#include "motiongraph/synthesis/path_synthesis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "motiongraph/core/stop.h"
#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/synthesis/path_cost.h"
#include "motiongraph/synthesis/path_rest.h"

namespace mg {

Status PathSynthesisSettings::validate() const {
  auto refused = [](const std::string& what) { return Error{"", 0, "path search: " + what}; };
  if (auto s = check_horizon_and_commit(horizon_s, commit_s, "path search"); !s) return s;
  auto at_least_zero = [&](double value, const char* what, const char* unit) -> Status {
    if (value >= 0.0 && std::isfinite(value)) return Ok{};
    return refused(fmt::format("{} must be finite and >= 0{}, not {:g}", what, unit, value));
  };
  for (const auto& [value, what, unit] : {std::tuple{tag_penalty_m2, "the tag penalty", " m^2"},
                                          std::tuple{transition_penalty_m2, "the transition penalty", " m^2"},
                                          std::tuple{bridge_penalty_m2, "the bridge penalty", " m^2"},
                                          std::tuple{min_speed_mps, "the slowest speed", " m/s"},
                                          std::tuple{behind_penalty_m, "the behind penalty", " m^2 per metre"},
                                          std::tuple{retry_deviation_m, "the deviation that asks for a retry", " m"}}) {
    if (auto s = at_least_zero(value, what, unit); !s) return s;
  }
  if (max_expansions < 1) {
    return refused(fmt::format("the search budget (expansions) must be at least 1, not {}", max_expansions));
  }
  if (start_candidates < 1) {
    return refused(fmt::format("the start candidates must be at least 1, not {}", start_candidates));
  }
  if (progress_retries < 0 || progress_retries > 100) {
    return refused(fmt::format("the retries must be from 0 to 100, not {}", progress_retries));
  }
  if (!(retry_tag_match >= 0.0 && retry_tag_match <= 1.0)) {
    return refused(fmt::format("the tag match that asks for a retry must be from 0 to 1, not {:g}", retry_tag_match));
  }
  if (!(retry_horizon_s == 0.0 || (retry_horizon_s >= commit_s && retry_horizon_s <= kMaxHorizonS))) {
    return refused(fmt::format("the retries' horizon must be 0 (the first search's) or from the commit ({:g} s) to "
                               "{:g} s, not {:g} s",
                               commit_s, kMaxHorizonS, retry_horizon_s));
  }
  if (beam_width < 0 || beam_width > kMaxBeamWidth) {
    return refused(fmt::format("the beam width must be from 0 to {}, not {}", kMaxBeamWidth, beam_width));
  }
  if (!(tag_lookahead >= 0.0 && tag_lookahead <= 1.0)) {
    return refused(fmt::format("the tag lookahead must be from 0 to 1, not {:g}", tag_lookahead));
  }
  if (start_node < -1) return refused(fmt::format("the start node must be >= 0, not {}", start_node));
  return path_edit.validate();
}

Status check_segment_tags(const SynthesisContext& context, const FloorPath& path, const std::string& path_file) {
  for (const PathSegment& segment : path.segments()) {
    if (auto mask = context.tag_mask(segment.tag); !mask) {
      if (!path_file.empty()) return Error{path_file, 0, mask.error().message};
      return Error{"", 0, fmt::format("--segment {}:{:g}-{:g}: {}", segment.tag, segment.from_m, segment.to_m,
                                      mask.error().message)};
    }
  }
  return Ok{};
}

int graph_frames_with(const SynthesisContext& context, TagMask mask) {
  const MotionGraph& graph = *context.graph;
  int count = 0;
  for (int e = 0; e < graph.edge_count(); ++e) {
    if (graph.edges[e].transition) continue;
    for (TagMask tags : context.tracks.tags_of(e)) count += (tags & mask) != 0 ? 1 : 0;
  }
  return count;
}

double typical_speed_mps(const SynthesisContext& context, TagMask mask) {
  std::vector<double> steps;
  const MotionGraph& graph = *context.graph;
  const EdgeTracks& tracks = context.tracks;
  for (int e = 0; e < graph.edge_count(); ++e) {
    if (graph.edges[e].transition) continue;
    const auto roots = tracks.roots_of(e);
    const auto tags = tracks.tags_of(e);
    for (size_t p = 0; p + 1 < roots.size(); ++p) {
      if ((tags[p] & mask) != 0) steps.push_back((roots[p + 1] - roots[p]).norm());
    }
    // The last frame's step: on to the next frame of its clip, the first of the piece leaving
    // the node it reaches (pieces are short on a dense graph: subject 16's average 1.9 frames).
    if (roots.empty() || (tags.back() & mask) == 0) continue;
    for (const GraphEdge& next : graph.out_edges(graph.edges[e].to_node)) {
      const int f = static_cast<int>(&next - graph.edges.data());
      if (next.transition || tracks.edges[f].count == 0) continue;
      const Vec2& first = tracks.roots_of(f).front();
      const Vec3 placed = tracks.edges[e].change.apply(Vec3(first.x(), 0.0, first.y()));
      steps.push_back((Vec2(placed.x(), placed.z()) - roots.back()).norm());
      break;
    }
  }
  if (steps.empty()) return 0.0;
  auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle * context.db->fps;
}

std::vector<double> slowest_seconds(const SynthesisContext& context, const FloorPath& path, double min_speed_mps) {
  // Each tag's typical speed once, however many segments ask for it.
  std::map<std::string, double> by_tag;
  std::vector<double> speeds;  // per segment, then where none is
  for (const PathSegment& segment : path.segments()) {
    auto [at, made] = by_tag.try_emplace(segment.tag, min_speed_mps);
    if (made) {
      auto mask = context.tag_mask(segment.tag);
      const double typical = mask ? typical_speed_mps(context, *mask) : 0.0;
      if (typical > 0.0) at->second = std::min(min_speed_mps, typical);
    }
    speeds.push_back(at->second);
  }
  speeds.push_back(min_speed_mps);
  std::vector<double> seconds(speeds.size(), 1.0);
  const auto spans = path.segment_spans();
  for (size_t i = 0; i < spans.size() && spans[i].from_m < path.length_m(); ++i) {
    const double to = i + 1 < spans.size() ? std::min(spans[i + 1].from_m, path.length_m()) : path.length_m();
    const size_t owner = spans[i].segment < 0 ? speeds.size() - 1 : static_cast<size_t>(spans[i].segment);
    seconds[owner] += (to - spans[i].from_m) / speeds[owner];
  }
  return seconds;
}

namespace {

// The tag bits each of the path's segments asks the search for. A segment asking for a type the
// graph plays in no frame (its frames pruned away) asks for nothing (0): no walk can carry it,
// and pricing every frame there alike held the walk back (CMU 49 asked to run round a figure 8
// took 194 s over its run half, walking). Fails on a tag the graph does not know.
Result<std::vector<TagMask>> asked_masks(const SynthesisContext& context, const FloorPath& path) {
  std::vector<TagMask> masks;
  for (const PathSegment& segment : path.segments()) {
    auto mask = context.tag_mask(segment.tag);
    if (!mask) return mask.error();
    masks.push_back(graph_frames_with(context, *mask) > 0 ? *mask : 0);
  }
  return masks;
}

// Of the frames within kEndReachedM of the path's length along it (`arcs`: followed_arcs of
// `roots`) and near its last point (within kEndReachedDistanceM, or kEndReachedShare of its
// length), the first furthest along; -1 when no frame is both.
int end_frame(const FloorPath& path, std::span<const Vec2> roots, std::span<const double> arcs) {
  const double near = std::max(kEndReachedDistanceM, kEndReachedShare * path.length_m());
  int best = -1;
  for (size_t f = 0; f < arcs.size(); ++f) {
    if (arcs[f] < path.length_m() - kEndReachedM || (roots[f] - path.points().back()).norm() > near) continue;
    if (best < 0 || arcs[f] > arcs[static_cast<size_t>(best)]) best = static_cast<int>(f);
  }
  return best;
}

// The motion of a searched walk (result.walk from result.start): assembled, edited onto the path
// (or left as played where the edit takes it further off), cut at the frame that reaches the end
// when `cut_at_end` (the walk then keeps the edges that play the frames kept), and judged: roots,
// deviations, how far along it got, its frames' tags and the segments' matches.
Status finish_walk(const SynthesisContext& context, const FloorPath& path, const std::vector<TagMask>& masks,
                   const PathSynthesisSettings& settings, bool cut_at_end, PathSynthesisResult& result) {
  // The motion (edited), cut at the frame that reaches the path's end.
  const MotionGraph& graph = *context.graph;
  auto motion = assemble_walk(*context.db, graph, result.walk, result.start, context.assembler.target_skeleton());
  if (!motion) return motion.error();
  auto roots_of = [](const Motion& m) {
    std::vector<Vec2> roots;
    for (int f = 0; f < m.frame_count; ++f) roots.emplace_back(m.translations(f)[0].x(), m.translations(f)[0].z());
    return roots;
  };
  const std::vector<Vec2> graph_roots = roots_of(*motion);
  // Each root's distance from the path, found once: for the edit's undoing and the deviations.
  auto distances_of = [&](std::span<const Vec2> roots) {
    std::vector<double> distances;
    distances.reserve(roots.size());
    for (const Vec2& p : roots) distances.push_back(path.distance_to(p));
    return distances;
  };
  auto mean_of = [](std::span<const double> values) {
    double sum = 0.0;
    for (double v : values) sum += v;
    return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
  };
  const std::vector<double> graph_distances = distances_of(graph_roots);
  std::vector<Vec2> edited_roots;
  std::vector<double> edited_distances;
  if (settings.edit_path) {
    Motion as_played = *motion;
    auto edited = edit_onto_path(*motion, path, settings.path_edit);
    if (!edited) return edited.error();
    result.edit = *edited;
    if (result.edit.edited) {
      edited_roots = roots_of(*motion);
      edited_distances = distances_of(edited_roots);
      if (mean_of(edited_distances) > mean_of(graph_distances)) {
        *motion = std::move(as_played);
        result.edit = PathEditStats{};
        result.edit_undone = true;
      }
    }
  }
  result.roots = result.edit.edited ? std::move(edited_roots) : graph_roots;
  // Up to the frame that reaches the end, when one does; all of it when the walk gave up short
  // of the end (what it did is shown, however little it got along).
  std::vector<double> arcs = path.followed_arcs(result.roots);
  const int reaching = end_frame(path, result.roots, arcs);
  result.reached_end = reaching >= 0;
  const int end = result.reached_end && cut_at_end ? reaching + 1 : motion->frame_count;
  result.motion = motion->slice(0, end);
  // The walk: the edges that play those frames (the search may have gone on past them).
  if (result.walk.rest_frames.empty()) {
    long long played_frames = 1;
    size_t kept_edges = 0;
    while (kept_edges < result.walk.edges.size() && played_frames < end) {
      played_frames += graph.edges[result.walk.edges[kept_edges++]].frame_count;
    }
    result.walk.edges.resize(kept_edges);
  }
  result.roots.resize(static_cast<size_t>(end));
  arcs.resize(static_cast<size_t>(end));
  result.arc_covered_m = arcs.empty() ? 0.0 : *std::max_element(arcs.begin(), arcs.end());
  result.end_distance_m = end > 0 ? (result.roots.back() - path.points().back()).norm() : path.length_m();
  // Tags of the output frames, from the tracks of the edges played (and the frames played at rest).
  result.frame_tags = context.walk_tags(result.walk);
  result.frame_tags.resize(static_cast<size_t>(end));
  // The roots' mean and largest distance from the path: as the graph played the walk, then
  // (when the edit moved them) edited.
  auto deviation = [&](std::span<const double> distances) {
    const auto kept = distances.first(static_cast<size_t>(end));
    return std::pair{mean_of(kept), kept.empty() ? 0.0 : *std::max_element(kept.begin(), kept.end())};
  };
  std::tie(result.graph_mean_deviation_m, result.graph_max_deviation_m) = deviation(graph_distances);
  if (result.edit.edited) {
    std::tie(result.mean_deviation_m, result.max_deviation_m) = deviation(edited_distances);
  } else {
    result.mean_deviation_m = result.graph_mean_deviation_m;
    result.max_deviation_m = result.graph_max_deviation_m;
  }
  const auto& segments = path.segments();
  result.segment_tag_matches.assign(segments.size(), {});
  int in_segments = 0, matched = 0;
  for (int f = 0; f < end; ++f) {
    const int i = path.segment_at(arcs[f]);  // as the search asks (PathCost::wanted_at)
    if (i < 0) continue;
    const bool carries = (result.frame_tags[f] & masks[static_cast<size_t>(i)]) != 0;
    ++result.segment_tag_matches[static_cast<size_t>(i)].frames;
    result.segment_tag_matches[static_cast<size_t>(i)].matched += carries ? 1 : 0;
    ++in_segments;
    matched += carries ? 1 : 0;
  }
  result.tag_match = in_segments > 0 ? static_cast<double>(matched) / in_segments : 1.0;
  return Ok{};
}

// One search of the whole path with these settings, its motion assembled (and edited); `masks`:
// asked_masks().
Result<PathSynthesisResult> synthesize_once(const SynthesisContext& context, const FloorPath& path,
                                            const std::vector<TagMask>& masks, const PathSynthesisSettings& settings,
                                            int attempt) {
  const MotionGraph& graph = *context.graph;
  const double fps = context.db->fps;
  if (settings.start_node >= graph.node_count()) {
    return Error{"", 0, fmt::format("start node {} does not exist (the graph has {})", settings.start_node,
                                    graph.node_count())};
  }
  PathCost cost(context, path, masks, settings);
  HorizonSettings search;
  search.horizon_frames = std::max(1, static_cast<int>(std::lround(settings.horizon_s * fps)));
  search.max_expansions = settings.max_expansions;
  search.beam_width = settings.beam_width;
  const int commit_frames = std::max(1, static_cast<int>(std::lround(settings.commit_s * fps)));

  PathSynthesisResult result;
  result.path_length_m = path.length_m();
  auto start_state = [&](int node) {
    SearchState s;
    s.node = node;
    s.placement = context.placement_heading(node, path.points().front(), path.direction_at(0.0));
    return s;
  };

  // The start node: the cheapest first search among candidates.
  std::vector<int> candidates;
  if (settings.start_node >= 0) {
    candidates.push_back(settings.start_node);
  } else {
    const TagMask wanted = cost.wanted_at(0.0);
    auto tags_at = [&](int n) {
      const auto out = graph.out_edges(n);
      return context.tracks.tags_of(static_cast<int>(&out.front() - graph.edges.data())).front();
    };
    std::vector<int> eligible;
    for (int n = 0; n < graph.node_count(); ++n) {
      if (wanted == 0 || (tags_at(n) & wanted) != 0) eligible.push_back(n);
    }
    if (eligible.empty()) {
      for (int n = 0; n < graph.node_count(); ++n) eligible.push_back(n);
    }
    // Spread over the graph and over its kinds of motion: each set of tags gets its share of
    // the candidates and at least one, so that a small motion type (running, beside hours of
    // walking) is tried as a start too.
    std::map<TagMask, std::vector<int>> kinds;
    for (int n : eligible) kinds[tags_at(n)].push_back(n);
    const double share = static_cast<double>(settings.start_candidates) / static_cast<double>(eligible.size());
    for (const auto& [tags, nodes] : kinds) {
      const auto wanted_count = static_cast<size_t>(std::lround(share * static_cast<double>(nodes.size())));
      const size_t count = std::clamp<size_t>(wanted_count, 1, nodes.size());
      for (size_t i = 0; i < count; ++i) candidates.push_back(nodes[i * nodes.size() / count]);
    }
  }
  // Candidates are compared on a quarter of the budget each, and a quarter of the beam (which
  // spends its width x out-degree x horizon edges whatever the budget): they only pick the
  // start. The chosen one's first walk is then searched with the whole budget and beam.
  HorizonSettings sample = search;
  sample.max_expansions = std::max<long long>(1, search.max_expansions / 4);
  if (search.beam_width > 0) sample.beam_width = std::max(1, search.beam_width / 4);
  auto tally = [&](const HorizonResult& r) {
    result.expansions += r.expansions;
    ++result.searches;
    result.budget_exhausted += r.budget_exhausted ? 1 : 0;
  };
  HorizonResult first;
  cost.start_search(0.0);
  for (int node : candidates) {
    if (auto s = check_stop(settings.stop); !s) return s.error();
    HorizonResult r = horizon_search(graph, context.tracks, start_state(node), cost,
                                     candidates.size() > 1 ? sample : search);
    tally(r);
    if (r.cost < first.cost || first.edges.empty()) {
      first = std::move(r);
      result.walk.start_node = node;
    }
  }
  if (candidates.size() > 1) {
    first = horizon_search(graph, context.tracks, start_state(result.walk.start_node), cost, search);
    tally(first);
  }
  SearchState state = start_state(result.walk.start_node);
  if (!first.edges.empty()) {
    state.placement = context.placement_heading_edge(first.edges.front(), path.points().front(), path.direction_at(0.0));
  }
  result.start = state.placement;

  // Incremental search until the path's end is reached or the walk takes far too long.
  const long long max_frames = static_cast<long long>((path.length_m() / 0.2 + 10.0) * fps);
  HorizonResult current = std::move(first);
  // The committed walk's roots on the floor as played, and (with the edit) the moves the edit
  // gives them: after each commit with the edit in the search, and wherever the search's arc
  // says the path is done.
  const bool edit_in_search = settings.edit_path && settings.edit_in_search;
  std::vector<RootPose> played;  // one edge's, on the way to played_roots
  std::vector<Vec2> played_roots;
  std::vector<FloorTransform> moves;
  FloorTransform played_at = result.start;
  size_t played_edges = 0;
  auto play_new_edges = [&] {
    for (; played_edges < result.walk.edges.size(); ++played_edges) {
      played.clear();
      context.assembler.append_edge_roots(result.walk.edges[played_edges], played_at, played);
      for (const RootPose& r : played) played_roots.emplace_back(r.position.x(), r.position.z());
    }
  };
  // The path the edit steers for, rounded once for all the plans below.
  const FloorPath rounded =
      settings.edit_path ? round_corners(path, settings.path_edit.round_corners_m) : FloorPath{};
  auto play_and_plan = [&]() -> Status {
    play_new_edges();
    if (!settings.edit_path) return Ok{};
    auto planned = plan_path_edit(played_roots, fps, rounded, settings.path_edit, moves);
    if (!planned) return planned.error();
    return Ok{};
  };
  // How far along the path the motion made of the walk so far gets (edited, when it is).
  auto delivered_arc = [&] {
    std::vector<Vec2> roots = played_roots;
    if (settings.edit_path) {
      for (size_t f = 0; f < roots.size(); ++f) {
        const Vec3 p = moves[f].apply(Vec3(roots[f].x(), 0.0, roots[f].y()));
        roots[f] = Vec2(p.x(), p.z());
      }
    }
    const std::vector<double> arcs = path.followed_arcs(roots);
    return arcs.empty() ? 0.0 : arcs.back();
  };
  double last_check_arc = -1.0;
  double followed = 0.0;
  size_t followed_frames = 0;
  int end_checks = 0;
  constexpr int kMaxEndChecks = 16;  // near the end each goes on by a step or less
  while (true) {
    long long committed = 0;
    size_t used = 0;
    for (int e : current.edges) {
      state = advance(graph, context.tracks, state, e);
      result.walk.edges.push_back(e);
      ++used;
      committed += graph.edges[e].frame_count;
      if (state.arc_m >= path.length_m() || committed >= commit_frames) break;
    }
    std::vector<int> hint(current.edges.begin() + static_cast<std::ptrdiff_t>(used), current.edges.end());
    if (!settings.warm_start) hint.clear();
    if (settings.anchor_arc && state.arc_m < path.length_m()) {
      // The next search starts from the way along the path the walk has come, not from the
      // distance its root travelled.
      play_new_edges();
      std::vector<Vec2> viewed;
      for (size_t f = followed_frames; f < played_roots.size(); ++f) viewed.push_back(cost.viewed(played_roots[f]));
      if (!viewed.empty()) followed = path.followed_arcs(viewed, 1.0, followed_frames == 0 ? -1.0 : followed).back();
      followed_frames = played_roots.size();
      state.arc_m = followed;
    }
    if (state.arc_m >= path.length_m()) {
      // The root has travelled the path's length, but sway, shuffles and steps aside count in
      // that and not in how far along the path the motion gets (nor in how far the edit, which
      // follows the motion's smoothed path, takes it): the search goes on from the arc the
      // motion reaches, seeing the walk where the edit puts it, until it reaches the end or
      // stops getting further.
      if (auto status = play_and_plan(); !status) return status.error();
      const double reached = delivered_arc();
      if (reached >= path.length_m() - kEndReachedM || reached <= last_check_arc || ++end_checks > kMaxEndChecks) {
        break;
      }
      last_check_arc = reached;
      state.arc_m = reached;
      if (settings.edit_path) cost.set_view(moves.back());
    }
    if (state.frames >= max_frames || current.edges.empty()) break;
    if (edit_in_search) {
      if (auto status = play_and_plan(); !status) return status.error();
      cost.set_view(moves.back());
    }
    if (auto s = check_stop(settings.stop); !s) return s.error();
    cost.start_search(state.arc_m);
    current = horizon_search(graph, context.tracks, state, cost, search, hint);
    tally(current);
    if (settings.searched) settings.searched(std::min(state.arc_m, path.length_m()), attempt);
  }

  if (auto finished = finish_walk(context, path, masks, settings, true, result); !finished) return finished.error();
  result.behind_penalty_m = settings.behind_penalty_m;
  result.tag_penalty_m2 = settings.tag_penalty_m2;
  result.horizon_s = settings.horizon_s;
  result.edit_in_search = edit_in_search;
  result.anchor_arc = settings.anchor_arc;
  return result;
}

// synthesize_path without rest at the end: the search, and its retries.
Result<PathSynthesisResult> search_path(const SynthesisContext& context, const FloorPath& path,
                                        const PathSynthesisSettings& settings) {
  auto masks = asked_masks(context, path);
  if (!masks) return masks.error();
  auto best = synthesize_once(context, path, *masks, settings, 1);
  if (!best) return best.error();
  int attempts = 1, searches = best->searches, exhausted = best->budget_exhausted;
  long long expansions = best->expansions;
  // The retries, in order, each looking retry_horizon_s ahead: first the same search (when that
  // horizon is another), then the arc corrected as the walk goes (when it is not already), then
  // the behind penalty 4x; with the edit, the edit in the search at the penalty given and at 4x;
  // then 16x, 64x, ... with and without the edit in the search.
  struct Rung {
    bool anchor_arc = false;
    bool edit_in_search = false;
    double factor = 1.0;
  };
  const double retry_horizon_s = settings.retry_horizon_s > 0.0 ? settings.retry_horizon_s : settings.horizon_s;
  std::vector<Rung> ladder;
  if (retry_horizon_s != settings.horizon_s) ladder.push_back({settings.anchor_arc, settings.edit_in_search, 1.0});
  if (!settings.anchor_arc) ladder.push_back({true, false, 1.0});
  for (double factor = kProgressRetryFactor; static_cast<int>(ladder.size()) < settings.progress_retries;
       factor *= kProgressRetryFactor) {
    ladder.push_back({settings.anchor_arc, false, factor});
    if (!settings.edit_path) continue;
    if (factor == kProgressRetryFactor) ladder.push_back({settings.anchor_arc, true, 1.0});
    ladder.push_back({settings.anchor_arc, true, factor});
  }
  ladder.resize(static_cast<size_t>(settings.progress_retries));
  // Dawdled: slower on average, in a segment or where none is, than the slowest speed asked for
  // (min_speed_mps, or a slower motion type's typical speed in a segment asking for it:
  // slowest_seconds), as a walk does that loops in place beside the path, its edit following it,
  // where the type asked for would take it off the path within the horizon. Good enough: the end
  // reached, not dawdling, within retry_deviation_m of the path. Better: the end reached, then
  // not dawdling, then the least deviation; short of the end, the furthest along.
  const std::vector<double> slowest =
      settings.min_speed_mps > 0.0 ? slowest_seconds(context, path, settings.min_speed_mps) : std::vector<double>{};
  // The first span the walk dawdled in (a segment's index; segments().size(): where none is) and
  // the seconds it took there; -1 when it did not dawdle.
  auto dawdling = [&](const PathSynthesisResult& r) -> std::pair<int, double> {
    if (slowest.empty()) return {-1, 0.0};
    const double fps = context.db->fps;
    int in_segments = 0;
    for (size_t i = 0; i < r.segment_tag_matches.size(); ++i) {
      in_segments += r.segment_tag_matches[i].frames;
      const double seconds = r.segment_tag_matches[i].frames / fps;
      if (seconds > slowest[i]) return {static_cast<int>(i), seconds};
    }
    const double seconds = (r.motion.frame_count - in_segments) / fps;
    if (seconds > slowest.back()) return {static_cast<int>(r.segment_tag_matches.size()), seconds};
    return {-1, 0.0};
  };
  auto dawdled = [&](const PathSynthesisResult& r) { return dawdling(r).first >= 0; };
  // Missed: segments of kTagMissMinSeconds or more asking for a motion type (not a modifier:
  // a stop or a turn is how a motion goes) the graph plays, whose frames carry it less than
  // retry_tag_match of the time; never with no tag penalty to raise.
  std::vector<bool> judged(path.segments().size(), false);
  for (size_t i = 0; i < judged.size() && settings.tag_penalty_m2 > 0.0; ++i) {
    judged[i] = (*masks)[i] != 0 && !is_modifier_tag(path.segments()[i].tag);
  }
  auto misses = [&](const PathSynthesisResult& r, size_t i) {
    const auto& m = r.segment_tag_matches[i];
    return settings.retry_tag_match > 0.0 && judged[i] && m.frames >= kTagMissMinSeconds * context.db->fps &&
           m.matched < settings.retry_tag_match * m.frames;
  };
  auto missed = [&](const PathSynthesisResult& r) {
    int count = 0;
    for (size_t i = 0; i < r.segment_tag_matches.size() && i < judged.size(); ++i) count += misses(r, i) ? 1 : 0;
    return count;
  };
  auto within = [&](const PathSynthesisResult& r) {
    return settings.retry_deviation_m <= 0.0 || r.mean_deviation_m <= settings.retry_deviation_m;
  };
  auto good = [&](const PathSynthesisResult& r) { return r.reached_end && !dawdled(r) && within(r) && missed(r) == 0; };
  auto better = [&](const PathSynthesisResult& r, const PathSynthesisResult& than) {
    if (r.reached_end != than.reached_end) return r.reached_end;
    if (!r.reached_end) return r.arc_covered_m > than.arc_covered_m;
    if (dawdled(r) != dawdled(than)) return !dawdled(r);
    if (within(r) != within(than)) return within(r);
    if (within(r) && missed(r) != missed(than)) return missed(r) < missed(than);
    return r.mean_deviation_m < than.mean_deviation_m;
  };
  double tag_factor = 1.0;
  for (size_t retry = 0; retry < ladder.size() && !good(*best) && settings.behind_penalty_m > 0.0; ++retry) {
    // The tag is priced higher, 4x the last time, only where it is all that is wrong: the end
    // reached, not dawdling, close to the path (a walk held up in a segment misses its type too,
    // and the rungs that push it on are searched at the penalty given). A type the graph keeps
    // few frames of may come only at a high price with a later rung's way (subject 16 at 1.6 cm,
    // a run round a circle: 5 % of the run half at 4x and 16x, 88 % at 256x with the edit in
    // the search), so it is chased through every retry.
    const bool for_tags = best->reached_end && !dawdled(*best) && within(*best) && missed(*best) > 0;
    if (for_tags) tag_factor *= kProgressRetryFactor;
    PathSynthesisSettings harder = settings;
    harder.anchor_arc = ladder[retry].anchor_arc;
    harder.edit_in_search = ladder[retry].edit_in_search;
    harder.behind_penalty_m = settings.behind_penalty_m * ladder[retry].factor;
    harder.tag_penalty_m2 = settings.tag_penalty_m2 * (for_tags ? tag_factor : 1.0);
    harder.horizon_s = retry_horizon_s;
    auto next = synthesize_once(context, path, *masks, harder, attempts + 1);
    if (!next) return next.error();
    ++attempts;
    searches += next->searches;
    exhausted += next->budget_exhausted;
    expansions += next->expansions;
    if (better(*next, *best)) best = std::move(next);
  }
  std::tie(best->dawdled_in, best->dawdled_s) = dawdling(*best);
  if (best->dawdled_in >= 0) best->dawdle_limit_s = slowest[static_cast<size_t>(best->dawdled_in)];
  for (size_t i = 0; i < best->segment_tag_matches.size() && i < judged.size(); ++i) {
    if (misses(*best, i)) best->missed_segments.push_back(static_cast<int>(i));
  }
  best->attempts = attempts;
  best->searches = searches;
  best->budget_exhausted = exhausted;
  best->expansions = expansions;
  return best;
}

}  // namespace

Result<PathSynthesisResult> synthesize_path(const SynthesisContext& context, const FloorPath& path,
                                            const PathSynthesisSettings& settings) {
  if (auto status = settings.validate(); !status) return status.error();
  if (!settings.rest_at_end) return search_path(context, path, settings);
  if (context.rest().empty()) {
    return Error{"", 0, "the path cannot end at rest: no clip of the graph ends standing still (every joint slower "
                        "than 0.5 m/s to its end)"};
  }
  const MotionGraph& graph = *context.graph;
  auto masks = asked_masks(context, path);
  if (!masks) return masks.error();
  // Each ending's travel to standing, for every way to rest measured below.
  const std::vector<double> travel = rest_ending_travel(context);
  // The path searched from `start_settings`, then cut where its way to rest stands nearest the end.
  auto at_rest = [&](const PathSynthesisSettings& start_settings) -> Result<PathSynthesisResult> {
    auto searched = search_path(context, path, start_settings);
    if (!searched) return searched.error();
    const PathRestWay way =
        nearest_rest_way(context, path, searched->walk, searched->start, searched->roots, travel);
    if (way.ending == nullptr) return Error{"", 0, "the path cannot end at rest: no way to rest from its end"};
    PathSynthesisResult result = std::move(*searched);
    result.walk.edges.resize(way.kept_edges);
    result.walk.edges.insert(result.walk.edges.end(), way.edges.begin(), way.edges.end());
    const long long before_ending = result.walk.frame_count(graph);
    result.walk.rest_frames = way.ending->frames(graph);
    result.edit = {};
    result.edit_undone = false;
    if (auto finished = finish_walk(context, path, *masks, start_settings, false, result); !finished) {
      return finished.error();
    }
    result.path_length_m = path.length_m();
    result.rest = way.ending;
    result.rest_frame = static_cast<int>(before_ending + way.ending->frames_to_rest(graph));
    return result;
  };
  auto best = at_rest(settings);
  if (!best || best->end_distance_m <= kEndReachedM || settings.start_node >= 0) return best;
  // Standing far from the end: a path shorter than the way to rest from where its walk starts.
  // Started at the node of a clip that stops whose travel to standing is nearest the path's length
  // (a landing's counting kRestLandingM more), the kRestStarts nearest tried.
  const RestEndings& rest = context.rest();
  std::vector<size_t> order(travel.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto miss = [&](size_t i) {
    return std::abs(travel[i] - path.length_m()) + (rest.endings[i].penalty_frames > 0 ? kRestLandingM : 0.0);
  };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return miss(a) < miss(b); });
  for (size_t k = 0; k < std::min<size_t>(order.size(), kRestStarts); ++k) {
    PathSynthesisSettings started = settings;
    started.start_node = rest.endings[order[k]].node;
    auto tried = at_rest(started);
    if (!tried) return tried.error();
    if (tried->end_distance_m < best->end_distance_m) best = std::move(tried);
  }
  return best;
}

}  // namespace mg
