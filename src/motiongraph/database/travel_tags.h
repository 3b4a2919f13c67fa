// Walk and run where the figure goes somewhere. CMU's descriptions tag whole clips
// (cmu_tags.h), but a clip described "jump up to grab, reach for, tiptoe" walks for a few of its
// frames, one described "walk, stop" stands at its end, and "jumping jacks, jog, squats" jogs on
// the spot. Asked to walk, a search that judges the facing (controller.h) finds a standing frame
// that faces the right way as good as any walk, and the character asked to walk stands (CMU
// 14's walk went 0.05 m/s). So the locomotion tags a description gives (walk, run:
// is_locomotion_tag) stay only where the root travels at least min_speed_mps: the root's floor
// displacement over window_s centred on the frame (cut at the clip's ends) by the time it spans.
// Pauses shorter than min_gap_s keep the tag, and what travels for less than min_run_s loses it
// (unless it is the whole clip). Likewise stop: "slow walk, stop" walks for most of its frames,
// and the steering controller asked to stop played them (10 m in 10 s, "stop after 0.00 s"); it
// stays on the frames where the root does not travel and on the stop_lead_s of travel that
// slows into each halt (the whole clip when the root never halts: the description is trusted).
// A manifest's tags are the user's word and stay as given (database_loader.h).
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/skeleton/rotation.h"

namespace mg {

struct TravelTagSettings {
  double min_speed_mps = 0.25;  // 0: descriptions tag whole clips, as they say
  double window_s = 1.0;
  double min_gap_s = 0.5;
  double min_run_s = 0.5;
  double stop_lead_s = 1.0;  // of a clip tagged stop, the travel before a halt that keeps the tag

  Status validate() const;
};

// walk and run: the tags that ask the character to go somewhere (cmu_tags.h's families).
bool is_locomotion_tag(std::string_view tag);
// stop (in any case, as asked: "Stop"): the tag that asks it to come to a halt.
bool is_stop_tag(std::string_view tag);

// Frames [first, first + count) of a clip.
struct FrameSpan {
  int first = 0;
  int count = 0;

  bool operator==(const FrameSpan&) const = default;
};

// The spans of a clip (its root's positions, y up, one per frame at `fps`) over which the root
// travels on the floor as above, in order; all its frames when settings.min_speed_mps is 0.
std::vector<FrameSpan> travelling_spans(std::span<const Vec3> roots, double fps,
                                        const TravelTagSettings& settings);

// The spans of a clip that keep a stop tag: its frames outside travelling_spans(), each halt
// after travel with the stop_lead_s before it, in order; all its frames when the root never
// halts or settings.min_speed_mps is 0.
std::vector<FrameSpan> stopping_spans(std::span<const Vec3> roots, double fps, const TravelTagSettings& settings);

// A clip that its description or name calls both walk and run ("Walk to Run", "walk, run/jog"):
// its travelling spans split where the root's pace (over settings.window_s, as above) crosses
// `run_mps`, walking below it and running at or above; a stretch shorter than
// settings.min_run_s goes with the stretch before it (the one after, at a span's start). One of
// the two is empty when the clip keeps one pace (the walking part of a "walk to run" cut at a
// capture glitch walks only).
struct PaceSpans {
  std::vector<FrameSpan> walking;
  std::vector<FrameSpan> running;
};
PaceSpans pace_spans(std::span<const Vec3> roots, double fps, const TravelTagSettings& settings, double run_mps);

// The pace from which a figure whose legs are `leg_m` long runs rather than walks: Froude number
// v^2 / (g leg) 0.3, 1.7 m/s for a metre of leg (subject 16 walks 1.2 m/s and runs 2.2).
double run_pace_mps(double leg_m);

}  // namespace mg
