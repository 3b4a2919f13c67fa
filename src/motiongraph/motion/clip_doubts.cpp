// What looks wrong with a clip as read (clip_doubts.h).
#include "motiongraph/motion/clip_doubts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "motiongraph/core/quantile.h"
#include "motiongraph/motion/flight_fall.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/length_unit.h"
#include "motiongraph/motion/walk_pace.h"

namespace mg {

Status ClipDoubtSettings::validate() const {
  if (!(off_floor_m > 0.0)) return Error{"", 0, "the distance off the floor must be positive"};
  if (!(min_contactless_s >= 0.0)) return Error{"", 0, "the shortest clip without contact must be >= 0 s"};
  if (!(min_figure_m > 0.0) || !(max_figure_m > min_figure_m) || !std::isfinite(max_figure_m)) {
    return Error{"", 0, "a person's size must be a range of positive lengths"};
  }
  if (!(max_slowdown > 1.0) || !std::isfinite(max_slowdown)) return Error{"", 0, "the largest slowdown must be > 1"};
  return Ok{};
}

std::vector<std::string> ClipDoubts::phrases() const {
  if (!size.empty()) return {size};
  std::vector<std::string> out = floor;
  if (!clock.empty()) out.push_back(clock);
  return out;
}

namespace {

// How the clock is off, "it plays about 4.0x slower than it was captured", and what to change,
// "its frame rate as read, 30 fps, is likely about 4.0 times that (...)"; or of several clips
// read at one rate ("they play ...", "their frame rate as read ..."). Captures' flights fall at
// 0.7-1.55 g (the mean of the joints is not the centre of mass), walks' ratios lie within 1.25x
// of kWalkRatio, so the factor is known to a fifth or so: the phrase gives it, "about", and no
// rate of its own.
std::string pace_phrase(double k, bool several) {
  const char* it = several ? "they play" : "it plays";
  const char* was = several ? "they were" : "it was";
  return k > 1.0 ? fmt::format("{} about {:.1f}x slower than {} captured", it, k, was)
                 : fmt::format("{} about {:.1f}x faster than {} captured", it, 1.0 / k, was);
}

std::string fix_phrase(double k, const ClipClock& clock, bool several) {
  const char* its = several ? "their" : "its";
  const std::string times = k > 1.0 ? fmt::format("about {:.1f} times", k) : fmt::format("about 1/{:.1f} of", 1.0 / k);
  if (clock.keys_in_seconds) {
    return fmt::format("{} keys' times look {} what they should (export {} again at the capture's rate)", its, times,
                       several ? "them" : "it");
  }
  const std::string rate = clock.read_fps > 0.0 ? fmt::format("{} frame rate as read, {:g} fps, is likely {} that", its,
                                                              clock.read_fps, times)
                                                : fmt::format("{} frame rate is likely {} the one read", its, times);
  return rate + " (--input-fps; a manifest's input_fps for one clip)";
}

}  // namespace

ClipDoubts clip_doubts(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                       std::span<const ContactMask> contacts, const ClipDoubtSettings& settings,
                       const ClipClock& clock, const FootJoints& feet) {
  ClipDoubts out;
  if (joint_count <= 0 || world_positions_m.empty()) return out;
  const size_t frames = world_positions_m.size() / static_cast<size_t>(joint_count);
  std::vector<double> lowest(frames, std::numeric_limits<double>::infinity());
  for (size_t f = 0; f < frames; ++f) {
    for (int j = 0; j < joint_count; ++j) {
      lowest[f] = std::min(lowest[f], static_cast<double>(world_positions_m[f * joint_count + j].y()));
    }
  }
  const double size = figure_size(world_positions_m, joint_count);  // the size units are chosen by
  if (size == 0.0) {
    out.size = "its joints all lie at one point (its bones have no length)";
    return out;
  }
  if (!(size >= settings.min_figure_m && size <= settings.max_figure_m)) {
    out.size = fmt::format("its figure is {:.3g} m tall, no person's size ({:g}-{:g} m): its length unit is wrong "
                           "(--scale gives metres per unit of the file)",
                           size, settings.min_figure_m, settings.max_figure_m);
    return out;
  }
  const double low = quantile(lowest, 0.02), median = quantile(lowest, 0.5), high = quantile(lowest, 0.98);
  if (median < -settings.off_floor_m) {
    out.floor.push_back(fmt::format("its lowest joint is {:.2f}-{:.2f} m below the floor (y = 0)", -high, -low));
  } else if (low > settings.off_floor_m) {
    out.floor.push_back(fmt::format("its lowest joint stays {:.2f}-{:.2f} m above the floor (y = 0)", low, high));
  }
  if (contacts.size() == frames && fps > 0.0 && static_cast<double>(frames) / fps >= settings.min_contactless_s &&
      std::all_of(contacts.begin(), contacts.end(), [](ContactMask m) { return m == 0; })) {
    out.floor.push_back("no foot rests on the floor in any frame");
  }
  if (out.floor.empty()) {
    const FlightFall& fall = out.flight_fall = measure_flight_fall(world_positions_m, joint_count, fps, contacts);
    const WalkPace& walk = out.walk_pace = measure_walk_pace(world_positions_m, joint_count, fps, contacts, feet);
    const double k = out.slowdown = fall.measured() ? fall.slowdown() : walk.slowdown();
    if (k > 0.0 && (k > settings.max_slowdown || k < 1.0 / settings.max_slowdown)) {
      const std::string evidence =
          fall.measured() ? fmt::format("its flights fall at {:.2f} m/s^2, not {:.2f}", fall.fall_mps2, kGravityMps2)
                          : fmt::format("its walking strides of {:.2f} m take {:.2f} s, where people's of that length "
                                        "take about {:.2f} s",
                                        walk.stride_m, walk.stride_s, walk.usual_stride_s());
      out.clock = evidence + ": " + pace_phrase(k, false) + "; " + fix_phrase(k, clock, false);
    }
  }
  return out;
}

ClipDoubts clip_doubts(const Skeleton& skeleton, const Motion& motion, const ClipDoubtSettings& settings) {
  const std::vector<Vec3> positions = world_positions(skeleton, motion);
  std::vector<ContactMask> masks;
  FootJoints found;
  if (auto feet = find_foot_joints(skeleton, {})) {
    if (auto contacts = detect_foot_contacts(positions, skeleton.joint_count(), motion.fps, *feet, {})) {
      for (int f = 0; f < motion.frame_count; ++f) masks.push_back(contact_mask(*contacts, f));
      found = *feet;
    }
  }
  return clip_doubts(positions, skeleton.joint_count(), motion.fps, masks, settings, ClipClock{motion.fps, false},
                     found);
}

std::string clip_doubts_text(const ClipDoubts& doubts) {
  if (!doubts.size.empty()) return doubts.size;
  std::string joined;
  for (size_t i = 0; i < doubts.floor.size(); ++i) joined += (i == 0 ? "" : ", and ") + doubts.floor[i];
  if (!joined.empty()) return joined + "; its root translation may be wrong";
  return doubts.clock;  // judged only where the floor is right
}

std::string clip_doubt_line(const std::string& name, const ClipDoubts& doubts) {
  const bool placed = !doubts.size.empty() || !doubts.floor.empty();
  return fmt::format("{}: {}{}", name, clip_doubts_text(doubts),
                     placed ? " (the distances compare clips as read, so the graph may join it to nothing)" : "");
}

std::vector<std::string> clip_doubt_lines(std::span<const DoubtedClip> clips) {
  // Clips whose only doubt is their clock, by the rate read and whether they play slow or fast.
  const auto clock_only = [](const ClipDoubts& d) { return d.size.empty() && d.floor.empty() && !d.clock.empty(); };
  const auto same_group = [](const DoubtedClip& a, const DoubtedClip& b) {
    return a.clock.read_fps == b.clock.read_fps && a.clock.keys_in_seconds == b.clock.keys_in_seconds &&
           (a.doubts.slowdown > 1.0) == (b.doubts.slowdown > 1.0);
  };
  std::vector<std::string> lines;
  std::vector<char> said(clips.size(), 0);
  for (size_t i = 0; i < clips.size(); ++i) {
    if (said[i] || clips[i].doubts.empty()) continue;
    std::vector<size_t> group = {i};
    if (clock_only(clips[i].doubts)) {
      for (size_t j = i + 1; j < clips.size(); ++j) {
        if (!said[j] && clock_only(clips[j].doubts) && same_group(clips[i], clips[j])) group.push_back(j);
      }
    }
    if (group.size() < kGroupedClockDoubts) {
      lines.push_back(clip_doubt_line(clips[i].name, clips[i].doubts));
      said[i] = 1;
      continue;
    }
    // Up to 4 named all; more, the first 3 "and N more".
    const int count = static_cast<int>(group.size());
    const int named = count <= 4 ? count : 3;
    std::vector<std::string> names;
    std::vector<double> factors;  // how many times slower, or faster: each at least 1
    int by_flights = 0;
    for (const size_t j : group) {
      said[j] = 1;
      if (static_cast<int>(names.size()) < named) names.push_back(clips[j].name);
      const double k = clips[j].doubts.slowdown;
      factors.push_back(k > 1.0 ? k : 1.0 / k);
      by_flights += clips[j].doubts.flight_fall.measured();
    }
    const bool slower = clips[i].doubts.slowdown > 1.0;
    const auto [low, high] = std::minmax_element(factors.begin(), factors.end());
    const double factor = quantile(factors, 0.5);
    const std::string range = fmt::format("{:.1f}", *low) == fmt::format("{:.1f}", *high)
                                  ? ""
                                  : fmt::format(" ({:.1f}-{:.1f}x)", *low, *high);
    const std::string evidence = by_flights == count ? "flights"
                                 : by_flights == 0   ? "walking strides"
                                                     : "flights or walking strides";
    const double k = slower ? factor : 1.0 / factor;
    lines.push_back(fmt::format("{}{}: their {} say {}{}; {}", fmt::join(names, ", "),
                                count > named ? fmt::format(" and {} more", count - named) : "", evidence,
                                pace_phrase(k, true), range, fix_phrase(k, clips[i].clock, true)));
  }
  return lines;
}

}  // namespace mg
