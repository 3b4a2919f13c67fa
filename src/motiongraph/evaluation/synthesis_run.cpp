#include "motiongraph/evaluation/synthesis_run.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <ctime>
#include <numbers>

#include <fmt/format.h>

#include "motiongraph/core/transition_rate.h"
#include "motiongraph/database/travel_tags.h"
#include "motiongraph/evaluation/foot_slide_report.h"
#include "motiongraph/evaluation/played_clips.h"
#include "motiongraph/evaluation/path_shortfalls.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/synthesis/assembler.h"

namespace mg {

namespace {

// How many of the database's frames carry one of `mask`'s tags (tag ranges may overlap).
long long clip_frames_with(const MotionDatabase& db, TagMask mask) {
  const std::vector<TagMask> tags = db.frame_tags();
  return std::count_if(tags.begin(), tags.end(), [&](TagMask t) { return (t & mask) != 0; });
}

// CPU seconds this thread has run (the search runs on one thread).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double seconds_since(std::chrono::steady_clock::time_point begin) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
}

// Cleans `motion` as played for `walk`; the report's "cleanup". Why none was made when one was
// asked for is appended to `warnings`.
Result<nlohmann::json> clean_up(const SynthesisContext& context, const SynthesisRunSettings& settings,
                                const Walk& walk, Motion& motion, std::vector<std::string>& warnings) {
  std::string warning;
  auto cleanup = make_cleanup(context, settings, warning);
  if (!warning.empty()) warnings.push_back(std::move(warning));
  if (cleanup) {
    if (auto s = context.clean_up_walk(walk, *cleanup, motion); !s) return s.error();
  }
  return cleanup_report(context, settings, cleanup);
}

}  // namespace

std::optional<FootCleanup> make_cleanup(const SynthesisContext& context, const SynthesisRunSettings& settings,
                                        std::string& warning) {
  if (!settings.cleanup) return std::nullopt;
  auto cleanup = context.foot_cleanup(FootCleanupSettings{});
  if (!cleanup) {
    warning = cleanup.error().message;
    return std::nullopt;
  }
  return std::move(*cleanup);
}

nlohmann::json cleanup_report(const SynthesisContext& context, const SynthesisRunSettings& settings,
                              const std::optional<FootCleanup>& cleanup) {
  if (!cleanup) {
    std::string reason = settings.cleanup_off_reason;
    if (settings.cleanup) {
      auto made = context.foot_cleanup(FootCleanupSettings{});  // what make_cleanup warned of
      reason = made ? std::string("not made") : made.error().message;
    }
    return {{"enabled", false}, {"reason", reason}};
  }
  const FootCleanupStats& s = cleanup->stats();
  return {{"enabled", true},
          {"frames", s.frames},
          {"planted_leg_frames", s.planted_leg_frames},
          {"root_lowered_frames", s.root_lowered_frames},
          {"max_root_drop_m", s.max_root_drop_m},
          {"max_correction_m", s.max_correction_m},
          {"max_ankle_miss_m", s.max_ankle_miss_m},
          {"replants", s.replants},
          {"stepping_leg_frames", s.stepping_leg_frames},
          {"both_stepping_frames", s.both_stepping_frames}};
}

nlohmann::json heading_edit_report(const HeadingEditSettings& settings, const HeadingEditStats& stats) {
  return {{"max_turn_deg_per_m", settings.max_turn_deg_per_m},
          {"turn_distance_m", settings.turn_distance_m},
          {"hold", settings.hold_travel ? "travel" : "facing"},
          {"travel_share", stats.frames > 0 ? stats.travel_share / static_cast<double>(stats.frames) : 0.0},
          {"added_turn_deg", stats.added_turn_rad * 180.0 / std::numbers::pi},
          {"max_rate_deg_per_m", stats.max_rate_deg_per_m}};
}

nlohmann::json path_edit_report(const PathSynthesisSettings& search, const PathSynthesisResult& result) {
  const PathEditStats& e = result.edit;
  nlohmann::json report = {{"enabled", search.edit_path}, {"edited", e.edited}};
  if (!search.edit_path) return report;
  report["max_turn_deg_per_m"] = search.path_edit.max_turn_deg_per_m;
  report["round_corners_m"] = search.path_edit.round_corners_m;
  report["undone"] = result.edit_undone;
  report["limited_share"] = e.limited_share;
  report["max_added_turn_deg"] = e.max_added_turn_deg;
  report["max_shift_m"] = e.max_shift_m;
  return report;
}

nlohmann::json path_segments_report(const SynthesisContext& context, const FloorPath& path,
                                    const PathSynthesisResult& result) {
  assert(result.segment_tag_matches.size() == path.segments().size());
  nlohmann::json segments = nlohmann::json::array();
  for (size_t i = 0; i < path.segments().size(); ++i) {
    const PathSegment& s = path.segments()[i];
    const PathSynthesisResult::SegmentTagMatch& m = result.segment_tag_matches[i];
    const auto known = context.tag_mask(s.tag);  // the path's tags were checked by the synthesis
    const TagMask mask = known ? *known : 0;
    segments.push_back({{"from_m", s.from_m},
                        {"to_m", s.to_m},
                        {"tag", s.tag},
                        {"frames", m.frames},
                        {"tag_match", m.frames > 0 ? nlohmann::json(static_cast<double>(m.matched) / m.frames)
                                                   : nlohmann::json(nullptr)},
                        {"graph_frames", graph_frames_with(context, mask)},
                        {"clip_frames", clip_frames_with(*context.db, mask)}});
  }
  return segments;
}

std::optional<std::string> unplayable_tag(const SynthesisContext& context, const std::string& tag) {
  const auto mask = context.tag_mask(tag);
  if (!mask) return std::nullopt;
  const int graph_frames = graph_frames_with(context, *mask);
  if (graph_frames >= context.db->fps) return std::nullopt;
  const int clip_frames = clip_frames_with(*context.db, *mask);
  if (graph_frames == 0) {
    return fmt::format("'{}', which the graph plays in no frame ({} of its clips' frames carry it; the build kept "
                       "none: `inspect` gives each type's frames before and after pruning)",
                       tag, clip_frames);
  }
  return fmt::format("'{}', which the graph plays in only {} frame{} ({:.1f} s; {} of its clips' frames carry it): "
                     "the motion can hardly carry it (`inspect` gives each type's frames before and after pruning)",
                     tag, graph_frames, graph_frames == 1 ? "" : "s", graph_frames / context.db->fps, clip_frames);
}

std::vector<std::string> segment_warnings(const SynthesisContext& context, const FloorPath& path) {
  std::vector<std::string> out;
  for (const PathSegment& segment : path.segments()) {
    if (auto why = unplayable_tag(context, segment.tag)) {
      out.push_back(fmt::format("the segment {:g}-{:g} m asks for {}", segment.from_m, segment.to_m, *why));
    }
  }
  return out;
}

nlohmann::json rest_report(const SynthesisContext& context, const RestEnding* ending, double at_s) {
  if (ending == nullptr) return nullptr;
  const DatabaseClip& clip = context.db->clips[static_cast<size_t>(context.db->clip_of(ending->last_frame))];
  return {{"at_s", at_s},
          {"clip", clip.name},
          {"clip_frame", ending->rest_frame - clip.first_frame},
          {"held_frame", ending->last_frame - clip.first_frame}};
}

nlohmann::json rests_report(const SynthesisContext& context, const Controller& controller, long long frames) {
  nlohmann::json out = nlohmann::json::array();
  for (size_t i = 0; i < controller.rest_frames().size() && controller.rest_frames()[i] < frames; ++i) {
    out.push_back(rest_report(context, controller.rest_endings()[i],
                              static_cast<double>(controller.rest_frames()[i]) / context.db->fps));
  }
  return out;
}

nlohmann::json starts_report(const SynthesisContext& context, std::span<const StartTaken> starts, long long frames) {
  nlohmann::json out = nlohmann::json::array();
  for (const StartTaken& taken : starts) {
    if (taken.frame >= frames) break;
    const RestStart& start = taken.start;
    const DatabaseClip& clip = context.db->clips[static_cast<size_t>(context.db->clip_of(start.first_frame))];
    out.push_back({{"at_s", static_cast<double>(taken.frame) / context.db->fps},
                   {"clip", clip.name},
                   {"clip_frame", start.first_frame - clip.first_frame},
                   {"node_frame", context.graph->nodes[start.node].frame - clip.first_frame},
                   {"rms_cm", 100.0 * start.rms_m},
                   {"under_way", taken.under_way}});
  }
  return out;
}

nlohmann::json rests_taken_back_report(const SynthesisContext& context, const Controller& controller,
                                       long long frames) {
  nlohmann::json out = nlohmann::json::array();
  for (const long long f : controller.rests_taken_back()) {
    if (f < frames) out.push_back(static_cast<double>(f) / context.db->fps);
  }
  return out;
}

bool stop_means_rest(const SynthesisContext& context, const std::string& tag) {
  return is_stop_tag(tag) && !context.rest().empty() && unplayable_tag(context, tag).has_value();
}

Result<SynthesizedMotion> run_walk_synthesis(const SynthesisContext& context, int from, int to,
                                             const WalkSearchSettings& walk, const SynthesisRunSettings& settings) {
  if (auto s = walk.validate(); !s) return s.error();
  const MotionGraph& graph = *context.graph;
  auto found = find_walk(graph, from, to, walk);
  if (!found) return Error{settings.graph_name, 0, found.error().message, found.error().kind};
  const FloorTransform start = context.placement_facing(from, Vec2::Zero(), Vec2(0.0, -1.0));
  auto motion = assemble_walk(*context.db, graph, found->walk, start, context.assembler.target_skeleton());
  if (!motion) return motion.error();
  SynthesizedMotion out{std::move(*motion), found->walk, {}, {}, {}, {}};
  auto cleanup = clean_up(context, settings, out.walk, out.motion, out.warnings);
  if (!cleanup) return cleanup.error();
  const int transitions = out.walk.transition_count(graph);
  out.report = {{"from", from},
                {"to", to},
                {"cost_function", walk_cost_name(walk.cost)},
                {"seed", walk.seed},
                {"cost", found->cost},
                {"edges", out.walk.edges},
                {"transitions", transitions},
                {"transitions_per_second", transitions_per_second(transitions, out.motion.frame_count, out.motion.fps)},
                {"bridges", count_bridges(graph, out.walk.edges)},
                {"frames", out.motion.frame_count},
                {"fps", out.motion.fps},
                {"expansions", found->expansions},
                {"seconds", seconds_since(settings.begin)},
                {"cleanup", *cleanup},
                {"warnings", out.warnings}};
  out.report["played"] =
      played_clips_json(*context.db, context.walk_sources(out.walk), out.motion.fps, out.motion.frame_count);
  out.report["foot_slide"] = foot_slide_report(context, out.walk, out.motion);
  return out;
}

Result<SynthesizedMotion> run_path_synthesis(const SynthesisContext& context, const FloorPath& path,
                                             const PathSynthesisSettings& search, const SynthesisRunSettings& settings) {
  if (auto s = search.validate(); !s) return s.error();
  const auto search_begin = std::chrono::steady_clock::now();
  const double search_cpu_begin = thread_cpu_seconds();
  auto result = synthesize_path(context, path, search);
  const double search_cpu_seconds = thread_cpu_seconds() - search_cpu_begin;
  const double search_seconds = seconds_since(search_begin);
  if (!result) return Error{settings.graph_name, 0, result.error().message, result.error().kind};
  std::vector<std::string> shortfalls = path_shortfalls(context, path, search, *result);
  SynthesizedMotion out{std::move(result->motion), result->walk, {}, {}, {}, std::move(shortfalls)};
  const Motion& motion = out.motion;
  out.warnings = segment_warnings(context, path);
  auto cleanup = clean_up(context, settings, out.walk, out.motion, out.warnings);
  if (!cleanup) return cleanup.error();
  out.warnings.insert(out.warnings.end(), out.shortfalls.begin(), out.shortfalls.end());
  const double seconds = seconds_since(settings.begin);
  nlohmann::json points = nlohmann::json::array();
  for (const Vec2& p : path.points()) points.push_back({p.x(), p.y()});
  nlohmann::json roots = nlohmann::json::array();
  for (const Vec2& p : result->roots) roots.push_back({std::round(p.x() * 1e4) / 1e4, std::round(p.y() * 1e4) / 1e4});
  const int transitions = out.walk.transition_count(*context.graph);
  out.report = {{"path_length_m", result->path_length_m},
                {"arc_covered_m", result->arc_covered_m},
                {"end_distance_m", result->end_distance_m},
                {"reached_end", result->reached_end},
                {"mean_deviation_m", result->mean_deviation_m},
                {"max_deviation_m", result->max_deviation_m},
                {"graph_mean_deviation_m", result->graph_mean_deviation_m},
                {"graph_max_deviation_m", result->graph_max_deviation_m},
                {"path_edit", path_edit_report(search, *result)},
                {"shortfalls", out.shortfalls},
                {"warnings", out.warnings},
                {"tag_match", result->tag_match},
                {"frames", motion.frame_count},
                {"fps", motion.fps},
                {"duration_s", motion.frame_count / motion.fps},
                {"seconds", seconds},
                {"realtime_factor", seconds > 0.0 ? motion.frame_count / motion.fps / seconds : 0.0},
                {"search_seconds", search_seconds},
                {"search_realtime_factor", search_seconds > 0.0 ? motion.frame_count / motion.fps / search_seconds : 0.0},
                // CPU time of the search: on a shared machine it varies less than the wall time.
                {"search_cpu_seconds", search_cpu_seconds},
                {"search_cpu_realtime_factor",
                 search_cpu_seconds > 0.0 ? motion.frame_count / motion.fps / search_cpu_seconds : 0.0},
                {"searches", result->searches},
                {"expansions", result->expansions},
                {"budget_exhausted_searches", result->budget_exhausted},
                {"attempts", result->attempts},
                {"behind_penalty_m", result->behind_penalty_m},
                {"tag_penalty_m2", result->tag_penalty_m2},
                {"horizon_s", result->horizon_s},
                {"edit_in_search", result->edit_in_search},
                {"anchor_arc", result->anchor_arc},
                {"start_node", out.walk.start_node},
                {"edges", out.walk.edges},
                {"transitions", transitions},
                {"transitions_per_second", transitions_per_second(transitions, motion.frame_count, motion.fps)},
                {"bridges", count_bridges(*context.graph, out.walk.edges)},
                {"segments", path_segments_report(context, path, *result)},
                {"path", points},
                {"roots", roots},
                {"cleanup", *cleanup}};
  out.report["rest"] = rest_report(context, result->rest, result->rest_frame / motion.fps);
  out.report["played"] =
      played_clips_json(*context.db, context.walk_sources(out.walk), out.motion.fps, out.motion.frame_count);
  out.report["foot_slide"] = foot_slide_report(context, out.walk, out.motion);
  return out;
}

Status write_synthesized_motion(const std::string& path, const SynthesisContext& context, const Motion& motion,
                                const Walk& walk, std::vector<ContactMask> contacts,
                                MotionFileSettings settings) {
  if (contacts.empty() && walk.start_node >= 0) contacts = context.walk_contacts(walk);
  const bool with_contacts = !context.frame_contacts.empty() && static_cast<int>(contacts.size()) >= motion.frame_count;
  contacts.resize(static_cast<size_t>(motion.frame_count));
  const PositionsJsonContacts json_contacts{context.feet, contacts};
  if (settings.root_motion) settings.root_motion->forward_axis = context.tracks.forward_axis;
  return write_motion(path, context.assembler.skeleton(), motion, settings, with_contacts ? &json_contacts : nullptr);
}

}  // namespace mg
