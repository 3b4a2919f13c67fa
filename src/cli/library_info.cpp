#include "cli/library_info.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/unit_report.h"
#include "motiongraph/core/file_extension.h"
#include "motiongraph/core/json_text.h"
#include "motiongraph/pipeline/feet_report.h"
#include "motiongraph/pipeline/library_summary.h"

namespace mg::cli {

bool is_library(const std::vector<std::string>& inputs) {
  return std::any_of(inputs.begin(), inputs.end(), [](const std::string& input) {
    std::error_code ec;
    return std::filesystem::is_directory(input, ec) || lower_extension(input) == ".toml";
  });
}

int run_library_info(const std::vector<std::string>& inputs, const LibraryInfoOptions& options) {
  DatabaseLoadNotes notes;
  DatabaseSettings database = options.database;
  database.progress_bar = true;  // a terminal's stderr only
  auto loaded = load_database(inputs, database, &notes);
  if (!loaded) return fail(loaded.error());
  const MotionDatabase& db = *loaded;
  report_units(notes, false);
  const LibrarySummary summary = summarize_library(db, notes, !options.database.foot_names.empty());
  if (options.json) {
    fmt::print("{}\n", json_text(library_summary_json(inputs, db, summary), 2));
    return 0;
  }
  for (const std::string& line : summary.warnings) spdlog::warn("{}", line);

  const std::string name =
      inputs.size() <= 2 ? fmt::format("{}", fmt::join(inputs, ", "))
                         : fmt::format("{} and {} more", inputs.front(), inputs.size() - 1);
  fmt::print("{}: library of {} clip{}, {} frames at {:g} fps ({:.1f} s)\n", name, db.clips.size(),
             db.clips.size() == 1 ? "" : "s", db.frame_count(), db.fps, db.frame_count() / db.fps);
  const std::vector<std::string>& files = summary.skeleton_files;
  if (files.size() == 1) {
    fmt::print("  skeleton: {}\n", files.front());
  } else {
    constexpr size_t kNamed = 3;
    const auto shown = static_cast<long>(std::min(files.size(), kNamed));
    const std::vector<std::string> named(files.begin(), files.begin() + shown);
    // How the clips came to one skeleton (the warnings above say what was matched or dropped).
    std::vector<std::string> how;
    if (!notes.rerooted.empty()) how.push_back(fmt::format("from '{}' down", notes.rerooted.front().root));
    if (!notes.dropped_joints.empty()) {
      how.push_back(fmt::format("on the {} joints they share", notes.common_joints.size()));
    }
    if (!notes.matched_rigs.empty()) how.push_back("on the first's joint names and rest pose");
    const std::string read = how.empty() ? "with the same joints" : fmt::format("read {}", fmt::join(how, ", "));
    fmt::print("  skeleton: {} {} ({}{})\n", files.size(), read, fmt::join(named, ", "),
               files.size() > kNamed ? fmt::format(" and {} more", files.size() - kNamed) : "");
  }
  std::vector<std::string> tag_parts;
  const auto tag_text = [&db](const std::string& tag, const TagTotal& total) {
    return fmt::format("{} {} clip{} ({:.1f} s)", tag, total.clips, total.clips == 1 ? "" : "s", total.frames / db.fps);
  };
  for (const auto& [tag, total] : summary.tags) tag_parts.push_back(tag_text(tag, total));
  if (summary.untagged.clips > 0) tag_parts.push_back(tag_text("none", summary.untagged));
  fmt::print("  tags:     {}\n", fmt::join(tag_parts, ", "));
  fmt::print("  feet:     {}\n", summary.feet ? feet_description(db.skeletons.front(), *summary.feet,
                                                                  db.frame_contacts, summary.feet_source)
                                              : missing_feet_description(summary.feet_missing));
  // Which way the clips as read turn as they travel, and so whether they were mirrored.
  const TurningBalance& turning = notes.turning;
  std::string mirrored;
  if (!notes.mirrored.empty()) {
    mirrored = notes.mirrored_for_turning ? "one way, so each is mirrored too (--mirror off reads them as they are)"
                                          : "each mirrored too (--mirror on)";
  } else if (notes.too_long_to_mirror) {
    mirrored = "one way, but a library this long is not mirrored (--mirror on mirrors it)";
  } else if (turning.lopsided() && notes.mirroring == DatabaseSettings::Mirroring::kOff) {
    mirrored = "one way, not mirrored (--mirror off)";
  } else {
    const char* ways = turning.lopsided() ? "one way"
                       : turning.left_deg + turning.right_deg > 0.0 ? "both ways"
                                                                    : "not at all";
    mirrored = notes.unmirrored.empty()
                   ? std::string(ways)
                   : fmt::format("{}, and its rig cannot be mirrored (the warning says why)", ways);
  }
  fmt::print("  turning:  the clips as read turn {:.0f} degrees left and {:.0f} right over the {:.1f} s they travel "
             "({:g} m/s or more; turning {:g} degrees a second or more): {}\n",
             turning.left_deg, turning.right_deg, turning.travel_s, TurningBalance::kTravelMps,
             TurningBalance::kTurnDegPerS, mirrored);
  size_t width = 4;
  for (const DatabaseClip& clip : db.clips) width = std::max(width, clip.name.size());
  fmt::print("  {:<{}}  {:>7}  {:>7}  {:>8}  {}\n", "clip", width, "frames", "seconds", "travels", "tags");
  for (size_t c = 0; c < db.clips.size(); ++c) {
    const DatabaseClip& clip = db.clips[c];
    fmt::print("  {:<{}}  {:>7}  {:>7.2f}  {:>6.2f} m  {}\n", clip.name, width, clip.frame_count,
               std::max(0, clip.frame_count - 1) / db.fps, summary.clip_travel_m[c],
               clip_tags_text(summary.clip_tags[c], clip.frame_count));
  }
  return 0;
}

}  // namespace mg::cli
