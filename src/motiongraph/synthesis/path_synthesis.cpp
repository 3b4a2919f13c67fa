#include "motiongraph/synthesis/path_synthesis.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace mg {

Status PathSynthesisSettings::validate() const {
  if (!(horizon_s > 0.0) || !(commit_s > 0.0) || commit_s > horizon_s) {
    return Error{"", 0, "path search: need 0 < commit_s <= horizon_s"};
  }
  if (!(tag_penalty_m2 >= 0.0)) return Error{"", 0, "path search: the tag penalty must be >= 0"};
  if (!(transition_penalty_m2 >= 0.0)) return Error{"", 0, "path search: the transition penalty must be >= 0"};
  if (!(min_speed_mps >= 0.0) || !(behind_penalty_m >= 0.0)) {
    return Error{"", 0, "path search: the slowest speed and its penalty must be >= 0"};
  }
  if (max_expansions < 1 || start_candidates < 1) return Error{"", 0, "path search: budgets must be positive"};
  if (progress_retries < 0) return Error{"", 0, "path search: the retries must be >= 0"};
  if (beam_width < 0) return Error{"", 0, "path search: the beam width must be >= 0"};
  return path_edit.validate();
}

namespace {

class PathCost final : public FrameCost {
 public:
  PathCost(const FloorPath& path, const std::vector<TagMask>& segment_masks, double penalty, double max_step,
           double min_step, double behind_penalty, double transition_penalty)
      : path_(path),
        masks_(segment_masks),
        penalty_(penalty),
        max_step_(max_step),
        min_step_(min_step),
        behind_penalty_(behind_penalty),
        transition_penalty_(transition_penalty) {}
  double transition_cost() const override { return transition_penalty_; }
  // Each search starts where the root has covered arc_m.
  void start_search(double arc_m) { search_arc_m_ = arc_m; }
  // Roots are compared with the path where `view` puts them (the edit's move of the last frame
  // committed: where the edited motion is).
  void set_view(const FloorTransform& view) {
    c_ = std::cos(view.yaw_rad);
    s_ = std::sin(view.yaw_rad);
    x_ = view.x_m;
    z_ = view.z_m;
  }
  Vec2 viewed(const Vec2& p) const { return {c_ * p.x() + s_ * p.y() + x_, -s_ * p.x() + c_ * p.y() + z_}; }
  // In m more frames the root moves at most m * max_step and so does the path's point at its
  // arc length, so the root is at least d - 2 m max_step from it (d: the distance now); and
  // the path's end cannot be reached sooner than (length - arc) / max_step frames.
  double remaining_bound(int frames_left, const Vec2& root, double arc_m) const override {
    if (!(max_step_ > 0.0)) return 0.0;
    const double d = (viewed(root) - path_.point_at(arc_m)).norm();
    const double before_end = (path_.length_m() - arc_m) / max_step_;
    double bound = 0.0;
    for (int m = 1; m <= frames_left && m < before_end; ++m) {
      const double gap = d - 2.0 * m * max_step_;
      if (gap <= 0.0) break;
      bound += gap * gap;
    }
    return bound;
  }
  double cost(int frame, const Vec2& root, const Vec2&, double arc_m, TagMask tags, bool* goal) const override {
    int segment = -1;
    return frame_cost(frame, root, arc_m, tags, goal, segment);
  }
  // The same costs as cost(), with the path's point found from the last frame's segment.
  bool add_costs(const PlayedFrames& frames, double bound, double* total, bool* goal) const override {
    int segment = -1;
    return add_frame_costs(frames.roots.size(), bound, total, goal, [&](size_t p, bool* reached) {
      return frame_cost(frames.first_frame + static_cast<int>(p), frames.roots[p], frames.arcs_m[p], frames.tags[p],
                        reached, segment);
    });
  }
  bool uses_facing() const override { return false; }
  TagMask wanted_at(double s) const {
    const auto& segments = path_.segments();
    for (size_t i = segments.size(); i-- > 0;) {
      if (s >= segments[i].from_m && s < segments[i].to_m) return masks_[i];
    }
    return 0;
  }

 private:
  double frame_cost(int frame, const Vec2& root, double arc_m, TagMask tags, bool* goal, int& segment) const {
    double c = (viewed(root) - path_.point_at(arc_m, segment)).squaredNorm();
    // Behind the slowest schedule allowed: metres not covered since the search began.
    const double behind = search_arc_m_ + min_step_ * (frame + 1) - arc_m;
    if (behind > 0.0) c += behind_penalty_ * behind;
    const TagMask wanted = wanted_at(arc_m);
    if (wanted != 0 && (tags & wanted) == 0) c += penalty_;
    if (arc_m >= path_.length_m()) *goal = true;
    return c;
  }

  const FloorPath& path_;
  const std::vector<TagMask>& masks_;
  double penalty_;
  double max_step_;
  double min_step_;
  double behind_penalty_;
  double transition_penalty_;
  double search_arc_m_ = 0.0;
  double c_ = 1.0, s_ = 0.0, x_ = 0.0, z_ = 0.0;
};

// One search of the whole path with these settings, its motion assembled (and edited).
Result<PathSynthesisResult> synthesize_once(const SynthesisContext& context, const FloorPath& path,
                                            const PathSynthesisSettings& settings) {
  const MotionGraph& graph = *context.graph;
  const double fps = context.db->fps;
  std::vector<TagMask> masks;
  for (const PathSegment& segment : path.segments()) {
    auto mask = context.tag_mask(segment.tag);
    if (!mask) return mask.error();
    masks.push_back(*mask);
  }
  if (settings.start_node >= graph.node_count()) {
    return Error{"", 0, fmt::format("start node {} does not exist (the graph has {})", settings.start_node,
                                    graph.node_count())};
  }
  PathCost cost(path, masks, settings.tag_penalty_m2, settings.lower_bound ? context.tracks.max_root_step_m : 0.0,
                settings.min_speed_mps / fps, settings.behind_penalty_m, settings.transition_penalty_m2);
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
    s.placement = context.placement_facing(node, path.points().front(), path.direction_at(0.0));
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
    state.placement = context.placement_facing_edge(first.edges.front(), path.points().front(), path.direction_at(0.0));
  }
  result.start = state.placement;

  // Incremental search until the path's end is reached or the walk takes far too long.
  const long long max_frames = static_cast<long long>((path.length_m() / 0.2 + 10.0) * fps);
  HorizonResult current = std::move(first);
  // The edit in the loop: the committed walk's roots, edited after each commit.
  const bool edit_in_search = settings.edit_path && settings.edit_in_search;
  std::vector<RootPose> played;
  std::vector<Vec2> played_roots;
  std::vector<FloorTransform> moves;
  FloorTransform played_at = result.start;
  size_t played_edges = 0;
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
    if (state.arc_m >= path.length_m()) {
      result.reached_end = true;
      break;
    }
    if (state.frames >= max_frames || current.edges.empty()) break;
    if (edit_in_search) {
      for (; played_edges < result.walk.edges.size(); ++played_edges) {
        context.assembler.append_edge_roots(result.walk.edges[played_edges], played_at, played);
      }
      played_roots.clear();
      for (const RootPose& r : played) played_roots.emplace_back(r.position.x(), r.position.z());
      auto planned = plan_path_edit(played_roots, fps, path, settings.path_edit, moves);
      if (!planned) return planned.error();
      cost.set_view(moves.back());
    }
    cost.start_search(state.arc_m);
    current = horizon_search(graph, context.tracks, state, cost, search, hint);
    tally(current);
  }

  // The motion, cut at the frame whose root completes the path.
  auto motion = assemble_walk(*context.db, graph, result.walk, result.start, context.assembler.target_skeleton());
  if (!motion) return motion.error();
  double arc = 0.0;
  int end = motion->frame_count;
  for (int f = 0; f < motion->frame_count; ++f) {
    const Vec3& p = motion->translations(f)[0];
    const Vec2 root(p.x(), p.z());
    if (f > 0) arc += (root - result.roots.back()).norm();
    result.roots.push_back(root);
    if (arc >= path.length_m()) {
      end = f + 1;
      break;
    }
  }
  result.motion = motion->slice(0, end);
  result.arc_covered_m = arc;
  // Tags of the output frames, from the tracks of the edges played.
  for (int e : result.walk.edges) {
    for (TagMask t : context.tracks.tags_of(e)) result.frame_tags.push_back(t);
  }
  result.frame_tags.push_back(context.frame_tags.empty() ? 0 : context.frame_tags[graph.nodes[result.walk.end_node(graph)].frame]);
  result.frame_tags.resize(static_cast<size_t>(end));
  // The roots' mean and largest distance from the path: as the graph played the walk, then
  // (when the edit moved them) edited.
  auto deviation = [&] {
    double sum = 0.0, most = 0.0;
    for (const Vec2& root : result.roots) {
      const double d = path.distance_to(root);
      sum += d;
      most = std::max(most, d);
    }
    return std::pair{sum / end, most};
  };
  std::tie(result.graph_mean_deviation_m, result.graph_max_deviation_m) = deviation();
  result.mean_deviation_m = result.graph_mean_deviation_m;
  result.max_deviation_m = result.graph_max_deviation_m;
  if (settings.edit_path) {
    auto edited = edit_onto_path(result.motion, path, settings.path_edit);
    if (!edited) return edited.error();
    result.edit = *edited;
    if (edited->edited) {
      for (int f = 0; f < end; ++f) {
        const Vec3& p = result.motion.translations(f)[0];
        result.roots[f] = Vec2(p.x(), p.z());
      }
      std::tie(result.mean_deviation_m, result.max_deviation_m) = deviation();
    }
  }
  double in_segments = 0.0, matched = 0.0;
  arc = 0.0;
  for (int f = 0; f < end; ++f) {
    if (f > 0) arc += (result.roots[f] - result.roots[f - 1]).norm();
    const TagMask wanted = cost.wanted_at(arc);
    if (wanted != 0) {
      in_segments += 1.0;
      matched += (result.frame_tags[f] & wanted) != 0 ? 1.0 : 0.0;
    }
  }
  result.tag_match = in_segments > 0.0 ? matched / in_segments : 1.0;
  result.behind_penalty_m = settings.behind_penalty_m;
  result.edit_in_search = edit_in_search;
  return result;
}

}  // namespace

Result<PathSynthesisResult> synthesize_path(const SynthesisContext& context, const FloorPath& path,
                                            const PathSynthesisSettings& settings) {
  if (auto status = settings.validate(); !status) return status.error();
  auto best = synthesize_once(context, path, settings);
  if (!best) return best.error();
  int attempts = 1, searches = best->searches, exhausted = best->budget_exhausted;
  long long expansions = best->expansions;
  // The retries' (edit in the search, factor on the behind penalty), in order.
  std::vector<std::pair<bool, double>> ladder;
  for (double factor = kProgressRetryFactor; static_cast<int>(ladder.size()) < settings.progress_retries;
       factor *= kProgressRetryFactor) {
    if (settings.edit_path && factor == kProgressRetryFactor) {
      ladder.insert(ladder.end(), {{false, factor}, {true, 1.0}, {true, factor}});
    } else {
      ladder.emplace_back(false, factor);
      if (settings.edit_path) ladder.emplace_back(true, factor);
    }
  }
  ladder.resize(static_cast<size_t>(settings.progress_retries));
  for (size_t retry = 0; retry < ladder.size() && !best->reached_end && settings.behind_penalty_m > 0.0; ++retry) {
    PathSynthesisSettings harder = settings;
    harder.edit_in_search = ladder[retry].first;
    harder.behind_penalty_m = settings.behind_penalty_m * ladder[retry].second;
    auto next = synthesize_once(context, path, harder);
    if (!next) return next.error();
    ++attempts;
    searches += next->searches;
    exhausted += next->budget_exhausted;
    expansions += next->expansions;
    if (next->reached_end || next->arc_covered_m > best->arc_covered_m) best = std::move(next);
  }
  best->attempts = attempts;
  best->searches = searches;
  best->budget_exhausted = exhausted;
  best->expansions = expansions;
  return best;
}

}  // namespace mg
