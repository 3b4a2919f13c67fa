#include "cli/unit_report.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "motiongraph/core/counted.h"
#include "motiongraph/motion/capture_glitches.h"
#include "motiongraph/motion/glitched_ends.h"
#include "motiongraph/motion/length_unit.h"

namespace mg::cli {

namespace {

void warn_implausible(const std::string& file, const LengthUnitChoice& choice) {
  spdlog::warn("{}: no length unit makes the figure human-sized ({:g}-{:g} m): it is {:.4g} units tall; read as "
               "{} (give --scale, metres per unit)",
               file, kPlausibleHeightMinM, kPlausibleHeightMaxM, choice.figure_size_units, choice.unit.name);
}

// "3 frames of 2 files (07_01.bvh and 1 more; --keep-rest-frames keeps them)": the frames the
// reader dropped from files, the first named.
std::string dropped_from_files(int frames, size_t files, const std::string& first) {
  return fmt::format("{} of {} ({}{}; --keep-rest-frames keeps them)", counted(frames, "frame"),
                     counted(static_cast<long long>(files), "file"), std::filesystem::path(first).filename().string(),
                     files > 1 ? fmt::format(" and {} more", files - 1) : "");
}

}  // namespace

std::string unit_description(const LengthUnitChoice& choice) {
  std::string text = fmt::format("{} ({:.6g} m), figure {:.2f} m", choice.unit.name, choice.unit.metres_per_unit,
                                 choice.figure_size_m);
  if (choice.plausible && choice.also) {
    text += fmt::format(" (in {} it is {:.2f} m, a person's size too: --scale {:g} reads it so)", choice.also->name,
                        choice.also_figure_size_m, choice.also->metres_per_unit);
  }
  return text;
}

void report_unit(const std::string& file, const LengthUnitChoice& choice) {
  if (!choice.plausible) {
    warn_implausible(file, choice);
    return;
  }
  spdlog::info("{}: lengths read in {} (--scale overrides)", file, unit_description(choice));
}

std::string up_axis_description(const UpAxisChoice& choice) {
  if (choice.axis == UpAxis::kZ) {
    return fmt::format("z (the figure stands along z: {:.1f} times as tall as along y; turned y up)",
                       choice.animation_ratio);
  }
  return "y";
}

void report_up_axis(const std::string& file, const UpAxisChoice& choice) {
  if (choice.axis != UpAxis::kZ) return;
  spdlog::info("{}: read z up (the figure stands along z: {:.1f} times as tall as along y) and turned y up "
               "(--up-axis overrides)",
               file, choice.animation_ratio);
}

std::string travel_description(const InPlaceChoice& choice) {
  const std::string why = fmt::format("planted feet slide {:.2f} m/s, the root moves {:.2f} m/s",
                                      choice.slide_speed_m_s, choice.root_speed_m_s);
  if (!choice.recovered) return fmt::format("from the root ({})", why);
  return fmt::format("{} ({}); {:.2f} m recovered from the planted feet",
                     choice.in_place ? "in place as read" : "from the feet (--travel feet)", why, choice.recovered_m);
}

void report_travel(const std::string& file, const InPlaceChoice& choice) {
  if (!choice.recovered) return;
  spdlog::info("{}: travel {} (--travel overrides)", file, travel_description(choice));
}

std::string glitch_rule_phrase() {
  return fmt::format("a joint jumping {:g} m or more at {:g} m/s or faster between two calm frames, or out and back "
                     "within a frame", kGlitchJumpM, kGlitchSpeedMps);
}

std::string glitched_ends_description(int leading, int trailing) {
  if (leading <= 0 && trailing <= 0) return "";
  auto frames = [](const char* which, int n) {
    return n == 1 ? fmt::format("the {} frame", which) : fmt::format("the {} {} frames", which, n);
  };
  const std::string ends = leading > 0 && trailing > 0
                               ? fmt::format("{} and {}", frames("first", leading), frames("last", trailing))
                           : leading > 0 ? frames("first", leading)
                                         : frames("last", trailing);
  return fmt::format("{} dropped, cut off by a capture glitch: {}", ends, glitch_rule_phrase());
}

std::string glitches_where(std::span<const FileGlitch> glitches) {
  if (glitches.empty()) return "no glitch";
  const auto largest = std::max_element(glitches.begin(), glitches.end(),
                                        [](const auto& a, const auto& b) { return a.jump_m < b.jump_m; });
  if (glitches.size() == 1) {
    return fmt::format("a glitch at {:.2f} s ({} {:.2f} m)", largest->seconds, largest->joint, largest->jump_m);
  }
  return fmt::format("{} glitches at {:.2f}-{:.2f} s (the largest {} {:.2f} m at {:.2f} s)", glitches.size(),
                     glitches.front().seconds, glitches.back().seconds, largest->joint, largest->jump_m,
                     largest->seconds);
}

std::string glitch_split_description(const DatabaseLoadNotes::GlitchSplit& split) {
  std::vector<std::string> parts;
  for (const auto& part : split.parts) parts.push_back(part.clip);
  return fmt::format("{} ({}): {} {}, {} dropped", split.clip, std::filesystem::path(split.file).filename().string(),
                     glitches_where(split.glitches),
                     parts.size() == 1 ? fmt::format("kept as {}", parts.front())
                                       : fmt::format("cut into {}", fmt::join(parts, ", ")),
                     counted(split.dropped_frames, "frame"));
}

std::string clip_glitches_description(const Clip& clip, const GlitchFreeParts& found) {
  if (found.glitches.empty()) return "";
  const std::string dropped = counted(found.dropped_frames(clip.motion.frame_count), "frame");
  return fmt::format("{} within it ({}): {}", glitches_where(in_file_frames(clip, found.glitches)), glitch_rule_phrase(),
                     found.parts.size() == 1
                         ? fmt::format("a library reads only its one part free of them lasting {:g} s or more, {} "
                                       "dropped", kGlitchFreeSeconds, dropped)
                         : fmt::format("a library cuts it there into {} parts, {} dropped (parts under {:g} s)",
                                       found.parts.size(), dropped, kGlitchFreeSeconds));
}

void report_units(const DatabaseLoadNotes& notes, bool quiet) {
  struct Group {
    int files = 0;
    double lowest_m = 1e300, highest_m = 0.0;
  };
  std::map<std::string_view, Group> groups;
  for (const auto& [file, choice] : notes.detected_units) {
    if (!choice.plausible) {
      warn_implausible(file, choice);
      continue;
    }
    Group& g = groups[choice.unit.name];
    ++g.files;
    g.lowest_m = std::min(g.lowest_m, choice.figure_size_m);
    g.highest_m = std::max(g.highest_m, choice.figure_size_m);
  }
  for (const auto& [name, g] : groups) {
    if (quiet) break;
    spdlog::info("lengths read in {}: {} file{}, figures {:.2f}-{:.2f} m (--scale overrides)", name, g.files,
                 g.files == 1 ? "" : "s", g.lowest_m, g.highest_m);
  }
  const auto z_up = std::count_if(notes.detected_up_axes.begin(), notes.detected_up_axes.end(),
                                  [](const auto& d) { return d.axis_read() == UpAxis::kZ; });
  if (z_up > 0 && !quiet) {
    const auto files = static_cast<long>(notes.detected_up_axes.size());
    spdlog::info("read z up and turned y up: {} of {} file{} (their figures stand along z; --up-axis overrides)",
                 z_up, files, files == 1 ? "" : "s");
  }
  if (!notes.rest_frames.empty() && !quiet) {
    int frames = 0;
    for (const auto& r : notes.rest_frames) frames += r.frames;
    spdlog::info("leading rest/T-pose frames a converter added, dropped: {}",
                 dropped_from_files(frames, notes.rest_frames.size(), notes.rest_frames.front().file));
  }
  if (!notes.glitched_ends.empty() && !quiet) {
    int frames = 0;
    for (const auto& g : notes.glitched_ends) frames += g.leading + g.trailing;
    spdlog::info("first or last frames a capture glitch cut off ({}), dropped: {}", glitch_rule_phrase(),
                 dropped_from_files(frames, notes.glitched_ends.size(), notes.glitched_ends.front().file));
  }
  if (!notes.glitch_splits.empty() && !quiet) {
    int frames = 0;
    for (const auto& g : notes.glitch_splits) frames += g.dropped_frames;
    spdlog::info("clips cut at capture glitches within them ({}; parts under {:g} s dropped): {}{}; {} dropped in all "
                 "(--keep-rest-frames keeps them whole)",
                 glitch_rule_phrase(), kGlitchFreeSeconds,
                 glitch_split_description(notes.glitch_splits.front()),
                 notes.glitch_splits.size() > 1 ? fmt::format(", and {} more clips", notes.glitch_splits.size() - 1)
                                                : "",
                 counted(frames, "frame"));
  }
  if (!notes.loops.empty() && !quiet) {
    int added = 0;
    for (const auto& loop : notes.loops) added += loop.added_frames;
    spdlog::info("{} clip{} loop (their end meets their start: {}{}): played on past their end, {} frames in all, so "
                 "that the graph can play them round (--no-loops turns this off)",
                 notes.loops.size(), notes.loops.size() == 1 ? "" : "s", notes.loops.front().clip,
                 notes.loops.size() > 1 ? fmt::format(" and {} more", notes.loops.size() - 1) : "", added);
  }
  if (!notes.name_tagged.empty() && !quiet) {
    // Per tag, in the order the names first give it: the clips.
    std::vector<std::string> tags;
    std::map<std::string, std::vector<std::string>> of_tag;
    for (const auto& named : notes.name_tagged) {
      for (const std::string& tag : named.tags) {
        if (!of_tag.contains(tag)) tags.push_back(tag);
        of_tag[tag].push_back(named.source == "name"
                                  ? named.clip
                                  : fmt::format("{} by its {} {}", named.clip, named.source, named.words));
      }
    }
    std::vector<std::string> parts;
    for (const std::string& tag : tags) {
      const auto& clips = of_tag.at(tag);
      parts.push_back(fmt::format("{} {} clip{} ({}{})", tag, clips.size(), clips.size() == 1 ? "" : "s",
                                  clips.front(),
                                  clips.size() > 1 ? fmt::format(" and {} more", clips.size() - 1) : ""));
    }
    spdlog::info("tags from clip names (or their folders'): {} (--no-name-tags turns them off; a manifest's tags = "
                 "[...] sets a clip's)",
                 fmt::join(parts, ", "));
  }
  if (notes.too_long_to_mirror && !quiet) {
    spdlog::info("the clips turn {:.0f} degrees left and {:.0f} right as they travel, but the library holds {:.0f} "
                 "minutes or more, so they are not mirrored (--mirror on mirrors them, for four times the distance "
                 "stage's pairs)",
                 notes.turning.left_deg, notes.turning.right_deg, notes.max_lopsided_mirror_s / 60.0);
  }
  if (!notes.mirrored.empty() && !quiet) {
    const TurningBalance& t = notes.turning;
    spdlog::info("{} clip{} mirrored left to right ({}{}), after the clips read, so that their turns go both ways{}",
                 notes.mirrored.size(), notes.mirrored.size() == 1 ? "" : "s", notes.mirrored.front(),
                 notes.mirrored.size() > 1 ? fmt::format(" and {} more", notes.mirrored.size() - 1) : "",
                 notes.mirrored_for_turning
                     ? fmt::format(": travelling {:.0f} s, they turn {:.0f} degrees left and {:.0f} right "
                                   "(--mirror off keeps them as they are)",
                                   t.travel_s, t.left_deg, t.right_deg)
                     : "");
  }
  if (!notes.standing_tags.empty() && !quiet) {
    // Per tag: the frames left off and the clips they are in, in clip order.
    std::vector<std::string> tags;
    std::map<std::string, std::pair<int, std::vector<std::string>>> of_tag;
    for (const auto& t : notes.standing_tags) {
      if (!of_tag.contains(t.tag)) tags.push_back(t.tag);
      auto& [frames, clips] = of_tag[t.tag];
      frames += t.frames - t.tagged_frames;
      clips.push_back(t.clip);
    }
    std::vector<std::string> parts;
    for (const std::string& tag : tags) {
      const auto& [frames, clips] = of_tag.at(tag);
      parts.push_back(fmt::format("{} {} frames of {} clip{} ({}{})", tag, frames, clips.size(),
                                  clips.size() == 1 ? "" : "s", clips.front(),
                                  clips.size() > 1 ? fmt::format(" and {} more", clips.size() - 1) : ""));
    }
    spdlog::info("walk and run from CMU's descriptions and clip names left off where the root stands (under {} m/s "
                 "over a second, "
                 "or travels less than half a second): {}; --whole-clip-tags keeps them",
                 notes.standing_speed_mps, fmt::join(parts, ", "));
  }
  const auto judged = std::count_if(notes.recovered_travels.begin(), notes.recovered_travels.end(),
                                    [](const auto& r) { return r.source == TravelSource::kAuto; });
  if (judged > 0 && !quiet) {
    double metres = 0.0;
    for (const auto& r : notes.recovered_travels) metres += r.choice.recovered_m;
    spdlog::info("travel recovered from the planted feet: {} clip{} animated in place ({:.1f} m in all; --travel "
                 "overrides)",
                 judged, judged == 1 ? "" : "s", metres);
  }
}

}  // namespace mg::cli
