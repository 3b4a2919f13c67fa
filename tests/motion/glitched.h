// Capture glitches made by hand, for the tests of motion/glitched_ends.h and
// motion/capture_glitches.h (and the loader's parts).
#pragma once

#include <string>

#include "motiongraph/motion/motion.h"

namespace mg::test {

// The largest step of any joint between frames f and f + 1, by brute force (world positions of
// the two frames).
double largest_step(const Skeleton& skeleton, const Motion& motion, int f);

// Every n-th frame of the clip's motion, played at `fps`.
Motion every_nth_frame(const Clip& clip, int n, double fps);

// The clip's first `frames` frames.
Clip first_frames(Clip clip, int frames);

// The clip with joint `name` turned by `radians` about x from frame `first` to `last`: a limb
// the capture put elsewhere for those frames.
Clip with_turn(Clip clip, const std::string& name, int first, int last, double radians);

}  // namespace mg::test
