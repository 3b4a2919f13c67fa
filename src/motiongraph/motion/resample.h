// Resampling a motion to another frame rate (e.g. 120 -> 30 fps): frame i of the result is
// time i / fps_out; rotations are slerped and translations lerped between the two source
// frames around it. The result spans the same duration: floor(duration * fps_out) + 1 frames.
#pragma once

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"

namespace mg {

Result<Motion> resample(const Motion& motion, double fps_out);

// The number of frames resample() gives (fps_out positive).
double resampled_frame_count(const Motion& motion, double fps_out);

}  // namespace mg
