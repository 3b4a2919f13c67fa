// motiongraph steer GRAPH --script CONTROLS.json -o OUT: replays a timed control script
// through the interactive controller (synthesis/controller.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/synthesis_options.h"
#include "motiongraph/core/transition_rate.h"
#include "motiongraph/evaluation/foot_slide_report.h"
#include "motiongraph/evaluation/path_shortfalls.h"
#include "motiongraph/evaluation/played_clips.h"
#include "motiongraph/evaluation/steering_controls.h"
#include "motiongraph/evaluation/synthesis_run.h"
#include "motiongraph/io/file.h"
#include "motiongraph/synthesis/control_script.h"
#include "motiongraph/synthesis/controller.h"
#include "motiongraph/synthesis/walk.h"

namespace mg::cli {

namespace {

struct SteerOptions {
  SynthesisOptions common;
  std::string script;
  ControllerSettings settings;
  double tolerance_deg = 20.0;
};

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t i = std::min(values.size() - 1, static_cast<size_t>(std::ceil(q * values.size())) - 1);
  return values[i];
}

int run_steer(const SteerOptions& o) {
  if (auto s = o.settings.validate(); !s) return fail_usage(s.error());
  if (auto s = check_output_options(o.common); !s) return fail_usage(s.error());
  auto text = read_text_file(o.script);
  if (!text) return fail(text.error());
  auto script = parse_control_script(*text, o.script);
  if (!script) return fail(script.error());
  auto loaded = load_for_synthesis(o.common, {o.script});
  if (!loaded) return fail(loaded.error());
  const SynthesisContext& context = (*loaded)->context();
  // Each control's input, in order (found once: a stop's costs run over the graph's edges); what
  // the graph cannot give is warned of once, and every warning goes into the report too.
  SteeringControls reader(context);
  std::vector<std::string> warnings;
  auto warn = [&warnings](std::string line) {
    spdlog::warn("{}", line);
    warnings.push_back(std::move(line));
  };
  // Tags as the graph spells them ("Walk" is walk), so that the report compares and names them so.
  for (ScriptedControl& c : script->controls) {
    if (auto name = context.tag_name(c.tag); !c.tag.empty() && name) c.tag = *name;
  }
  std::vector<ControlInput> inputs;
  for (const ScriptedControl& c : script->controls) {
    auto input = reader.input({c.bearing_deg, c.tag, c.rest}, fmt::format("the control at {:g} s", c.at_s));
    if (!input) return fail(Error{o.script, 0, input.error().message});
    inputs.push_back(*input);
  }
  for (const std::string& line : reader.warnings()) warn(line);
  auto input_at = [&](double t) { return inputs[static_cast<size_t>(&script->at(t) - script->controls.data())]; };
  auto controller = Controller::create(context, o.settings, input_at(0.0));
  if (!controller) return fail(controller.error());
  Motion motion = context.assembler.empty_motion();
  const double fps = context.db->fps;
  const int total = static_cast<int>(std::lround(script->duration_s * fps));
  if (total < 1) {
    return fail(Error{o.script, 0, fmt::format("duration_s {:g} is shorter than a frame at {:g} fps",
                                                    script->duration_s, fps)});
  }
  std::vector<double> latencies;
  int exhausted = 0;
  int transitions = 0;  // transition edges that start within the script's duration
  int bridges = 0;      // of which bridges
  Walk played{-1, {}};  // every edge the controller chose (for the clips the motion is cut from)
  const SynthesisRunSettings run = run_settings(o.common, std::chrono::steady_clock::now());
  std::string cleanup_warning;
  auto cleanup = make_cleanup(context, run, cleanup_warning);
  if (!cleanup_warning.empty()) warn(cleanup_warning);
  std::vector<ContactMask> all_contacts;
  std::vector<FrameSource> played_sources;  // each frame's, in order (decision_sources)
  std::vector<double> cleanup_seconds;
  std::vector<double> took_way_s;  // the seconds at which decisions took the way to rest
  while (motion.frame_count < total) {
    controller->set_input(input_at(motion.frame_count / fps));
    long long edge_start = motion.frame_count;
    const int first_new = motion.frame_count;
    const bool was_resting = controller->resting();
    const ControllerDecision d = controller->step(motion);
    if (!was_resting && controller->resting()) took_way_s.push_back(first_new / fps);
    const std::vector<ContactMask>& contacts = d.contacts;
    all_contacts.insert(all_contacts.end(), contacts.begin(), contacts.end());
    if (cleanup) {
      // The decision's frames, cleaned as a game would before showing them.
      const auto cleanup_begin = std::chrono::steady_clock::now();
      if (auto s = cleanup->clean(motion, first_new, contacts); !s) return fail(s.error());
      cleanup_seconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - cleanup_begin).count());
    }
    latencies.push_back(d.search_seconds);
    exhausted += d.budget_exhausted ? 1 : 0;
    played.edges.insert(played.edges.end(), d.edges.begin(), d.edges.end());
    const std::vector<FrameSource> sources = decision_sources(context, d);
    played_sources.insert(played_sources.end(), sources.begin(), sources.end());
    // (a start from rest is a blend too)
    if (!d.start_frames.empty() && edge_start < total) ++transitions;
    edge_start += static_cast<long long>(d.start_frames.size());
    for (int e : d.edges) {
      const GraphEdge& edge = context.graph->edges[e];
      if (edge.transition && edge_start < total) ++transitions;
      if (edge.bridge && edge_start < total) ++bridges;
      edge_start += edge.frame_count;
    }
  }
  motion = motion.slice(0, total);
  // Response: the first frame after a control whose facing is within the tolerance of it; for a
  // control that changes the tag, the first that carries it.
  nlohmann::json controls = nlohmann::json::array();
  std::string tag_before;
  bool rest_before = false;
  // The seconds from which the character stood still each time it came to rest within the script;
  // the last one's (-1: none).
  std::vector<double> rests_s;
  for (long long f : controller->rest_frames()) {
    if (f < motion.frame_count) rests_s.push_back(static_cast<double>(f) / fps);
  }
  const double rest_s = rests_s.empty() ? -1.0 : rests_s.back();
  // Controls after a rest for good: nothing moves the character. Otherwise a turn asked with rest
  // while it stands is not heard (a move starts it off).
  const bool for_good = controller->rest_is_for_good() && rest_s >= 0.0;
  std::vector<double> starts_s;
  for (const StartTaken& start : controller->starts()) {
    if (start.frame < motion.frame_count) starts_s.push_back(static_cast<double>(start.frame) / fps);
  }
  auto standing_at = [&](double t) {
    double stood = -1.0;
    for (const double r : rests_s) stood = r <= t ? r : stood;
    return stood >= 0.0 &&
           std::none_of(starts_s.begin(), starts_s.end(), [&](double s) { return s >= stood && s <= t; });
  };
  std::vector<double> unheard_s, turns_at_rest_s;
  for (size_t i = 0; i < script->controls.size(); ++i) {
    const ScriptedControl& c = script->controls[i];
    const bool rest = inputs[i].rest;
    nlohmann::json tag_response = nullptr;
    // (a stop the graph has no tag for was rest: no tag to reach)
    const Result<TagMask> asked = context.tag_mask(c.tag);
    const bool changes_tag = !c.tag.empty() && c.tag != tag_before && asked.ok();
    // The first motion frame from which a later control asks for something else than control i
    // (`same` says whether it asks the same): what is reached after that was asked again.
    auto asked_until = [&](auto same) {
      double until_s = script->duration_s;
      for (size_t j = i + 1; j < script->controls.size(); ++j) {
        if (!same(script->controls[j])) {
          until_s = script->controls[j].at_s;
          break;
        }
      }
      return std::min(motion.frame_count, static_cast<int>(std::ceil(until_s * fps)));
    };
    if (changes_tag) {
      const int until = asked_until([&](const ScriptedControl& later) { return later.tag == c.tag; });
      const TagMask mask = *asked;
      for (int f = static_cast<int>(std::ceil(c.at_s * fps)); f < until; ++f) {
        if ((context.frame_tag(played_sources[static_cast<size_t>(f)].dominant()) & mask) != 0) {
          tag_response = f / fps - c.at_s;
          break;
        }
      }
    }
    tag_before = c.tag;
    const Vec2 want = bearing_direction(c.bearing_deg);
    nlohmann::json response = nullptr;
    const int heading_until =
        asked_until([&](const ScriptedControl& later) { return later.bearing_deg == c.bearing_deg; });
    for (int f = static_cast<int>(std::ceil(c.at_s * fps)); f < heading_until; ++f) {
      const Vec2 facing = facing_on_floor(motion.rotations(f)[0], context.tracks.forward_axis);
      if (facing.dot(want) >= std::cos(o.tolerance_deg * std::numbers::pi / 180.0)) {
        response = f / fps - c.at_s;
        break;
      }
    }
    nlohmann::json control = {{"at_s", c.at_s}, {"heading_deg", c.bearing_deg}, {"tag", c.tag}, {"response_s", response}};
    if (changes_tag) control["tag_response_s"] = tag_response;
    control["rest"] = rest;
    if (rest && !rest_before && !context.rest().empty()) {
      // The first time it stands from the control on, before a later control asks for rest again
      // after one took it back (that rest is that control's; a rest taken back before it stood,
      // its stopping clip under way too, is none; a rest that came before it: it stood already).
      const auto back = std::find_if(inputs.begin() + static_cast<long>(i) + 1, inputs.end(),
                                     [](const ControlInput& later) { return !later.rest; });
      const bool taken_back = back != inputs.end();
      const auto again =
          taken_back ? std::find_if(back + 1, inputs.end(), [](const ControlInput& later) { return later.rest; })
                     : inputs.end();
      const double until_s = again != inputs.end() ? script->controls[static_cast<size_t>(again - inputs.begin())].at_s
                                                   : std::numeric_limits<double>::infinity();
      const auto first =
          std::find_if(rests_s.begin(), rests_s.end(), [&](double r) { return r >= c.at_s && r < until_s; });
      control["rest_response_s"] = first != rests_s.end() ? nlohmann::json(*first - c.at_s)
                                   : !taken_back && !rests_s.empty() && controller->resting() ? nlohmann::json(0.0)
                                                                                              : nlohmann::json(nullptr);
      // Taken back before it stood: said in the summary, and whether it was heard at all (a
      // decision whose frames ran past both the asking and the taking back never saw it).
      const double back_s =
          taken_back ? script->controls[static_cast<size_t>(back - inputs.begin())].at_s : script->duration_s;
      control["rest_taken_back"] = control["rest_response_s"].is_null() && taken_back;
      control["rest_heard"] =
          !control["rest_response_s"].is_null() || (!taken_back && controller->resting()) ||
          std::any_of(took_way_s.begin(), took_way_s.end(), [&](double t) { return t >= c.at_s - 1e-9 && t < back_s; });
      if (control["rest_response_s"].is_null() && !taken_back) {
        warn(fmt::format("the control at {:g} s asks to rest, but the character does not stand before the script "
                         "ends at {:g} s (duration_s is too short for the way to rest)",
                         c.at_s, script->duration_s));
      }
    }
    // (asking only to rest on is heard: a turn or a move is not)
    const bool turns = i > 0 && c.bearing_deg != script->controls[i - 1].bearing_deg;
    if (for_good && c.at_s >= rest_s && (!rest || turns)) {
      unheard_s.push_back(c.at_s);
    } else if (rest && turns && standing_at(c.at_s)) {
      turns_at_rest_s.push_back(c.at_s);
    }
    rest_before = rest;
    controls.push_back(std::move(control));
  }
  // Each time it stood: which way, against the heading of the control in force then (a rest taken
  // back, or asked again facing elsewhere, is not judged by its first asking).
  for (const double r : rests_s) {
    const auto in_force = static_cast<size_t>(&script->at(r) - script->controls.data());
    if (!inputs[in_force].rest) continue;
    const ScriptedControl& c = script->controls[in_force];
    const int still = std::min(motion.frame_count - 1, static_cast<int>(std::lround(r * fps)));
    const double off_deg =
        facing_off_deg(motion.rotations(still)[0], context.tracks.forward_axis, bearing_direction(c.bearing_deg));
    if (off_deg > kRestFacingWarnDeg) {
      warn(fmt::format("the control at {:g} s asks to rest facing {:g} degrees; the character stands {:.0f} degrees "
                       "off it (the stopping clip's last steps turn only so far, and the way to rest is the cheapest, "
                       "whichever way it faces)",
                       c.at_s, c.bearing_deg, off_deg));
    }
  }
  nlohmann::json rested = rest_report(context, controller->rest_ending(),
                                      static_cast<double>(controller->rest_frame()) / fps);
  if (!rested.is_null() && rest_s < 0.0) rested["at_s"] = nullptr;  // it stands only after the script's end
  if (!unheard_s.empty()) {
    warn(fmt::format("the character came to rest at {:.2f} s, at the end of {}, and stays there: the control{} at {} "
                     "s cannot turn or move it (the graph has no way on from that clip's last frame, and no clip "
                     "the graph goes on from has the half second to start off from it)",
                     rest_s, rested["clip"].get<std::string>(), unheard_s.size() == 1 ? "" : "s",
                     fmt::join(unheard_s, ", ")));
  }
  if (!turns_at_rest_s.empty()) {
    warn(fmt::format("the control{} at {} s ask{} to turn while the character stands at rest, which it does not: it "
                     "turns on its way to rest and as it starts off (a control that asks it to move)",
                     turns_at_rest_s.size() == 1 ? "" : "s", fmt::join(turns_at_rest_s, ", "),
                     turns_at_rest_s.size() == 1 ? "s" : ""));
  }
  // The seconds from which it went on each time it took a rest back on its way there.
  const nlohmann::json taken_back_s = rests_taken_back_report(context, *controller, motion.frame_count);
  const HeadingEditStats& edit_stats = controller->heading_edit_stats();
  const nlohmann::json report = {{"frames", motion.frame_count},
                                 {"fps", fps},
                                 {"transitions", transitions},
                                 {"transitions_per_second", transitions_per_second(transitions, motion.frame_count, fps)},
                                 {"bridges", bridges},
                                 {"edges", played.edges},
                                 {"played", played_clips_json(*context.db, played_sources, fps, motion.frame_count)},
                                 {"decisions", latencies.size()},
                                 {"decision_ms_p50", 1e3 * percentile(latencies, 0.5)},
                                 {"decision_ms_p99", 1e3 * percentile(latencies, 0.99)},
                                 {"decision_ms_max", 1e3 * percentile(latencies, 1.0)},
                                 {"budget_exhausted_decisions", exhausted},
                                 {"tolerance_deg", o.tolerance_deg},
                                 {"heading_edit", heading_edit_report(o.settings.heading_edit, edit_stats)},
                                 {"cleanup", cleanup_report(context, run, cleanup)},
                                 {"cleanup_ms_p99", cleanup ? nlohmann::json(1e3 * percentile(cleanup_seconds, 0.99))
                                                            : nlohmann::json(nullptr)},
                                 {"controls", controls},
                                 {"rest", rested},
                                 {"rests", rests_report(context, *controller, motion.frame_count)},
                                 {"starts", starts_report(context, controller->starts(), motion.frame_count)},
                                 {"rests_taken_back_s", taken_back_s},
                                 {"foot_slide", foot_slide_report(context, played, motion, played_sources)},
                                 {"warnings", warnings}};
  if (auto s = write_synthesis_outputs(o.common, **loaded, motion, played, report, all_contacts); !s) return fail(s.error());
  fmt::print("steer: {} frames ({:.1f} s), {} decisions, decision p99 {:.3f} ms\n", motion.frame_count,
             motion.frame_count / fps, latencies.size(), 1e3 * percentile(latencies, 0.99));
  for (const auto& c : controls) {
    std::string tag_reached;
    if (c.contains("tag_response_s")) {
      tag_reached = c["tag_response_s"].is_null()
                        ? fmt::format(", no {}", c["tag"].get<std::string>())
                        : fmt::format(", {} after {:.2f} s", c["tag"].get<std::string>(), c["tag_response_s"].get<double>());
    }
    if (c.contains("rest_response_s")) {
      tag_reached += !c["rest_response_s"].is_null()
                         ? fmt::format(", at rest after {:.2f} s", c["rest_response_s"].get<double>())
                     : c["rest_taken_back"].get<bool>()
                         ? std::string(c["rest_heard"].get<bool>() ? ", rest taken back before it stood"
                                                                   : ", rest taken back before a decision heard it")
                         : std::string(", not at rest");
    }
    // What it asked: the tag (any), and rest when it means rest ("stop, rest": a stop heard as rest).
    const std::string tag = c["tag"].get<std::string>();
    const std::string asked = !c["rest"].get<bool>() ? (tag.empty() ? "any" : tag)
                              : tag.empty()          ? "rest"
                                                     : tag + ", rest";
    fmt::print("  at {:5.1f} s heading {:5.1f} deg {:<6} -> {}{}\n", c["at_s"].get<double>(), c["heading_deg"].get<double>(),
               asked,
               c["response_s"].is_null() ? std::string("not reached")
                                         : fmt::format("facing it after {:.2f} s", c["response_s"].get<double>()),
               tag_reached);
  }
  for (const nlohmann::json& back : taken_back_s) {
    const double t = back.get<double>();
    const bool by_start = std::any_of(report["starts"].begin(), report["starts"].end(), [&](const nlohmann::json& s) {
      return s["under_way"].get<bool>() && std::abs(s["at_s"].get<double>() - t) < 1e-9;
    });
    if (!by_start) fmt::print("  went on from its way to rest at {:.2f} s, on through the graph from the stop\n", t);
  }
  for (const auto& start : report["starts"]) {
    if (start["under_way"].get<bool>()) {
      fmt::print("  went on from its way to rest at {:.2f} s into {} (its first frames {:.1f} cm from the stop's)\n",
                 start["at_s"].get<double>(), start["clip"].get<std::string>(), start["rms_cm"].get<double>());
    } else {
      fmt::print("  started off from rest at {:.2f} s into {} (its first frames {:.1f} cm from the pose held)\n",
                 start["at_s"].get<double>(), start["clip"].get<std::string>(), start["rms_cm"].get<double>());
    }
  }
  return 0;
}

}  // namespace

Command add_steer_command(CLI::App& app) {
  auto o = std::make_shared<SteerOptions>();
  CLI::App* sub = app.add_subcommand(
      "steer", "Replay a timed control script through the interactive controller and write the motion.\n"
               "CONTROLS.json: {\"duration_s\": 12, \"controls\": [{\"at_s\": 0, \"heading\": \"north\", \"tag\":\n"
               "\"walk\"}, {\"at_s\": 4, \"heading_deg\": 90}, {\"at_s\": 8, \"tag\": \"run\"}]};\n"
               "\"heading\": north (-z), east (+x), south or west, or \"heading_deg\": degrees clockwise from\n"
               "north; a key left out keeps the control before's; without duration_s, the motion ends 4 s after\n"
               "the last control. {\"at_s\": 10, \"rest\": true} comes to rest at the end of a clip that ends\n"
               "standing still (as does a stop the graph can hardly play or has no tag for); a later \"rest\":\n"
               "false starts it off again, or takes the rest back on its way there (the report's \"starts\").");
  o->common.add_to(*sub);
  sub->add_option("--script", o->script, "CONTROLS.json")->required()->check(CLI::ExistingFile);
  sub->add_option("--horizon", o->settings.horizon_s, "Seconds each decision looks ahead")->capture_default_str();
  sub->add_option("--commit", o->settings.commit_s, "Seconds of motion each decision commits")->capture_default_str();
  sub->add_option("--max-expansions", o->settings.max_expansions, "Search budget per decision")->capture_default_str();
  sub->add_option("--transition-penalty", o->settings.transition_penalty,
                  "Cost of each transition taken, in frames facing 90 degrees off (0: none)")
      ->capture_default_str();
  sub->add_option("--bridge-penalty", o->settings.bridge_penalty,
                  "Cost of each bridge (a blend between motion types above the threshold) taken, on top of "
                  "--transition-penalty, unless it leads into the tag asked for, in frames facing 90 degrees off (0: as "
                  "any transition)")
      ->capture_default_str();
  sub->add_option("--tag-lookahead", o->settings.tag_lookahead,
                  "Weight (0 to 1) of what a walk that reaches the horizon still pays before the tag asked for (its "
                  "frames without it, the transitions and bridges on the way), so that a tag beyond the horizon is "
                  "headed for; with no tag asked, before a frame that travels at --travel-pace (0: the horizon only)")
      ->capture_default_str();
  sub->add_option("--travel-pace", o->settings.travel_mps,
                  "With no tag asked, metres a second along the heading each decision asks of a walk (0: none; a "
                  "walk that faces the way asked but stands in place is then as good as one that goes)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 20.0));
  sub->add_option("--travel-penalty", o->settings.travel_penalty,
                  "Cost per frame of each metre a walk is behind --travel-pace, in frames facing 90 degrees off")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1000.0));
  sub->add_option("--beam", o->settings.beam_width,
                  "Beam width of each decision's first pass (0: depth-first branch and bound alone)")
      ->capture_default_str();
  sub->add_option("--time-budget", o->settings.time_budget_s, "Wall-clock seconds per decision (0: expansions only, the same motion on any machine)")
      ->capture_default_str();
  sub->add_option("--edit-max-turn", o->settings.heading_edit.max_turn_deg_per_m,
                  "Degrees per metre travelled the heading edit may turn the motion toward the heading asked for "
                  "(0: as the graph plays it)")
      ->capture_default_str();
  sub->add_option("--edit-turn-distance", o->settings.heading_edit.turn_distance_m,
                  "Metres travelled over which the heading edit takes out the facing's error (about)")
      ->capture_default_str();
  sub->add_option_function<std::string>(
         "--edit-hold", [o](const std::string& hold) { o->settings.heading_edit.hold_travel = hold == "travel"; },
         "What the heading edit holds on the heading: 'facing', the body's facing, or 'travel', the direction the "
         "root travels over a second where it walks roughly where it faces (blended in by speed and angle, else the facing; the "
         "search judges it too): held walks go straighter, but on some libraries change piece more often (docs/performance.md)")
      ->check(CLI::IsMember({"travel", "facing"}))
      ->default_str("facing");
  sub->add_option("--tolerance", o->tolerance_deg, "Report: degrees within which a heading counts as reached")
      ->capture_default_str();
  return {sub, [o] { return run_steer(*o); }};
}

}  // namespace mg::cli
