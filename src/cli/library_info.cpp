#include "cli/library_info.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/feet_report.h"
#include "cli/unit_report.h"
#include "motiongraph/core/json_text.h"
#include "motiongraph/motion/clip_summary.h"
#include "motiongraph/pipeline/build_report.h"

namespace mg::cli {

namespace {

// A tag on (part of) a clip, in the clip's own frames at the database's rate.
struct ClipTag {
  std::string name;
  int first_frame = 0;
  int frame_count = 0;
};

// Each tag's frames of the clip as runs of consecutive frames (ranges of one tag that overlap
// or touch merged), in tag order.
std::vector<ClipTag> tags_of_clip(const MotionDatabase& db, const DatabaseClip& clip) {
  std::vector<std::vector<bool>> covered(db.tag_names.size());
  for (const TagRange& range : db.tag_ranges) {
    const int first = std::max(range.first_frame, clip.first_frame);
    const int end = std::min(range.first_frame + range.frame_count, clip.first_frame + clip.frame_count);
    if (first >= end) continue;
    std::vector<bool>& frames = covered[static_cast<size_t>(range.tag)];
    frames.resize(static_cast<size_t>(clip.frame_count), false);
    for (int f = first; f < end; ++f) frames[static_cast<size_t>(f - clip.first_frame)] = true;
  }
  std::vector<ClipTag> tags;
  for (size_t t = 0; t < covered.size(); ++t) {
    const std::vector<bool>& frames = covered[t];
    for (size_t f = 0; f < frames.size();) {
      if (!frames[f]) {
        ++f;
        continue;
      }
      size_t end = f;
      while (end < frames.size() && frames[end]) ++end;
      tags.push_back({db.tag_names[t], static_cast<int>(f), static_cast<int>(end - f)});
      f = end;
    }
  }
  return tags;
}

// "walk" for a tag on the whole clip, "walk 12-40" for one on its frames 12 to 40.
std::string clip_tags_text(const std::vector<ClipTag>& tags, const DatabaseClip& clip) {
  std::vector<std::string> parts;
  for (const ClipTag& tag : tags) {
    if (tag.frame_count == clip.frame_count) {
      parts.push_back(tag.name);
    } else {
      parts.push_back(fmt::format("{} {}-{}", tag.name, tag.first_frame, tag.first_frame + tag.frame_count - 1));
    }
  }
  return parts.empty() ? "-" : fmt::format("{}", fmt::join(parts, ", "));
}

struct TagTotal {
  int clips = 0;
  int frames = 0;
};

}  // namespace

int run_library_info(const std::vector<std::string>& inputs, const LibraryInfoOptions& options) {
  DatabaseLoadNotes notes;
  auto loaded = load_database(inputs, options.database, &notes);
  if (!loaded) return fail(loaded.error());
  const MotionDatabase& db = *loaded;
  report_units(notes, false);
  const std::vector<std::string> warnings = load_warnings(notes);
  if (!options.json) {
    for (const std::string& line : warnings) spdlog::warn("{}", line);
  }

  // Per clip, and the tags' totals (clips and frames under each tag).
  std::map<std::string, TagTotal> totals;
  int untagged_clips = 0, untagged_frames = 0;
  std::vector<std::vector<ClipTag>> clip_tags;
  std::vector<ClipSummary> summaries;
  for (const DatabaseClip& clip : db.clips) {
    clip_tags.push_back(tags_of_clip(db, clip));
    summaries.push_back(summarize(db.skeletons[static_cast<size_t>(clip.skeleton)], clip.motion));
    std::map<std::string, int> frames_of_tag;  // the runs of one tag do not overlap
    for (const ClipTag& tag : clip_tags.back()) frames_of_tag[tag.name] += tag.frame_count;
    for (const auto& [name, frames] : frames_of_tag) {
      totals[name].clips += 1;
      totals[name].frames += frames;
    }
    if (clip_tags.back().empty()) {
      ++untagged_clips;
      untagged_frames += clip.frame_count;
    }
  }
  const std::string feet_source = !options.database.foot_names.empty() ? "--feet"
                                  : db.foot_names.empty()                ? "found by name"
                                                                         : "the manifest's [feet]";
  // Every skeleton of a database has the same joints, so the first one's feet are every clip's.
  const auto feet = db.skeletons.empty() ? Result<FootJoints>(Error{"", 0, "no skeleton"})
                                         : find_foot_joints(db.skeletons.front(), db.foot_names);
  const bool have_feet = feet && !db.frame_contacts.empty();
  const std::string feet_missing = db.contacts_error.empty() && !feet ? feet.error().message : db.contacts_error;
  const double seconds = db.frame_count() / db.fps;
  const std::string name =
      inputs.size() <= 2 ? fmt::format("{}", fmt::join(inputs, ", "))
                         : fmt::format("{} and {} more", inputs.front(), inputs.size() - 1);

  if (options.json) {
    nlohmann::json tags = nlohmann::json::object();
    for (const auto& [tag, total] : totals) {
      tags[tag] = {{"clips", total.clips}, {"frames", total.frames}, {"seconds", total.frames / db.fps}};
    }
    // The clips as the build report lists them, with their length, travel and tag ranges.
    nlohmann::json clips = clips_json(db);
    for (size_t c = 0; c < db.clips.size(); ++c) {
      const DatabaseClip& clip = db.clips[c];
      nlohmann::json ranges = nlohmann::json::array();
      for (const ClipTag& tag : clip_tags[c]) {
        ranges.push_back({{"tag", tag.name}, {"first_frame", tag.first_frame}, {"frames", tag.frame_count}});
      }
      clips[c]["duration_s"] = clip.frame_count / db.fps;
      clips[c]["root_path_m"] = summaries[c].root_path_m;
      clips[c]["tag_ranges"] = std::move(ranges);
    }
    const nlohmann::json doc = {
        {"inputs", inputs},
        {"fps", db.fps},
        {"frames", db.frame_count()},
        {"duration_s", seconds},
        {"skeletons", db.skeleton_names},
        {"tags", std::move(tags)},
        {"untagged", {{"clips", untagged_clips}, {"frames", untagged_frames}}},
        {"feet", have_feet ? feet_json(db.skeletons.front(), *feet, db.frame_contacts, feet_source)
                           : missing_feet_json(feet_missing)},
        {"foot_contacts", foot_contacts_json(db)},
        {"clips", std::move(clips)},
        {"warnings", warnings}};
    fmt::print("{}\n", json_text(doc, 2));
    return 0;
  }

  fmt::print("{}: library of {} clip{}, {} frames at {:g} fps ({:.1f} s)\n", name, db.clips.size(),
             db.clips.size() == 1 ? "" : "s", db.frame_count(), db.fps, seconds);
  // Skeletons: one per ASF or BVH file (an ASF read both y and z up is two), all with the same joints.
  std::vector<std::string> skeleton_files;
  for (const std::string& file : db.skeleton_names) {
    if (std::find(skeleton_files.begin(), skeleton_files.end(), file) == skeleton_files.end()) {
      skeleton_files.push_back(file);
    }
  }
  const size_t skeletons = skeleton_files.size();
  if (skeletons == 1) {
    fmt::print("  skeleton: {}\n", skeleton_files.front());
  } else {
    constexpr size_t kNamed = 3;
    const std::vector<std::string> named(skeleton_files.begin(),
                                         skeleton_files.begin() + static_cast<long>(std::min(skeletons, kNamed)));
    fmt::print("  skeleton: {} with the same joints ({}{})\n", skeletons, fmt::join(named, ", "),
               skeletons > kNamed ? fmt::format(" and {} more", skeletons - kNamed) : "");
  }
  std::vector<std::string> tag_parts;
  for (const auto& [tag, total] : totals) {
    tag_parts.push_back(fmt::format("{} {} clip{} ({:.1f} s)", tag, total.clips, total.clips == 1 ? "" : "s",
                                    total.frames / db.fps));
  }
  if (untagged_clips > 0) {
    tag_parts.push_back(fmt::format("none {} clip{} ({:.1f} s)", untagged_clips, untagged_clips == 1 ? "" : "s",
                                    untagged_frames / db.fps));
  }
  fmt::print("  tags:     {}\n", fmt::join(tag_parts, ", "));
  fmt::print("  feet:     {}\n", have_feet ? feet_description(db.skeletons.front(), *feet, db.frame_contacts, feet_source)
                                           : missing_feet_description(feet_missing));
  size_t width = 4;
  for (const DatabaseClip& clip : db.clips) width = std::max(width, clip.name.size());
  fmt::print("  {:<{}}  {:>7}  {:>7}  {:>8}  {}\n", "clip", width, "frames", "seconds", "travels", "tags");
  for (size_t c = 0; c < db.clips.size(); ++c) {
    const DatabaseClip& clip = db.clips[c];
    fmt::print("  {:<{}}  {:>7}  {:>7.2f}  {:>6.2f} m  {}\n", clip.name, width, clip.frame_count,
               clip.frame_count / db.fps, summaries[c].root_path_m, clip_tags_text(clip_tags[c], clip));
  }
  return 0;
}

}  // namespace mg::cli
