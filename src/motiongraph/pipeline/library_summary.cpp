#include "motiongraph/pipeline/library_summary.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "motiongraph/motion/clip_summary.h"
#include "motiongraph/motion/up_axis.h"
#include "motiongraph/pipeline/build_report.h"
#include "motiongraph/pipeline/feet_report.h"

namespace mg {

namespace {

// Each tag's frames of the clip as runs of consecutive frames (ranges of one tag that overlap
// or touch merged), in tag order.
std::vector<ClipTagRun> tags_of_clip(const MotionDatabase& db, const DatabaseClip& clip) {
  std::vector<std::vector<bool>> covered(db.tag_names.size());
  for (const TagRange& range : db.tag_ranges) {
    const int first = std::max(range.first_frame, clip.first_frame);
    const int end = std::min(range.first_frame + range.frame_count, clip.first_frame + clip.frame_count);
    if (first >= end) continue;
    std::vector<bool>& frames = covered[static_cast<size_t>(range.tag)];
    frames.resize(static_cast<size_t>(clip.frame_count), false);
    for (int f = first; f < end; ++f) frames[static_cast<size_t>(f - clip.first_frame)] = true;
  }
  std::vector<ClipTagRun> runs;
  for (size_t t = 0; t < covered.size(); ++t) {
    const std::vector<bool>& frames = covered[t];
    for (size_t f = 0; f < frames.size();) {
      if (!frames[f]) {
        ++f;
        continue;
      }
      size_t end = f;
      while (end < frames.size() && frames[end]) ++end;
      runs.push_back({db.tag_names[t], static_cast<int>(f), static_cast<int>(end - f)});
      f = end;
    }
  }
  return runs;
}

// What loading chose by itself for each file (database_loader.h's notes).
nlohmann::json reading_json(const DatabaseLoadNotes& notes) {
  nlohmann::json units = nlohmann::json::array();
  for (const auto& [file, choice] : notes.detected_units) {
    units.push_back({{"file", file},
                     {"unit", choice.unit.name},
                     {"metres_per_unit", choice.unit.metres_per_unit},
                     {"figure_m", choice.figure_size_m},
                     {"plausible", choice.plausible},
                     {"also", choice.also ? nlohmann::json{{"unit", choice.also->name},
                                                           {"metres_per_unit", choice.also->metres_per_unit},
                                                           {"figure_m", choice.also_figure_size_m}}
                                          : nlohmann::json(nullptr)}});
  }
  nlohmann::json up_axes = nlohmann::json::array();
  for (const auto& detected : notes.detected_up_axes) {
    up_axes.push_back({{"file", detected.file},
                       {"axis", up_axis_name(detected.axis_read())},
                       {"own_axis", up_axis_name(detected.choice.axis)},
                       {"animation_ratio", detected.choice.animation_ratio},
                       {"rest_ratio", detected.choice.rest_ratio}});
  }
  nlohmann::json travel = nlohmann::json::array();
  for (const auto& recovered : notes.recovered_travels) {
    travel.push_back({{"file", recovered.file},
                      {"in_place", recovered.choice.in_place},
                      {"recovered_m", recovered.choice.recovered_m},
                      {"slide_m_s", recovered.choice.slide_speed_m_s},
                      {"root_m_s", recovered.choice.root_speed_m_s}});
  }
  nlohmann::json rest = nlohmann::json::array();
  for (const auto& r : notes.rest_frames) rest.push_back({{"file", r.file}, {"frames", r.frames}});
  nlohmann::json glitched = nlohmann::json::array();
  for (const auto& g : notes.glitched_ends) {
    glitched.push_back({{"file", g.file}, {"leading", g.leading}, {"trailing", g.trailing}});
  }
  nlohmann::json splits = nlohmann::json::array();
  for (const auto& g : notes.glitch_splits) {
    nlohmann::json glitches = nlohmann::json::array(), parts = nlohmann::json::array();
    for (const auto& glitch : g.glitches) {
      glitches.push_back(
          {{"frame", glitch.frame}, {"seconds", glitch.seconds}, {"joint", glitch.joint}, {"jump_m", glitch.jump_m}});
    }
    for (const auto& part : g.parts) {
      parts.push_back({{"clip", part.clip}, {"first_frame", part.first_frame}, {"last_frame", part.last_frame}});
    }
    splits.push_back({{"file", g.file},
                      {"clip", g.clip},
                      {"glitches", std::move(glitches)},
                      {"parts", std::move(parts)},
                      {"dropped_frames", g.dropped_frames}});
  }
  nlohmann::json rigs = nlohmann::json::array();
  for (const auto& rig : notes.matched_rigs) {
    nlohmann::json renamed = nlohmann::json::array();
    for (const auto& [own, library] : rig.renamed) renamed.push_back({own, library});
    rigs.push_back({{"file", rig.file},
                    {"renamed", std::move(renamed)},
                    {"rest_pose", rig.rest_pose ? nlohmann::json{{"bone", rig.rest_pose->bone},
                                                                 {"angle_deg", rig.rest_pose->angle_deg}}
                                                : nlohmann::json(nullptr)}});
  }
  nlohmann::json loops = nlohmann::json::array();
  for (const auto& loop : notes.loops) {
    loops.push_back({{"clip", loop.clip},
                     {"file", loop.file},
                     {"period_frames", loop.choice.period},
                     {"last_repeats_first", loop.choice.last_repeats_first},
                     {"seam_ratio", loop.choice.seam_ratio},
                     {"added_frames", loop.added_frames}});
  }
  nlohmann::json standing = nlohmann::json::array();
  for (const auto& t : notes.standing_tags) {
    standing.push_back({{"clip", t.clip}, {"tag", t.tag}, {"tagged_frames", t.tagged_frames}, {"frames", t.frames}});
  }
  nlohmann::json named = nlohmann::json::array();
  for (const auto& n : notes.name_tagged) {
    named.push_back({{"clip", n.clip}, {"tags", n.tags}, {"source", n.source}, {"words", n.words}});
  }
  nlohmann::json poses = nlohmann::json::array();
  for (const auto& p : notes.poses) poses.push_back({{"file", p.file}, {"frames", p.frames}, {"fps", p.fps}});
  nlohmann::json unreadable = nlohmann::json::array();
  for (const Error& e : notes.unreadable) {
    unreadable.push_back({{"file", e.file}, {"line", e.line}, {"error", e.message}});
  }
  nlohmann::json other_rigs = nlohmann::json::array();
  for (const auto& o : notes.other_rigs) other_rigs.push_back({{"files", o.files}, {"reason", o.reason}});
  nlohmann::json turning = turning_json(notes.turning);
  turning["too_long_to_mirror"] = notes.too_long_to_mirror;
  return {{"units", std::move(units)},
          {"up_axes", std::move(up_axes)},
          {"travel_recovered", std::move(travel)},
          {"rest_frames", std::move(rest)},
          {"glitched_ends", std::move(glitched)},
          {"glitch_splits", std::move(splits)},
          {"rigs", std::move(rigs)},
          {"other_rigs_left_out", std::move(other_rigs)},
          {"poses_passed_over", std::move(poses)},
          {"unreadable_passed_over", std::move(unreadable)},
          {"loops", std::move(loops)},
          {"standing_tags", std::move(standing)},
          {"name_tags", std::move(named)},
          {"turning", turning},
          {"mirrored", notes.mirrored},
          {"unmirrored", unmirrored_json(notes)}};
}

}  // namespace

LibrarySummary summarize_library(const MotionDatabase& db, const DatabaseLoadNotes& notes, bool feet_named) {
  LibrarySummary s;
  s.warnings = load_warnings(notes);
  s.notes = notes;
  for (const DatabaseClip& clip : db.clips) {
    s.clip_tags.push_back(tags_of_clip(db, clip));
    s.clip_travel_m.push_back(summarize(db.skeletons[static_cast<size_t>(clip.skeleton)], clip.motion).root_path_m);
    std::map<std::string, int> frames_of_tag;  // the runs of one tag do not overlap
    for (const ClipTagRun& run : s.clip_tags.back()) frames_of_tag[run.tag] += run.frame_count;
    for (const auto& [name, frames] : frames_of_tag) {
      s.tags[name].clips += 1;
      s.tags[name].frames += frames;
    }
    if (s.clip_tags.back().empty()) {
      s.untagged.clips += 1;
      s.untagged.frames += clip.frame_count;
    }
  }
  // One skeleton per ASF or BVH file, but an ASF read both y and z up is two.
  for (const std::string& file : db.skeleton_names) {
    if (std::find(s.skeleton_files.begin(), s.skeleton_files.end(), file) == s.skeleton_files.end()) {
      s.skeleton_files.push_back(file);
    }
  }
  s.feet_source = feet_named ? "--feet" : db.foot_names.empty() ? "found by name" : "the manifest's [feet]";
  // Every skeleton of a database has the same joints, so the first one's feet are every clip's.
  const auto feet = db.skeletons.empty() ? Result<FootJoints>(Error{"", 0, "no skeleton"})
                                         : find_foot_joints(db.skeletons.front(), db.foot_names);
  if (feet && !db.frame_contacts.empty()) {
    s.feet = *feet;
  } else {
    s.feet_missing = db.contacts_error.empty() && !feet ? feet.error().message : db.contacts_error;
  }
  return s;
}

std::string clip_tags_text(std::span<const ClipTagRun> runs, int clip_frames) {
  std::vector<std::string> parts;
  for (const ClipTagRun& run : runs) {
    if (run.frame_count == clip_frames) {
      parts.push_back(run.tag);
    } else {
      parts.push_back(fmt::format("{} {}-{}", run.tag, run.first_frame, run.first_frame + run.frame_count - 1));
    }
  }
  return parts.empty() ? "-" : fmt::format("{}", fmt::join(parts, ", "));
}

nlohmann::json library_summary_json(std::span<const std::string> inputs, const MotionDatabase& db,
                                    const LibrarySummary& summary) {
  nlohmann::json tags = nlohmann::json::object();
  for (const auto& [tag, total] : summary.tags) {
    tags[tag] = {{"clips", total.clips}, {"frames", total.frames}, {"seconds", total.frames / db.fps}};
  }
  // The clips as the build report lists them, with their length, travel and tag ranges.
  nlohmann::json clips = clips_json(db);
  for (size_t c = 0; c < db.clips.size(); ++c) {
    nlohmann::json ranges = nlohmann::json::array();
    for (const ClipTagRun& run : summary.clip_tags[c]) {
      ranges.push_back({{"tag", run.tag}, {"first_frame", run.first_frame}, {"frames", run.frame_count}});
    }
    clips[c]["duration_s"] = std::max(0, db.clips[c].frame_count - 1) / db.fps;  // as a file's: first frame to last
    clips[c]["root_path_m"] = summary.clip_travel_m[c];
    clips[c]["tag_ranges"] = std::move(ranges);
  }
  add_clip_doubts(clips, db, summary.notes.clip_doubts);  // as info says them of a file
  add_mirror_of(clips, db, summary.notes);
  return {{"inputs", std::vector<std::string>(inputs.begin(), inputs.end())},
          {"fps", db.fps},
          {"frames", db.frame_count()},
          {"duration_s", db.frame_count() / db.fps},
          {"skeletons", db.skeleton_names},
          {"tags", std::move(tags)},
          {"untagged", {{"clips", summary.untagged.clips}, {"frames", summary.untagged.frames}}},
          {"feet", summary.feet ? feet_json(db.skeletons.front(), *summary.feet, db.frame_contacts, summary.feet_source)
                                : missing_feet_json(summary.feet_missing)},
          {"foot_contacts", foot_contacts_json(db)},
          {"clips", std::move(clips)},
          {"reading", reading_json(summary.notes)},
          {"warnings", summary.warnings}};
}

}  // namespace mg
