#include "studio/studio_api.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <exception>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "motiongraph/core/json_text.h"
#include "motiongraph/core/text.h"
#include "motiongraph/core/transition_rate.h"
#include "motiongraph/database/travel_tags.h"
#include "motiongraph/evaluation/foot_slide_report.h"
#include "motiongraph/evaluation/played_clips.h"
#include "motiongraph/evaluation/path_shortfalls.h"
#include "motiongraph/evaluation/synthesis_run.h"
#include "motiongraph/export/positions_json.h"
#include "motiongraph/graph/clip_coverage.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg::studio {

namespace {

using nlohmann::json;

// A request that cannot be answered: its status and one line saying why. Thrown inside the
// router only, and always caught by StudioApi::handle.
struct ApiError {
  int status = 400;
  std::string message;
  std::string allow = {};  // a 405's: the methods the path takes
};

ApiResponse json_response(const json& body, int status = 200) {
  ApiResponse r;
  r.status = status;
  r.body = json_text(body);
  return r;
}

ApiResponse error_response(const ApiError& e) {
  ApiResponse r = json_response({{"error", e.message}}, e.status);
  r.allow = e.allow;
  return r;
}

// A whole decimal integer in [lo, hi], written as it is written back: no '+', no leading zero,
// no "-0" (/api/clips/01 and /api/clips/-0 named clip 1 and clip 0).
std::optional<long long> parse_integer(const std::string& text, long long lo, long long hi) {
  long long value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || value < lo || value > hi || text != std::to_string(value)) return std::nullopt;
  return value;
}

// Query parameter `name` as an integer in [lo, hi], or `fallback` when absent.
long long query_integer(const ApiRequest& request, const std::string& name, long long fallback, long long lo,
                        long long hi) {
  auto it = request.query.find(name);
  if (it == request.query.end()) return fallback;
  auto value = parse_integer(it->second, lo, hi);
  if (!value) throw ApiError{400, fmt::format("'{}' must be an integer in [{}, {}]", name, lo, hi)};
  return *value;
}

json body_object(const ApiRequest& request) {
  if (request.body.empty()) return json::object();
  auto parsed = parse_json_text(request.body, "request body");
  if (!parsed) throw ApiError{400, parsed.error().to_string()};
  if (!parsed->is_object()) throw ApiError{400, "the request body must be a JSON object"};
  return std::move(*parsed);
}

// The names a request takes, for a message: "'from', 'count'".
template <class Names>
std::string quoted_names(const Names& known) {
  std::string names;
  for (std::string_view name : known) names += fmt::format("{}'{}'", names.empty() ? "" : ", ", name);
  return names;
}

// A body's keys are the request's: one it does not take (a misspelt "min_frame", an option of the
// CLI's) is an error rather than ignored.
void check_keys(const json& body, std::initializer_list<std::string_view> known) {
  const std::string key = unknown_key(body, known);
  if (key.empty()) return;
  throw ApiError{400, fmt::format("unknown key {} (this request takes {})", mg::quoted(key), quoted_names(known))};
}

double number_field(const json& body, const std::string& name, double fallback, double lo, double hi) {
  if (!body.contains(name)) return fallback;
  const json& v = body[name];
  if (!v.is_number()) throw ApiError{400, fmt::format("'{}' must be a number", name)};
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) throw ApiError{400, fmt::format("'{}' must be in [{}, {}]", name, lo, hi)};
  return x;
}

long long integer_field(const json& body, const std::string& name, long long fallback, long long lo, long long hi) {
  if (!body.contains(name)) return fallback;
  const json& v = body[name];
  if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi) {
    throw ApiError{400, fmt::format("'{}' must be an integer in [{}, {}]", name, lo, hi)};
  }
  return v.get<long long>();
}

std::string string_field(const json& body, const std::string& name, const std::string& fallback) {
  if (!body.contains(name)) return fallback;
  if (!body[name].is_string()) throw ApiError{400, fmt::format("'{}' must be a string", name)};
  return body[name].get<std::string>();
}

bool boolean_field(const json& body, const std::string& name, bool fallback) {
  if (!body.contains(name)) return fallback;
  if (!body[name].is_boolean()) throw ApiError{400, fmt::format("'{}' must be true or false", name)};
  return body[name].get<bool>();
}

double round_mm(double v) { return std::round(v * 1e4) / 1e4 + 0.0; }

json joints_json(const Skeleton& skeleton) {
  json joints = json::array();
  for (const JointDef& joint : skeleton.joints()) joints.push_back({{"name", joint.name}, {"parent", joint.parent}});
  return joints;
}

// World joint positions per frame, flat [x0, y0, z0, x1, ...], metres; `centre` is
// subtracted from x and z.
json positions_json(const Skeleton& skeleton, const Motion& motion, const Vec2& centre = Vec2::Zero()) {
  const std::vector<Vec3> world = world_positions(skeleton, motion);
  const size_t joints = static_cast<size_t>(skeleton.joint_count());
  json frames = json::array();
  for (int f = 0; f < motion.frame_count; ++f) {
    json frame = json::array();
    for (size_t j = 0; j < joints; ++j) {
      const Vec3& p = world[f * joints + j];
      frame.push_back(round_mm(p.x() - centre.x()));
      frame.push_back(round_mm(p.y()));
      frame.push_back(round_mm(p.z() - centre.y()));
    }
    frames.push_back(std::move(frame));
  }
  return frames;
}

json motion_json(const Skeleton& skeleton, const Motion& motion) {
  return {{"fps", motion.fps},
          {"frames", motion.frame_count},
          {"joints", joints_json(skeleton)},
          {"positions", positions_json(skeleton, motion)}};
}

class Router {
 public:
  Router(SynthesisService& service, const ApiRequest& request) : service_(service), request_(request) {
    size_t begin = 1;
    const std::string& path = request.path;
    while (begin <= path.size()) {
      size_t end = path.find('/', begin);
      if (end == std::string::npos) end = path.size();
      parts_.push_back(path.substr(begin, end - begin));
      begin = end + 1;
    }
  }

  ApiResponse route() {
    using Handler = ApiResponse (Router::*)();
    struct Endpoint {
      const char* method;  // "GET" (HEAD too) or "POST"
      Handler handler;
      std::vector<std::string_view> query;  // the query keys it takes
    };
    const auto& p = parts_;
    const size_t n = p.size();
    std::optional<Endpoint> endpoint;
    if (n >= 2 && p[0] == "api") {
      const std::string& what = p[1];
      if (n == 2 && what == "summary") endpoint = Endpoint{"GET", &Router::summary, {}};
      if (n == 2 && what == "clips") endpoint = Endpoint{"GET", &Router::clips, {}};
      if (n == 4 && what == "clips" && p[3] == "frames") {
        endpoint = Endpoint{"GET", &Router::clip_frames, {"from", "count"}};
      }
      if (n == 2 && what == "matrix.png") endpoint = Endpoint{"GET", &Router::matrix, {}};
      if (n == 2 && what == "transitions") endpoint = Endpoint{"GET", &Router::transitions, {}};
      if (n == 4 && what == "transitions" && p[3] == "poses") {
        endpoint = Endpoint{"GET", &Router::transition_poses, {}};
      }
      if (n == 2 && what == "walk") endpoint = Endpoint{"POST", &Router::walk, {}};
      if (n == 2 && what == "path") endpoint = Endpoint{"POST", &Router::path, {}};
      if (n == 3 && what == "steer" && p[2] == "sessions") endpoint = Endpoint{"POST", &Router::create_session, {}};
      if (n == 5 && what == "steer" && p[2] == "sessions" && p[4] == "step") {
        endpoint = Endpoint{"POST", &Router::step_session, {}};
      }
      if (n == 3 && what == "results") endpoint = Endpoint{"GET", &Router::result_file, {"root_motion", "figure"}};
    }
    if (!endpoint) throw ApiError{404, fmt::format("no such endpoint: {}", request_.path)};
    const bool get = std::string_view(endpoint->method) == "GET";
    const std::string allow = get ? "GET, HEAD, OPTIONS" : "POST, OPTIONS";
    if (request_.method == "OPTIONS") {
      ApiResponse r;
      r.status = 204;
      r.allow = allow;
      return r;
    }
    if (request_.method != endpoint->method && !(get && request_.method == "HEAD")) {
      throw ApiError{405, fmt::format("{} takes {}, not {}", request_.path, endpoint->method, request_.method), allow};
    }
    check_query(endpoint->query);
    return (this->*endpoint->handler)();
  }

 private:
  // The query's keys are the endpoint's, each given once: a misspelt "?rootmotion=1" was
  // ignored (the download came without it), and of "?from=5&from=7" the first was taken.
  void check_query(const std::vector<std::string_view>& known) const {
    for (auto it = request_.query.begin(); it != request_.query.end(); it = request_.query.upper_bound(it->first)) {
      const std::string& key = it->first;
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        throw ApiError{400, fmt::format("unknown query parameter {} ({})", mg::quoted(key),
                                        known.empty() ? "this request takes none"
                                                      : "this request takes " + quoted_names(known))};
      }
      if (request_.query.count(key) > 1) {
        throw ApiError{400, fmt::format("query parameter {} is given twice", mg::quoted(key))};
      }
    }
  }

  const MotionDatabase& db() const { return service_.file().database; }
  const MotionGraph& graph() const { return service_.file().graph; }
  const Skeleton& skeleton() const { return service_.context().assembler.skeleton(); }

  // The contacts of database frames [first, first + count) (one clip's) in the CLI's shape
  // (export/positions_json.h: joint names and indices, planted per frame), or null when the
  // graph's feet were not found.
  json database_contacts_json(int first, int count) const {
    const SynthesisContext& context = service_.context();
    if (context.frame_contacts.empty()) return nullptr;
    const DatabaseClip& c = db().clips[db().clip_of(first)];
    // Each clip's contacts are found on its own skeleton's feet (database/database_contacts.h).
    auto feet = c.skeleton == context.assembler.target_skeleton() ? Result<FootJoints>(context.feet)
                                                                    : find_foot_joints(db().skeletons[c.skeleton]);
    if (!feet) return nullptr;
    const std::span<const ContactMask> masks(context.frame_contacts.data() + first, static_cast<size_t>(count));
    return contacts_json(db().skeletons[c.skeleton], PositionsJsonContacts{*feet, masks}, count);
  }

  // The same for a synthesized motion's frames (on the target skeleton), from the contacts the
  // service passed to the clean-up.
  json played_contacts_json(std::span<const ContactMask> masks, int frames) const {
    const SynthesisContext& context = service_.context();
    if (context.frame_contacts.empty() || static_cast<int>(masks.size()) < frames) return nullptr;
    return contacts_json(skeleton(), PositionsJsonContacts{context.feet, masks}, frames);
  }

  int index_part(size_t i, int count, const char* what) const {
    auto value = parse_integer(parts_[i], 0, count - 1);
    if (!value) throw ApiError{404, fmt::format("no {} '{}' (there are {})", what, parts_[i], count)};
    return static_cast<int>(*value);
  }

  // A steering control: heading_deg, tag (a tag of the graph; none or 'any': any motion) and
  // rest: true, which comes to rest (controller.h), as does a tag 'stop' the graph can hardly play.
  SteeringControl control_of(const json& body) const {
    SteeringControl control;
    control.heading_deg = number_field(body, "heading_deg", 0.0, -720.0, 720.0);
    control.tag = string_field(body, "tag", "");
    if (ascii_lower(control.tag) == "any") control.tag.clear();
    // (a stop the graph has no tag for is rest where it can: steering_controls.h)
    if (!control.tag.empty() && !is_stop_tag(control.tag)) {
      if (auto mask = service_.context().tag_mask(control.tag); !mask) throw ApiError{400, mask.error().message};
    }
    control.rest = boolean_field(body, "rest", false);
    return control;
  }

  ApiResponse summary() {
    const GraphFile& file = service_.file();
    const GraphStatistics stats = compute_graph_statistics(graph(), service_.context().frame_tags);
    const int frames = db().frame_count();
    const int block = service_.picture_block();
    return json_response({{"graph", service_.graph_path()},
                          {"fps", db().fps},
                          {"frames", frames},
                          {"clips", db().clips.size()},
                          {"skeleton_joints", skeleton().joint_count()},
                          {"window", graph().window},
                          {"threshold", file.threshold},
                          {"threshold_quantile", file.threshold_quantile},
                          {"tags", db().tag_names},
                          {"matrix", {{"block", block}, {"side", (frames + block - 1) / block}}},
                          {"statistics", json::parse(to_json(stats, db().tag_names))}});
  }

  ApiResponse clips() {
    json out = json::array();
    const std::vector<TagMask>& tags = service_.context().frame_tags;
    const std::vector<ClipCoverage> coverage = clip_coverage(graph(), db(), {});
    const std::vector<std::vector<std::string>>& doubts = service_.clip_doubts();
    const std::vector<std::string>& mirror_of = service_.clip_mirror_of();
    for (size_t i = 0; i < db().clips.size(); ++i) {
      const DatabaseClip& c = db().clips[i];
      TagMask mask = 0;
      for (int f = c.first_frame; f < c.first_frame + c.frame_count; ++f) mask |= tags[f];
      out.push_back({{"index", i},
                     {"name", c.name},
                     {"first_frame", c.first_frame},
                     {"frames", c.frame_count},
                     {"duration_s", std::max(0, c.frame_count - 1) / db().fps},  // first frame to last, as info
                     {"read_fps", c.read_fps},
                     {"kept_frames", coverage[i].kept_frames},
                     {"tags", db().tag_names_of(mask)},
                     {"doubts", doubts[i]},
                     {"mirror_of", mirror_of[i].empty() ? json(nullptr) : json(mirror_of[i])}});
    }
    return json_response(out);
  }

  ApiResponse clip_frames() {
    const int index = index_part(2, static_cast<int>(db().clips.size()), "clip");
    const DatabaseClip& c = db().clips[index];
    const int from = static_cast<int>(query_integer(request_, "from", 0, 0, c.frame_count - 1));
    const int count = static_cast<int>(
        query_integer(request_, "count", std::min(StudioApi::kMaxFramesPerRequest, c.frame_count - from), 1,
                      StudioApi::kMaxFramesPerRequest));
    const Motion slice = c.motion.slice(from, std::min(count, c.frame_count - from));
    json out = motion_json(db().skeletons[c.skeleton], slice);
    out["clip"] = index;
    out["from"] = from;
    out["contacts"] = database_contacts_json(c.first_frame + from, slice.frame_count);
    return json_response(out);
  }

  ApiResponse matrix() {
    auto png = service_.distance_png();
    if (!png) throw ApiError{500, png.error().to_string()};
    ApiResponse r;
    r.content_type = "image/png";
    r.body = std::move(*png);
    return r;
  }

  ApiResponse transitions() {
    // Each transition's blend length and whether it is a bridge, from its edge (bridges blend
    // longer than the window).
    std::vector<int> blend(graph().transitions.size(), graph().window);
    std::vector<char> bridge(graph().transitions.size(), 0);
    std::vector<MeasuredPair> measured(graph().transitions.size());
    for (size_t i = 0; i < measured.size(); ++i) {
      measured[i] = {graph().transitions[i].from_frame, graph().transitions[i].to_frame};
    }
    for (const GraphEdge& e : graph().edges) {
      if (!e.transition) continue;
      blend[e.transition_index] = blend_frames(e);
      bridge[e.transition_index] = e.bridge;
      measured[e.transition_index] = measured_pair(graph(), e);
    }
    json out = json::array();
    for (size_t i = 0; i < graph().transitions.size(); ++i) {
      const Transition& t = graph().transitions[i];
      out.push_back({{"index", i},
                     {"from_frame", t.from_frame},
                     {"to_frame", t.to_frame},
                     {"window_from_frame", measured[i].from_frame},
                     {"window_to_frame", measured[i].to_frame},
                     {"distance", t.distance},
                     {"blend_frames", blend[i]},
                     {"bridge", bridge[i] != 0},
                     {"from_clip", db().clips[db().clip_of(t.from_frame)].name},
                     {"to_clip", db().clips[db().clip_of(t.to_frame)].name}});
    }
    return json_response(out);
  }

  // The k frames from global frame `first`, centred on the floor position of the root of
  // their first frame.
  json window_json(int first, int count) const {
    const DatabaseClip& c = db().clips[db().clip_of(first)];
    const Motion slice = c.motion.slice(first - c.first_frame, count);
    const Skeleton& s = db().skeletons[c.skeleton];
    std::vector<Vec3> world(s.joint_count());
    std::vector<Quat> rotations(s.joint_count());
    forward_kinematics(s, slice, 0, world, rotations);
    return {{"clip", c.name},
            {"first_frame", first},
            {"positions", positions_json(s, slice, Vec2(world[0].x(), world[0].z()))},
            {"contacts", database_contacts_json(first, count)}};
  }

  // The two windows the transition's D was measured on (a bridge blends over more frames,
  // centred on them).
  ApiResponse transition_poses() {
    const int index = index_part(2, static_cast<int>(graph().transitions.size()), "transition");
    const Transition& t = graph().transitions[index];
    const int k = graph().window;
    MeasuredPair pair{t.from_frame, t.to_frame};
    for (const GraphEdge& e : graph().edges) {
      if (e.transition && e.transition_index == index) pair = measured_pair(graph(), e);
    }
    return json_response({{"index", index},
                          {"distance", t.distance},
                          {"fps", db().fps},
                          {"joints", joints_json(skeleton())},
                          {"from", window_json(pair.from_frame, k)},
                          {"to", window_json(pair.to_frame - k + 1, k)}});
  }

  ApiResponse walk() {
    const json body = body_object(request_);
    check_keys(body, {"from", "to", "min_frames", "seed", "cost", "cleanup"});
    const int nodes = graph().node_count();
    WalkRequest w;
    w.from = static_cast<int>(integer_field(body, "from", 0, 0, nodes - 1));
    w.to = static_cast<int>(integer_field(body, "to", w.from, 0, nodes - 1));
    w.min_frames = static_cast<int>(integer_field(body, "min_frames", 150, 0, 1800));
    w.seed = static_cast<std::uint64_t>(integer_field(body, "seed", 1, 0, 1LL << 40));
    auto cost = parse_walk_cost(string_field(body, "cost", "random"));
    if (!cost) throw ApiError{400, cost.error().message};
    w.cost = *cost;
    w.cleanup = boolean_field(body, "cleanup", true);
    auto result = service_.walk(w);
    if (!result) throw ApiError{422, result.error().to_string()};
    json out = motion_json(skeleton(), result->motion);
    out["result"] = result->result;
    out["cleanup"] = result->cleaned;
    out["contacts"] = played_contacts_json(result->contacts, result->motion.frame_count);
    out["foot_slide"] = foot_slide_report(service_.context(), result->walk, result->motion);
    out["played"] = played_clips_json(db(), service_.context().walk_sources(result->walk), result->motion.fps,
                                      result->motion.frame_count);
    out["transitions"] = result->transitions;
    out["transitions_per_second"] =
        transitions_per_second(result->transitions, result->motion.frame_count, result->motion.fps);
    out["bridges"] = count_bridges(graph(), result->walk.edges);
    return json_response(out);
  }

  ApiResponse path() {
    const json body = body_object(request_);
    check_keys(body, {"points", "segments", "edit_path", "rest_at_end", "cleanup"});
    if (body.contains("points") && body["points"].is_array() &&
        body["points"].size() > static_cast<size_t>(StudioApi::kMaxPathPoints)) {
      throw ApiError{400, fmt::format("at most {} points", StudioApi::kMaxPathPoints)};
    }
    if (body.contains("segments") && body["segments"].is_array() &&
        body["segments"].size() > static_cast<size_t>(StudioApi::kMaxPathSegments)) {
      throw ApiError{400, fmt::format("at most {} segments", StudioApi::kMaxPathSegments)};
    }
    // Points on the studio's floor (far from the origin the floor's doubles hold fewer digits of
    // the motion: the same path 1e15 m out played other frames); the parser judges the rest.
    if (body.contains("points") && body["points"].is_array()) {
      for (size_t i = 0; i < body["points"].size(); ++i) {
        const json& p = body["points"][i];
        if (!p.is_array()) continue;
        for (const json& v : p) {
          if (v.is_number() && !(std::abs(v.get<double>()) <= StudioApi::kMaxPathCoordinateM)) {
            throw ApiError{400, fmt::format("point {}: {:g} m is off the floor (at most {:g} m from the origin)", i,
                                            v.get<double>(), StudioApi::kMaxPathCoordinateM)};
          }
        }
      }
    }
    auto floor_path = parse_path_document(body, "request body");
    if (!floor_path) throw ApiError{400, floor_path.error().to_string()};
    if (floor_path->length_m() > StudioApi::kMaxPathLengthM) {
      throw ApiError{400, fmt::format("the path is {} m long, over the {:g} m a path may be", floor_path->length_m(),
                                      StudioApi::kMaxPathLengthM)};
    }
    for (const PathSegment& s : floor_path->segments()) {
      if (auto mask = service_.context().tag_mask(s.tag); !mask) throw ApiError{400, mask.error().message};
    }
    PathSynthesisSettings settings;
    settings.edit_path = boolean_field(body, "edit_path", true);
    settings.rest_at_end = boolean_field(body, "rest_at_end", false);
    auto synthesized = service_.path(*floor_path, settings, boolean_field(body, "cleanup", true));
    if (!synthesized) throw ApiError{422, synthesized.error().to_string()};
    const PathSynthesisResult* result = &synthesized->synthesis;
    json out = motion_json(skeleton(), result->motion);
    out["result"] = service_.store_result(result->motion);
    out["cleanup"] = synthesized->cleaned;
    out["contacts"] = played_contacts_json(synthesized->contacts, result->motion.frame_count);
    out["foot_slide"] = foot_slide_report(service_.context(), result->walk, result->motion);
    out["played"] = played_clips_json(db(), service_.context().walk_sources(result->walk), result->motion.fps,
                                      result->motion.frame_count);
    out["path_length_m"] = result->path_length_m;
    out["arc_covered_m"] = result->arc_covered_m;
    out["end_distance_m"] = result->end_distance_m;
    out["reached_end"] = result->reached_end;
    out["mean_deviation_m"] = result->mean_deviation_m;
    out["max_deviation_m"] = result->max_deviation_m;
    out["graph_mean_deviation_m"] = result->graph_mean_deviation_m;
    out["graph_max_deviation_m"] = result->graph_max_deviation_m;
    out["path_edit"] = path_edit_report(settings, *result);
    out["shortfalls"] = path_shortfalls(service_.context(), *floor_path, settings, *result);
    // What the user should be told, as the CLI's path warns it: the segments' types the graph can
    // hardly play, then the shortfalls (the clean-up's absence is "cleanup": false).
    std::vector<std::string> warnings = segment_warnings(service_.context(), *floor_path);
    for (const json& shortfall : out["shortfalls"]) warnings.push_back(shortfall.get<std::string>());
    out["warnings"] = warnings;
    out["tag_match"] = result->tag_match;
    out["rest"] = rest_report(service_.context(), result->rest, result->rest_frame / db().fps);
    out["segments"] = path_segments_report(service_.context(), *floor_path, *result);
    const int transitions = result->walk.transition_count(graph());
    out["transitions"] = transitions;
    out["transitions_per_second"] = transitions_per_second(transitions, result->motion.frame_count, result->motion.fps);
    out["bridges"] = count_bridges(graph(), result->walk.edges);
    json frame_tags = json::array();
    for (TagMask m : result->frame_tags) frame_tags.push_back(db().tag_names_of(m));
    out["frame_tags"] = std::move(frame_tags);
    return json_response(out);
  }

  ApiResponse create_session() {
    const json body = body_object(request_);
    check_keys(body, {"heading_deg", "tag", "cleanup"});
    const bool cleanup = boolean_field(body, "cleanup", true);
    auto started = service_.create_session(control_of(body), cleanup);
    if (!started) throw ApiError{started.error().kind == ErrorKind::kBusy ? 503 : 422, started.error().to_string()};
    return json_response({{"session", started->id},
                          {"result", started->id},
                          {"cleanup", cleanup && !service_.context().frame_contacts.empty()},
                          {"fps", db().fps},
                          {"joints", joints_json(skeleton())},
                          {"tags", db().tag_names},
                          {"can_rest", !service_.context().rest().empty()},
                          {"warnings", started->warnings}});
  }

  ApiResponse step_session() {
    auto id = parse_integer(parts_[3], 0, 1LL << 30);
    if (!id) throw ApiError{404, fmt::format("no steering session '{}'", parts_[3])};
    const json body = body_object(request_);
    check_keys(body, {"heading_deg", "tag", "rest", "min_frames"});
    const SteeringControl control = control_of(body);
    const int min_frames = static_cast<int>(integer_field(body, "min_frames", 1, 1, 90));
    auto step = service_.step_session(static_cast<int>(*id), control, min_frames);
    if (!step) throw ApiError{404, step.error().to_string()};
    return json_response({{"session", *id},
                          {"first_frame", step->first_frame},
                          {"frames", step->motion.frame_count},
                          {"search_ms", 1e3 * step->search_seconds},
                          {"transitions", step->transitions},
                          {"session_transitions", step->session_transitions},
                          {"bridges", step->bridges},
                          {"session_bridges", step->session_bridges},
                          {"session_transitions_per_second",
                           transitions_per_second(step->session_transitions, step->first_frame + step->motion.frame_count,
                                                  db().fps)},
                          {"positions", positions_json(skeleton(), step->motion)},
                          {"contacts", played_contacts_json(step->contacts, step->motion.frame_count)},
                          {"rest_s", step->rest_s >= 0.0 ? json(step->rest_s) : json(nullptr)},
                          {"rest_clip", step->rest_clip.empty() ? json(nullptr) : json(step->rest_clip)},
                          {"resting", step->resting},
                          {"standing", step->standing},
                          {"rest_for_good", step->rest_for_good},
                          {"starts", starts_report(service_.context(), step->starts,
                                                   std::numeric_limits<long long>::max())},
                          {"warnings", step->warnings}});
  }

  // ID.bvh, ID.glb, ID.gltf or ID.fbx.
  ApiResponse result_file() {
    using Format = SynthesisService::FileFormat;
    const std::string& name = parts_[2];
    std::optional<long long> id;
    std::string suffix;
    Format format = Format::kBvh;
    using Suffix = std::pair<std::string_view, Format>;
    for (const auto& [s, f] : {Suffix{".bvh", Format::kBvh}, Suffix{".glb", Format::kGlb},
                               Suffix{".gltf", Format::kGltf}, Suffix{".fbx", Format::kFbx}}) {
      if (name.size() > s.size() && name.ends_with(s)) {
        suffix = s;
        format = f;
        id = parse_integer(name.substr(0, name.size() - s.size()), 0, 1LL << 30);
      }
    }
    const std::string_view number = std::string_view(name).substr(0, name.size() - suffix.size());
    if (!id && !suffix.empty() && is_ascii_digits(number)) {
      // The form, but a number no result has had (past 2^30).
      throw ApiError{404, fmt::format("no result {} (results are kept for the latest {})", mg::quoted(number),
                                      SynthesisService::kMaxResults)};
    }
    if (!id) {
      throw ApiError{404, fmt::format("no result {}: expected /api/results/ID.bvh, ID.glb, ID.gltf or ID.fbx",
                                      mg::quoted(name))};
    }
    const bool root_motion = query_integer(request_, "root_motion", 0, 0, 1) == 1;
    const bool figure = query_integer(request_, "figure", 1, 0, 1) == 1;
    auto bytes = service_.result_file(static_cast<int>(*id), format, root_motion, figure);
    if (!bytes) throw ApiError{404, fmt::format("no result {} (results are kept for the latest {})", *id,
                                                SynthesisService::kMaxResults)};
    ApiResponse r;
    r.content_type = format == Format::kGlb    ? "model/gltf-binary"
                     : format == Format::kGltf ? "model/gltf+json"
                                               : "application/octet-stream";
    r.body = std::move(*bytes);
    r.file_name = fmt::format("motiongraph-{}{}{}", *id, root_motion ? "-root-motion" : "", suffix);
    return r;
  }

  SynthesisService& service_;
  const ApiRequest& request_;
  std::vector<std::string> parts_;
};

}  // namespace

ApiResponse StudioApi::handle(const ApiRequest& request) const {
  try {
    return route(request);
  } catch (const ApiError& e) {
    return error_response(e);
  } catch (const std::bad_alloc&) {
    return error_response({503, "out of memory"});
  } catch (const std::exception& e) {
    return error_response({500, e.what()});
  }
}

ApiResponse StudioApi::route(const ApiRequest& request) const { return Router(*service_, request).route(); }

}  // namespace mg::studio
