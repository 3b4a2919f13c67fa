// A synthesis job from start to report, as the CLI's `walk` and `path` and the Python
// package run it: search, play the walk as motion, the foot clean-up (synthesis/foot_cleanup.h)
// unless turned off, and the JSON report (the CLI's --report: figures of the result, the
// clean-up's, timings, "foot_slide"). The motion is written with write_synthesized_motion().
#pragma once

#include <chrono>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "motiongraph/core/error.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/synthesis/controller.h"
#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/heading_edit.h"
#include "motiongraph/synthesis/path_synthesis.h"
#include "motiongraph/synthesis/synthesis_context.h"
#include "motiongraph/synthesis/walk_search.h"

namespace mg {

struct SynthesisRunSettings {
  bool cleanup = true;
  std::string cleanup_off_reason = "--no-cleanup";  // the report's reason when cleanup is false
  // Errors of the search name this (the graph file).
  std::string graph_name;
  // The report's "seconds" count from here (the CLI: before it reads the graph).
  std::chrono::steady_clock::time_point begin = std::chrono::steady_clock::now();
};

struct SynthesizedMotion {
  Motion motion;                      // on the context's target skeleton
  Walk walk;                          // the edges the motion plays
  std::vector<ContactMask> contacts;  // per frame, when the walk's own are not the motion's
  nlohmann::json report;
  // What the user should be told of the result, one line each, also the report's "warnings": a
  // path's segments asking for a motion type the graph can hardly play (unplayable_tag), why no
  // clean-up was made when one was asked for, a path's shortfalls.
  std::vector<std::string> warnings;
  // A path's: what it falls short of (path_shortfalls.h), also the report's "shortfalls".
  std::vector<std::string> shortfalls;
};

// The clean-up asked for: none when `settings.cleanup` is false, nor when the feet cannot be
// found (then `warning` says why).
std::optional<FootCleanup> make_cleanup(const SynthesisContext& context, const SynthesisRunSettings& settings,
                                        std::string& warning);
// The report's "cleanup": {"enabled": false, "reason": ...} or the clean-up's figures.
nlohmann::json cleanup_report(const SynthesisContext& context, const SynthesisRunSettings& settings,
                              const std::optional<FootCleanup>& cleanup);

// A steering report's "heading_edit": the edit's settings and what it did (heading_edit.h).
nlohmann::json heading_edit_report(const HeadingEditSettings& settings, const HeadingEditStats& stats);

// The report's "path_edit": whether the motion was edited onto the path and what the edit did
// (path_edit.h).
nlohmann::json path_edit_report(const PathSynthesisSettings& search, const PathSynthesisResult& result);
// The report's "segments": each of the path's segments as given (from_m, to_m, tag), the frames
// of the motion that fall in it and the share of them carrying its tag (null: none fell in it),
// and how many frames carry the tag in the graph's clip pieces ("graph_frames"; 0: the segment
// cannot be followed) and in the database's clips ("clip_frames": the pruning may keep none).
nlohmann::json path_segments_report(const SynthesisContext& context, const FloorPath& path,
                                    const PathSynthesisResult& result);
// When the graph plays `tag` in no frame (graph_frames_with: the pruning kept none of its
// clips' frames, or none carry it), or in less than a second of frames (subject 16's stop: 9 of
// its clips' 88, the ends of clips where nothing leads on), what to tell a user asking for it:
// "'run', which the graph plays in no frame (104 of its clips' frames carry it; ...)"; nullopt
// when it plays it or the tag is unknown (an error elsewhere).
std::optional<std::string> unplayable_tag(const SynthesisContext& context, const std::string& tag);
// For each of the path's segments asking for a motion type the graph can hardly play (above),
// what to tell the user: "the segment 0-20 m asks for 'run', which ...".
std::vector<std::string> segment_warnings(const SynthesisContext& context, const FloorPath& path);
// Where a motion came to rest (rest_endings.h), as reports give it: {"at_s", the "clip" at whose end
// it stands, "clip_frame" from which it stands, "held_frame"}; null without an ending.
nlohmann::json rest_report(const SynthesisContext& context, const RestEnding* ending, double at_s);
// Each time a steering session came to rest before frame `frames`, as rest_report gives it.
nlohmann::json rests_report(const SynthesisContext& context, const Controller& controller, long long frames);
// The starts from rest a steering session took (synthesis/rest_starts.h) before frame `frames`, as
// reports give them: [{"at_s", the "clip" it started off into, "clip_frame" of the lead-in's first
// frame, "node_frame" the graph went on from, "rms_cm" from the pose held (or the frames it was
// playing), "under_way": from its way to rest, the rest taken back before it stood}].
nlohmann::json starts_report(const SynthesisContext& context, std::span<const StartTaken> starts, long long frames);
// The seconds from which a steering session went on each time it took a rest back on its way
// there (Controller::rests_taken_back), before frame `frames`.
nlohmann::json rests_taken_back_report(const SynthesisContext& context, const Controller& controller,
                                       long long frames);

// Whether asking for `tag` asks the controller to rest (controller.h): it is stop, the graph plays
// it in less than a second (unplayable_tag) and has clips that end standing still to rest at.
bool stop_means_rest(const SynthesisContext& context, const std::string& tag);

// The cheapest walk from node `from` to node `to` (walk_search.h), starting at the origin
// facing north.
Result<SynthesizedMotion> run_walk_synthesis(const SynthesisContext& context, int from, int to,
                                             const WalkSearchSettings& walk, const SynthesisRunSettings& settings);
// Motion following `path` (path_synthesis.h).
Result<SynthesizedMotion> run_path_synthesis(const SynthesisContext& context, const FloorPath& path,
                                             const PathSynthesisSettings& search, const SynthesisRunSettings& settings);

// Writes the motion (.bvh, .glb, .gltf, .fbx or .json, export/motion_file.h); JSON gets the feet's contacts per
// frame: `contacts`, or when empty those of the frames `walk` plays.
// A root-motion joint asked for in `settings` faces the way the target skeleton faces (the
// context's forward axis, whatever the settings' own).
Status write_synthesized_motion(const std::string& path, const SynthesisContext& context, const Motion& motion,
                                const Walk& walk, std::vector<ContactMask> contacts = {},
                                MotionFileSettings settings = {});

}  // namespace mg
