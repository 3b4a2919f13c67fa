// Graph.walk(), Graph.path() and Graph.controller(): the CLI's walk, path and steer on a graph
// in memory, through the same library calls (evaluation/synthesis_run.h, synthesis/controller.h)
// and with the same options as keywords.
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "binding.h"
#include "motiongraph/core/progress.h"
#include "motiongraph/core/quantile.h"
#include "motiongraph/core/transition_rate.h"
#include "motiongraph/evaluation/foot_slide_report.h"
#include "motiongraph/evaluation/steering_controls.h"
#include "motiongraph/evaluation/synthesis_run.h"
#include "motiongraph/synthesis/controller.h"

namespace mg::python {

namespace {

SynthesisRunSettings run_settings(const PyGraph& graph) {
  SynthesisRunSettings run;
  run.graph_name = graph.name;
  run.cleanup_off_reason = "cleanup=False";
  return run;
}

// The synthesized motion as a Python Motion that keeps its graph.
PyMotion result_motion(const PyGraph& graph, const char* name, SynthesizedMotion&& made) {
  // What the user should be told of it, as the CLI's warnings (the report's "warnings").
  for (const std::string& line : made.warnings) warn(graph.name + ": " + line);
  PyMotion motion(name, graph.loaded->context().assembler.skeleton(), std::move(made.motion));
  motion.report = std::move(made.report);
  motion.graph = graph.loaded;
  motion.walk = std::move(made.walk);
  motion.contacts = std::move(made.contacts);
  motion.take_feet_from(graph.loaded->context());
  return motion;
}

PyMotion walk(const PyGraph& graph, Integer from_node, Integer to_node, const py::kwargs& options) {
  const int from = from_node.value, to = to_node.value;
  WalkSearchSettings settings;
  SynthesisRunSettings run = run_settings(graph);
  std::string cost = "quality";
  apply_options(options,
                {{"cost", set(cost)},
                 {"seed", set(settings.seed)},
                 {"min_frames", set(settings.min_frames)},
                 {"max_expansions", set(settings.max_expansions)},
                 {"cleanup", set(run.cleanup)}},
                "walk");
  settings.cost = take(parse_walk_cost(cost));
  std::stop_source stop;  // Ctrl-C (run_stoppable)
  settings.stop = stop.get_token();
  Result<SynthesizedMotion> made = Error{};
  run_stoppable(stop, [&] { made = run_walk_synthesis(graph.loaded->context(), from, to, settings, run); });
  return result_motion(graph, "walk", take(std::move(made)));
}

PyMotion path(const PyGraph& graph, const std::optional<std::vector<std::array<Real, 2>>>& points,
              const std::optional<std::string>& shape, const std::optional<std::vector<std::string>>& segments,
              const std::optional<std::filesystem::path>& file, const py::kwargs& options) {
  PathSynthesisSettings settings;
  SynthesisRunSettings run = run_settings(graph);
  py::object progress = py::none();
  apply_options(options,
                {{"horizon", set(settings.horizon_s)},
                 {"commit", set(settings.commit_s)},
                 {"tag_penalty", set(settings.tag_penalty_m2)},
                 {"tag_lookahead", set(settings.tag_lookahead)},
                 {"max_expansions", set(settings.max_expansions)},
                 {"beam", set(settings.beam_width)},
                 {"min_speed", set(settings.min_speed_mps)},
                 {"transition_penalty", set(settings.transition_penalty_m2)},
                 {"bridge_penalty", set(settings.bridge_penalty_m2)},
                 {"behind_penalty", set(settings.behind_penalty_m)},
                 {"start_node", set(settings.start_node)},
                 {"progress_retries", set(settings.progress_retries)},
                 {"retry_deviation", set(settings.retry_deviation_m)},
                 {"retry_horizon", set(settings.retry_horizon_s)},
                 {"retry_tag_match", set(settings.retry_tag_match)},
                 {"path_edit", set(settings.edit_path)},
                 {"rest_at_end", set(settings.rest_at_end)},
                 {"edit_max_turn", set(settings.path_edit.max_turn_deg_per_m)},
                 {"edit_round_corners", set(settings.path_edit.round_corners_m)},
                 {"cleanup", set(run.cleanup)},
                 {"progress",
                  [&progress](py::handle value) {
                    // Said now, not when the search has run 2 s.
                    if (!PyCallable_Check(value.ptr())) throw py::type_error("path(): progress must be callable");
                    progress = py::reinterpret_borrow<py::object>(value);
                  }}},
                "path");
  check(settings.validate());
  if (points.has_value() + shape.has_value() + file.has_value() != 1) {
    throw py::value_error("path() takes exactly one of points, shape and file");
  }
  if (points && points->size() < 2) {
    throw py::value_error(fmt::format("path(): a path needs at least two points, not {}", points->size()));
  }
  FloorPathSource source{file ? file->string() : std::string(), shape.value_or(""), {},
                         segments.value_or(std::vector<std::string>{})};
  for (const auto& [x, z] : points.value_or(std::vector<std::array<Real, 2>>{})) {
    source.points.emplace_back(x.value, z.value);
  }
  std::stop_source stop;  // Ctrl-C (run_stoppable)
  settings.stop = stop.get_token();
  // progress: every 2 s, how far along the path the searches have come; it runs with the GIL,
  // and its first exception stops the search and is raised (as build's progress).
  std::optional<py::error_already_set> callback_error;
  ProgressLineClock clock;
  double length_m = 0.0;
  if (!progress.is_none()) {
    settings.searched = [&](double arc_m, int attempt) {
      if (!clock.due()) return;
      py::gil_scoped_acquire acquire;
      if (callback_error) return;
      try {
        progress(fmt::format("path: {:.1f} m of {:.1f} m along it (search {} of the whole path) in {:.1f} s", arc_m,
                             length_m, attempt, clock.elapsed_s()));
      } catch (py::error_already_set& e) {
        callback_error = std::move(e);
        stop.request_stop();
      }
    };
  }
  Result<SynthesizedMotion> made = Error{};
  run_stoppable(stop, [&] {
    auto floor_path = make_floor_path(source);
    if (floor_path) length_m = floor_path->length_m();
    if (!floor_path) {
      made = floor_path.error();
    } else if (auto known = check_segment_tags(graph.loaded->context(), *floor_path, source.file); !known) {
      made = known.error();
    } else {
      made = run_path_synthesis(graph.loaded->context(), *floor_path, settings, run);
    }
  });
  if (callback_error) throw std::move(*callback_error);
  return result_motion(graph, "path", take(std::move(made)));
}

// The interactive controller: each step() takes a heading and a motion type and returns the
// frames it decided on, cleaned as the CLI's steer cleans them.
class PyController {
 public:
  static constexpr int kMaxStepFrames = 3600;  // a step's min_frames: two minutes at 30 fps

  PyController(const PyGraph& graph, double heading_deg, const std::optional<std::string>& tag,
               std::array<double, 2> at, const py::kwargs& options)
      : loaded_(graph.loaded),
        name_(graph.name),
        controls_(graph.loaded->context()),
        motion_(graph.loaded->context().assembler.empty_motion()) {
    ControllerSettings settings;
    SynthesisRunSettings run = run_settings(graph);
    std::string hold = "facing";
    apply_options(options,
                  {{"horizon", set(settings.horizon_s)},
                   {"commit", set(settings.commit_s)},
                   {"tag_penalty", set(settings.tag_penalty)},
                   {"transition_penalty", set(settings.transition_penalty)},
                   {"bridge_penalty", set(settings.bridge_penalty)},
                   {"tag_lookahead", set(settings.tag_lookahead)},
                   {"travel_pace", set(settings.travel_mps)},
                   {"travel_penalty", set(settings.travel_penalty)},
                   {"max_expansions", set(settings.max_expansions)},
                   {"beam", set(settings.beam_width)},
                   {"time_budget", set(settings.time_budget_s)},
                   {"start_node", set(settings.start_node)},
                   {"edit_max_turn", set(settings.heading_edit.max_turn_deg_per_m)},
                   {"edit_turn_distance", set(settings.heading_edit.turn_distance_m)},
                   {"edit_hold", set(hold)},
                   {"cleanup", set(run.cleanup)}},
                  "controller");
    if (hold != "travel" && hold != "facing") check(Error{"", 0, "--edit-hold must be 'travel' or 'facing', not '" + hold + "'"});
    settings.heading_edit.hold_travel = hold == "travel";
    check(settings.validate());
    settings_ = settings;
    run_ = run;
    std::string cleanup_warning;
    cleanup_ = make_cleanup(context(), run, cleanup_warning);
    if (!cleanup_warning.empty()) say(cleanup_warning);
    // The first input picks where it starts, and says nothing: each step gives its own (a stop
    // asked here is not a rest to come: a step without it asks for any motion).
    SteeringControls starting(context());
    const ControlInput first = resolve(starting, heading_deg, tag, false);
    controller_ = take(Controller::create(context(), settings, first, Vec2(at[0], at[1])));
  }

  // Threads may share a controller: its steps take turns (the lock taken without the GIL, which a
  // step gives up while it searches).
  PyMotion step(Real heading, const std::optional<std::string>& tag, bool rest, Integer min_frames_given) {
    const double heading_deg = heading.value;
    const int min_frames = min_frames_given.value;
    if (min_frames < 1 || min_frames > kMaxStepFrames) {
      throw py::value_error(fmt::format("min_frames must be from 1 to {}, not {}", kMaxStepFrames, min_frames));
    }
    const ControlInput in = input(heading_deg, tag, rest);
    bool stays = false;  // at rest for good, asked to move
    bool turns = false;  // asked to turn standing at rest
    double rest_s = 0.0;
    std::string rest_clip;
    std::unique_lock<std::mutex> lock(mutex_, std::defer_lock);
    int first = 0;
    std::vector<ContactMask> contacts;
    Status cleaned = Ok{};
    Motion decided;
    {
      py::gil_scoped_release release;
      lock.lock();
      turns = turns_at_rest(in, *controller_);
      controller_->set_input(in);
      first = motion_.frame_count;
      // Decisions until min_frames are played (each commits whole edges: a few frames more).
      do {
        const int from = motion_.frame_count;
        const ControllerDecision decision = controller_->step(motion_);
        decision_seconds_.push_back(decision.search_seconds);
        exhausted_ += decision.budget_exhausted ? 1 : 0;
        if (cleanup_ && cleaned) cleaned = cleanup_->clean(motion_, from, decision.contacts);
        contacts.insert(contacts.end(), decision.contacts.begin(), decision.contacts.end());
        played_.edges.insert(played_.edges.end(), decision.edges.begin(), decision.edges.end());
        const std::vector<FrameSource> sources = decision_sources(context(), decision);
        played_sources_.insert(played_sources_.end(), sources.begin(), sources.end());
        transitions_ += decision_transitions(*context().graph, decision);
        if (decision.frames == 0) break;
      } while (cleaned && motion_.frame_count - first < min_frames);
      if (!in.rest && controller_->standing() && controller_->rest_is_for_good()) {
        stays = true;
        rest_s = static_cast<double>(controller_->rest_frame()) / context().db->fps;
        const RestEnding* ending = controller_->rest_ending();
        rest_clip = context().db->clips[static_cast<size_t>(context().db->clip_of(ending->last_frame))].name;
      }
      if (cleaned) {
        contacts_.insert(contacts_.end(), contacts.begin(), contacts.end());
        decided = motion_.slice(first, motion_.frame_count - first);
      }
    }
    lock.unlock();
    if (turns && controls_.turn_at_rest("a step")) say(controls_.warnings().back());
    if (stays && !warned_stays_) {
      warned_stays_ = true;
      say(fmt::format("the character came to rest at {:.2f} s, at the end of {}, and stays there: the steps asking "
                      "it to move cannot (the graph has no way on from that clip's last frame, and no clip the "
                      "graph goes on from has the half second to start off from it)",
                      rest_s, rest_clip));
    }
    check(cleaned);
    return frames(std::move(decided), std::move(contacts));
  }

  // The second from which the character stands still, once it has come to rest; None before.
  std::optional<double> rest_s() const {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    if (controller_->rest_frame() < 0) return std::nullopt;
    return static_cast<double>(controller_->rest_frame()) / context().db->fps;
  }

  bool resting() const {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    return controller_->resting();
  }

  bool standing() const {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    return controller_->still();
  }

  std::string repr() const {
    int frames = 0;
    {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> lock(mutex_);
      frames = motion_.frame_count;
    }
    return fmt::format("<motiongraph.Controller on '{}': {} frames ({:.1f} s) so far>", name_, frames,
                       frames / context().db->fps);
  }

  // With the report the CLI's steer --report gives of the same decisions (but its controls, which
  // a script gives): transitions, bridges, the decisions' times, the heading edit, the clean-up
  // and the foot slide against the clips the motion was cut from, and the warnings said.
  PyMotion motion() const {
    Motion all;
    std::vector<ContactMask> contacts;
    nlohmann::json report;
    Walk played{-1, {}};
    std::vector<std::string> warnings = said_;  // (with the GIL, under which they are said)
    {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> lock(mutex_);
      all = motion_;
      contacts = contacts_;
      report = steering_report();
      played = played_;
    }
    PyMotion out = frames(std::move(all), std::move(contacts));
    out.report = std::move(report);
    out.report["warnings"] = std::move(warnings);
    out.walk = std::move(played);
    return out;
  }

 private:
  const SynthesisContext& context() const { return loaded_->context(); }

  // (the lock held)
  nlohmann::json steering_report() const {
    const double fps = context().db->fps;
    const int transitions = transitions_, bridges = count_bridges(*context().graph, played_.edges);
    return {{"frames", motion_.frame_count},
            {"fps", fps},
            {"transitions", transitions},
            {"transitions_per_second", transitions_per_second(transitions, motion_.frame_count, fps)},
            {"bridges", bridges},
            {"edges", played_.edges},
            {"decisions", decision_seconds_.size()},
            {"decision_ms_p50", 1e3 * quantile(decision_seconds_, 0.5)},
            {"decision_ms_p99", 1e3 * quantile(decision_seconds_, 0.99)},
            {"decision_ms_max", 1e3 * quantile(decision_seconds_, 1.0)},
            {"budget_exhausted_decisions", exhausted_},
            {"heading_edit", heading_edit_report(settings_.heading_edit, controller_->heading_edit_stats())},
            {"cleanup", cleanup_report(context(), run_, cleanup_)},
            {"foot_slide", foot_slide_report(context(), played_, motion_, played_sources_)},
            {"rests", rests_report(context(), *controller_, motion_.frame_count)},
            {"starts", starts_report(context(), controller_->starts(), motion_.frame_count)},
            {"rests_taken_back_s", rests_taken_back_report(context(), *controller_, motion_.frame_count)},
            {"rest", rest_report(context(), controller_->rest_ending(),
                                 static_cast<double>(controller_->rest_frame()) / context().db->fps)}};
  }



  // The input for a step (evaluation/steering_controls.h): the first time a motion type the graph
  // can hardly play is asked for, a warning says so; a stop the graph can hardly play is rest, and
  // rest a graph cannot come to is warned of. (With the GIL held, before the step takes the lock.)
  ControlInput input(double heading_deg, const std::optional<std::string>& tag, bool rest) {
    const size_t said = controls_.warnings().size();
    const ControlInput in = resolve(controls_, heading_deg, tag, rest);
    for (size_t i = said; i < controls_.warnings().size(); ++i) say(controls_.warnings()[i]);
    return in;
  }

  // The input `controls` reads for a heading (finite: ValueError otherwise), a tag and rest.
  static ControlInput resolve(SteeringControls& controls, double heading_deg, const std::optional<std::string>& tag,
                              bool rest) {
    if (!std::isfinite(heading_deg)) throw py::value_error(fmt::format("heading_deg must be finite, not {}", heading_deg));
    return take(controls.input({heading_deg, tag.value_or(""), rest}, "the controller"));
  }

  // A warning: given now (with the graph's name) and kept for the report (with the GIL held).
  void say(const std::string& line) {
    said_.push_back(line);
    warn(name_ + ": " + line);
  }

  PyMotion frames(Motion motion, std::vector<ContactMask> contacts) const {
    PyMotion out("steer", context().assembler.skeleton(), std::move(motion));
    out.graph = loaded_;
    out.contacts = std::move(contacts);
    out.take_feet_from(context());
    return out;
  }

  std::shared_ptr<const LoadedGraph> loaded_;
  std::string name_;
  SteeringControls controls_;       // the steps' inputs, their warnings said once (with the GIL held)
  std::vector<std::string> said_;   // every warning given, in order, for the report (with the GIL held)
  bool warned_stays_ = false;       // steps asking to move after a rest for good, warned of once
  mutable std::mutex mutex_;       // held by a step, and while the motion so far is copied
  Motion motion_;
  std::optional<FootCleanup> cleanup_;
  std::optional<Controller> controller_;
  Walk played_{-1, {}};  // every edge chosen: the report's edges and the clips the motion is cut from
  std::vector<FrameSource> played_sources_;  // each frame's, in order (decision_sources)
  int transitions_ = 0;  // the blends played (decision_transitions)
  std::vector<ContactMask> contacts_;
  ControllerSettings settings_;
  SynthesisRunSettings run_;
  std::vector<double> decision_seconds_;  // each step's search
  int exhausted_ = 0;                     // steps whose search ran out of budget
};

}  // namespace

void bind_synthesis(py::module_& m, py::class_<PyGraph>& graph) {
  // Before the graph's controller(), so that its signature names the class.
  py::class_<PyController>(m, "Controller", "Steers motion on a graph from a heading and a motion type.")
      .def("step", &PyController::step, py::arg("heading_deg"), py::arg("tag") = py::none(),
           py::arg("rest").noconvert() = false, py::arg("min_frames") = 1,
           "Decides the next frames towards heading_deg (degrees clockwise from north) with motion type `tag` "
           "(None: any) and returns them as a Motion: one decision's (a fifth of a second or so), or as many "
           "decisions' as make min_frames (1 to 3600; each ends with a whole edge). rest=True comes to rest at the "
           "end of a clip that ends standing still and holds its last frame (so does tag 'stop' where the graph can "
           "hardly play it), until asked to move: it goes on where the graph has a way on from there, and elsewhere "
           "starts off, the frame held blended into a clip that walks off (the report's 'starts'); asked to move "
           "before it stands, it takes the rest back and goes on; rest_s says when it stands still.")
      .def_property_readonly("rest_s", &PyController::rest_s,
                             "The second from which the character last stood still, once it has come to rest (on its "
                             "way there, will stand); None before.")
      .def_property_readonly("resting", &PyController::resting,
                             "Whether it has taken its way to rest: on it to the clip that stops, playing it, or "
                             "standing (until asked to move).")
      .def_property_readonly("standing", &PyController::standing,
                             "Whether it stands still at rest now (from rest_s on, until asked to move).")
      .def_property_readonly("motion", &PyController::motion, "All frames so far, as a Motion.")
      .def("__repr__", &PyController::repr);
  graph.def("walk", &walk, py::arg("from_node"), py::arg("to_node"),
            "The cheapest walk between two nodes (the CLI's walk): keywords cost ('constant', 'quality', "
            "'random', 'hybrid'), seed, min_frames, max_expansions, cleanup.")
      .def("path", &path, py::arg("points") = py::none(), py::arg("shape") = py::none(),
           py::arg("segments") = py::none(), py::arg("file") = py::none(),
           "Motion following a path on the floor (the CLI's path): exactly one of points ([(x, z), ...] metres), "
           "shape ('line:20', 'circle:5', 'figure8:4', 's-curve:100', 'square:10', 'zigzag:6') or file "
           "(PATH.json); segments ['TAG:FROM-TO', ...]; keywords horizon, commit, tag_penalty, tag_lookahead (0 to 1), max_expansions, "
           "beam, min_speed, transition_penalty, bridge_penalty, behind_penalty, progress_retries, retry_deviation (m), "
           "retry_horizon (s), retry_tag_match (0 to 1), "
           "start_node, path_edit (bend the motion onto the path, default True), edit_max_turn (degrees per "
           "metre it may add), edit_round_corners (m), rest_at_end (come to rest at the path's end, default False), "
           "cleanup, progress (called every 2 s of searching with how far "
           "along the path it has come; an exception it raises stops the search and is raised).")
      .def(
          "controller",
          [](const PyGraph& g, Real heading_deg, const std::optional<std::string>& tag, std::array<Real, 2> at,
             const py::kwargs& options) {
            const std::array<double, 2> start{at[0].value, at[1].value};
            return std::make_unique<PyController>(g, heading_deg.value, tag, start, options);
          },
          py::arg("heading_deg") = 0.0, py::arg("tag") = py::none(), py::arg("at") = std::array<double, 2>{0.0, 0.0},
          "A steering controller (the CLI's steer) starting at `at` (x, z) facing heading_deg (degrees clockwise "
          "from north, -z): keywords horizon, commit, tag_penalty, transition_penalty, bridge_penalty, tag_lookahead (0 "
          "to 1: the weight of what is still to pay before the tag past the horizon; with no tag, before a frame "
          "travelling at travel_pace), travel_pace (m/s along the "
          "heading asked of a walk with no tag; 0: none), travel_penalty, max_expansions, "
          "beam, time_budget, start_node, edit_max_turn (degrees per metre the heading edit may turn the motion "
          "toward the heading; 0: as the graph plays it), edit_turn_distance (m), edit_hold ('facing' or 'travel': "
          "what the heading edit holds on the heading), cleanup.");
}

}  // namespace mg::python
