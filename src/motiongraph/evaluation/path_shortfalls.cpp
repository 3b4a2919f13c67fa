#include "motiongraph/evaluation/path_shortfalls.h"

#include <algorithm>

#include <fmt/format.h>

#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/synthesis/facing.h"
#include "motiongraph/synthesis/path_check.h"

namespace mg {

namespace {

std::string searches_made(int attempts) {
  return fmt::format("{} search{} of the whole path", attempts, attempts == 1 ? "" : "es");
}

std::string segment_name(const PathSegment& segment) {
  return fmt::format("the segment {} {:g}-{:g} m", segment.tag, segment.from_m, segment.to_m);
}

}  // namespace

std::vector<std::string> path_shortfalls(const SynthesisContext& context, const FloorPath& path,
                                         const PathSynthesisSettings& settings, const PathSynthesisResult& result) {
  std::vector<std::string> said;
  const auto& segments = path.segments();
  // Asked of the path, not of the motion: a segment no way along it reaches.
  for (const PathSegment& segment : segments) {
    if (segment.from_m >= path.length_m()) {
      said.push_back(fmt::format("{} lies past the path's end ({:.1f} m): no frame can carry its motion type",
                                 segment_name(segment), path.length_m()));
    }
  }
  // Asked to end at rest: where it stands.
  if (result.rest != nullptr && result.end_distance_m > kEndReachedM && !result.roots.empty()) {
    const double ahead = (result.roots.back() - path.points().back()).dot(path.direction_at(path.length_m()));
    said.push_back(fmt::format("the character comes to rest {:.2f} m {} the path's end: no way to rest the search "
                               "tried stands nearer (its clips that stop take a metre or two to slow down; a longer "
                               "path, or walking rather than running into the end, leaves room)",
                               result.end_distance_m, ahead > 0.0 ? "past" : "short of"));
  }
  // Asked to end at rest: which way it stands. The way to rest is chosen by where it stands; the
  // clip it stops in may turn on the spot as it stops (CMU 29's and 135's by 90 degrees and more).
  if (result.rest != nullptr && result.motion.frame_count > 0) {
    const double off_deg = facing_off_deg(result.motion.rotations(result.motion.frame_count - 1)[0],
                                          context.tracks.forward_axis, path.direction_at(path.length_m()));
    if (off_deg > kRestFacingWarnDeg) {
      const DatabaseClip& clip = context.db->clips[static_cast<size_t>(context.db->clip_of(result.rest->last_frame))];
      said.push_back(fmt::format("the character stands facing {:.0f} degrees off the path's last direction: {}, the "
                                 "clip it stops in, turns as it stops (the way to rest is chosen by where it stands, "
                                 "not by which way it faces)",
                                 off_deg, clip.name));
    }
  }
  if (!result.reached_end) {
    const PathCheckSettings check;
    const double share = travelling_share(context, check.travel_speed_mps);
    std::string why;
    if (result.arc_covered_m >= path.length_m() - kEndReachedM) {
      why = "its way along the path reaches the end, but not where the end is: the path turns back on itself more "
            "tightly than the motion can follow";
    } else if (share < check.min_travel_share) {
      why = fmt::format("the graph's clips hardly travel ({:.0f} % of its clip frames move {:g} m/s or faster): a "
                        "path wants clips that walk or run",
                        100.0 * share, check.travel_speed_mps);
    } else {
      why = fmt::format("the search gave up after {} (a larger search budget, a longer horizon or more retries "
                        "search further)",
                        searches_made(result.attempts));
    }
    said.push_back(fmt::format("the motion did not reach the path's end: it went {:.1f} m of {:.1f} m and stops "
                               "{:.2f} m from the end; {}",
                               result.arc_covered_m, path.length_m(), result.end_distance_m, why));
    return said;  // what it did on the way is all of it: the rest says little more
  }
  if (result.dawdled_in >= 0) {
    const size_t in = static_cast<size_t>(result.dawdled_in);
    const std::string where = in < segments.size() ? segment_name(segments[in])
                              : segments.empty()   ? fmt::format("the path's {:.1f} m", path.length_m())
                                                   : std::string("the stretches no segment holds");
    said.push_back(fmt::format("the motion dawdles: it takes {:.1f} s over {}, where {:.1f} s would do at the slowest "
                               "speed asked ({:g} m/s, or the motion type's own where slower); {} found none "
                               "quicker",
                               result.dawdled_s, where, result.dawdle_limit_s, settings.min_speed_mps,
                               searches_made(result.attempts)));
  }
  if (settings.retry_deviation_m > 0.0 && result.mean_deviation_m > settings.retry_deviation_m) {
    said.push_back(fmt::format("the motion follows the path {:.2f} m off on average (at most {:.2f} m), more than "
                               "the {:g} m the retries look for: the path may turn more tightly, or lead where, the "
                               "graph's motion does not go; {} found none closer",
                               result.mean_deviation_m, result.max_deviation_m, settings.retry_deviation_m,
                               searches_made(result.attempts)));
  }
  for (int i : result.missed_segments) {
    const size_t at = static_cast<size_t>(i);
    if (at >= segments.size() || at >= result.segment_tag_matches.size()) continue;
    const auto& m = result.segment_tag_matches[at];
    said.push_back(fmt::format("{} misses its motion type: {:.0f} % of its {} frames carry {} (the retries look for "
                               "{:.0f} %)",
                               segment_name(segments[at]), m.frames > 0 ? 100.0 * m.matched / m.frames : 0.0,
                               m.frames, segments[at].tag, 100.0 * settings.retry_tag_match));
  }
  // A segment too short for the retries to judge (under kTagMissMinSeconds of motion) that got
  // none of the motion type it asks for, which the graph plays: said too (a jump asked for over
  // the last metres of a run, none played, went unsaid while a miss of 48 % was warned of).
  for (size_t at = 0; at < segments.size() && at < result.segment_tag_matches.size(); ++at) {
    const auto& m = result.segment_tag_matches[at];
    if (m.frames <= 0 || m.matched > 0 || is_modifier_tag(segments[at].tag)) continue;
    // (2 s or more: the retries' to judge, or not when told not to.)
    if (m.frames >= kTagMissMinSeconds * context.db->fps) continue;
    if (segments[at].from_m >= path.length_m()) continue;  // past the end: said above
    if (std::find(result.missed_segments.begin(), result.missed_segments.end(), static_cast<int>(at)) !=
        result.missed_segments.end()) {
      continue;
    }
    const auto mask = context.tag_mask(segments[at].tag);
    if (!mask || graph_frames_with(context, *mask) == 0) continue;  // not in the graph: said where the path is read
    said.push_back(fmt::format("{} gets none of its motion type: none of its {} frames ({:.1f} s) carry {} (shorter "
                               "than the {:g} s the retries judge a segment by, it may be too short to change into "
                               "it)",
                               segment_name(segments[at]), m.frames, m.frames / context.db->fps, segments[at].tag,
                               kTagMissMinSeconds));
  }
  return said;
}

}  // namespace mg
