// The "foot_slide" entry of every synthesis report (the CLI's --report of walk, path and
// steer, and the studio's results): a result measured against the clips it was cut from
// (evaluation/source_foot_slide.h), as JSON.
//
//   {"mean_mps", "p95_mps", "max_joint_step_m", "p999_joint_step_m", "contact_steps",
//    "source": {the same, "clips": [names]},
//    "ratio": {"mean_mps", "p95_mps", "max_joint_step_m", "max_joint_step_over_source_p999"},
//    "same_frames": {"steps", "lifted_steps", "mean_mps", "source_mean_mps", "ratio"}}
// A ratio is output / source (null where the source's is 0); max_joint_step_over_source_p999
// is the output's largest step over the source's 99.9th percentile (the clean-up's bound is
// 1.5). "same_frames" is the result's foot slide on the steps its frames' own source frames
// are planted, beside theirs (evaluation/same_frames_slide.h): what synthesis added to the
// capture it played. {"error": "..."} when a skeleton's feet cannot be found by name.
#pragma once

#include <span>

#include <nlohmann/json.hpp>

#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

nlohmann::json foot_slide_report(const SynthesisContext& context, const Walk& walk, const Motion& motion);
// The same for motion whose frames' sources are `sources`, in order (a steering session's: its
// decisions', decision_sources), not the walk's; the walk says the clips it was cut from.
nlohmann::json foot_slide_report(const SynthesisContext& context, const Walk& walk, const Motion& motion,
                                 std::span<const FrameSource> sources);

}  // namespace mg
