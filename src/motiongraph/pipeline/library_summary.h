// A library summarised as `build` reads it (database/database_loader.h): its clips at the
// database's rate with their tags and travel, the tags' totals, the skeleton files, the feet
// found and how often each is planted, and what loading chose or doubts. What `info
// FOLDER|MANIFEST` prints and Python's load_library() gives.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "motiongraph/database/database_loader.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg {

// A run of consecutive frames of a clip under one tag, in the clip's own frames.
struct ClipTagRun {
  std::string tag;
  int first_frame = 0;
  int frame_count = 0;
};

struct TagTotal {
  int clips = 0;
  int frames = 0;
};

struct LibrarySummary {
  std::vector<std::vector<ClipTagRun>> clip_tags;  // per clip: each tag's runs (overlaps merged), in tag order
  std::vector<double> clip_travel_m;               // per clip: the root's path over the floor
  std::map<std::string, TagTotal> tags;            // clips and frames under each tag
  TagTotal untagged;                               // clips with no tag at all
  std::vector<std::string> skeleton_files;         // each once, in the order first read
  std::optional<FootJoints> feet;                  // every clip's (they share the joints)
  std::string feet_source;                         // "found by name", "--feet", "the manifest's [feet]"
  std::string feet_missing;                        // why there are none, when feet is empty
  std::vector<std::string> warnings;               // load_warnings(notes)
  DatabaseLoadNotes notes;                         // what loading chose by itself, per file
};

// feet_named: the feet were named by the caller (--feet), not found by name or in a manifest.
LibrarySummary summarize_library(const MotionDatabase& db, const DatabaseLoadNotes& notes, bool feet_named);

// "walk" for a tag on the whole clip, "walk 12-40" for one on its frames 12 to 40, "-" for none.
std::string clip_tags_text(std::span<const ClipTagRun> runs, int clip_frames);

// {inputs, fps, frames, duration_s, skeletons, tags: {TAG: {clips, frames, seconds}},
// untagged: {clips, frames}, feet, foot_contacts, clips: [build report's clips with duration_s,
// root_path_m, tag_ranges, doubts (what looks wrong with it as read: phrases, as info's of a
// file)], reading: {units: [{file, unit, metres_per_unit, figure_m,
// plausible}], up_axes: [{file, axis, own_axis, animation_ratio, rest_ratio}], travel_recovered:
// [{file, in_place, recovered_m, slide_m_s, root_m_s}], rest_frames: [{file, frames}],
// glitched_ends: [{file, leading, trailing}], glitch_splits: [{file, clip, glitches: [{frame,
// seconds, joint, jump_m}], parts: [{clip, first_frame, last_frame}], dropped_frames}], rigs:
// [{file, renamed: [[its name, the library's], ...], rest_pose: {bone, angle_deg} or null}],
// loops: [{clip, file, period_frames (the file's), last_repeats_first, seam_ratio, added_frames
// (the library's)}], standing_tags: [{clip, tag, tagged_frames, frames}]} (files read without
// --scale, without --up-axis, clips whose travel came from their feet, BVH files whose leading
// rest/T-pose frames were dropped (at the file's rate), files whose ends a capture glitch cut
// off (frames at the file's rate), clips cut at capture glitches within them (the file's frames,
// 1-based, and seconds from its start), files read as the first file's rig,
// clips that loop, clips whose description's walk or run was left off where they stand),
// warnings}: `info --json` on a library.
nlohmann::json library_summary_json(std::span<const std::string> inputs, const MotionDatabase& db,
                                    const LibrarySummary& summary);

}  // namespace mg
