// Foot slide of synthesized motion on the very frames it plays, beside those frames in the
// capture (DESIGN.md section 5b: a result is judged against the clips it was cut from).
//
// The pooled comparison (evaluation/source_foot_slide.h) measures the result with one floor,
// its own 2nd percentile, and its source clips whole, each with its own floor. Which pieces a
// result plays then moves both sides: a path round a tight circle plays the clips' turning
// steps, whose toes pivot on the floor (CMU 135's karate walks: 0.23 m/s on those frames
// against 0.07 m/s over the clips whole), and a result cut from clips captured on floors of
// other heights has the higher ones' steps above its one floor (a copy raised 10 cm: 32 of 72
// steps counted). Height alone still cannot judge a clip walking on uneven ground (CMU 03:
// its toes come within 2 cm of the clip's floor only where the ground is lowest).
//
// Here every played frame f knows its database frames (assembler.h FrameSource: departure,
// arrival, alpha). A step f-1 -> f of a measured foot joint (the toes; a foot without a toe by
// its ankle; the ankles too with include_ankles) counts when the frame that weighs most in f,
// g, and the frame before it in its clip, g-1, are both planted there by the measure's contacts
// (FootSlideSettings::contacts: height alone, within 2 cm of the clip's own floor; a clip is
// judged on its own skeleton's joint of the same side and part, and skipped without one), and
// the result's joint at f is no more than those 2 cm above the capture's height there (the
// joint's heights at the frame's departure and arrival, weighed by alpha, in the result's
// scale): a foot the result lifts, as the foot clean-up's step to a new plant, is off the floor,
// not sliding. Such a step is counted in lifted_steps.
// For a counted step:
//   output speed: the joint's horizontal step in the result times fps;
//   source speed: alpha v(departure) + (1 - alpha) v(arrival), v(x) the same joint's
//     horizontal step into database frame x in its clip (out of it at a clip's first frame)
//     times fps, times the scale the assembler plays that skeleton's translations at.
// A result that plays one clip as captured, placed anywhere, gives the capture's speed step for
// step (1x); the foot clean-up holds planted toes still (below 1x); blends, alignment and the
// path edit's added turning show as more.
#pragma once

#include <span>

#include "motiongraph/evaluation/foot_slide.h"
#include "motiongraph/synthesis/assembler.h"

namespace mg {

struct SameFramesSlide {
  long long steps = 0;           // steps counted (see above), over all measured joints
  long long lifted_steps = 0;    // planted in the capture, lifted in the result: not counted
  double mean_mps = 0.0;         // the result's mean speed over them (0 without any)
  double source_mean_mps = 0.0;  // the capture's over the same steps
};

// `output` on the assembler's skeleton; sources[f] the database frames of its frame f (at least
// output.frame_count of them). Fails when the settings are wrong, a skeleton's feet cannot be
// found, or there are fewer sources than frames.
Result<SameFramesSlide> same_frames_foot_slide(const MotionDatabase& db, const MotionAssembler& assembler,
                                               const Motion& output, std::span<const FrameSource> sources,
                                               const FootSlideSettings& settings = {});

}  // namespace mg
