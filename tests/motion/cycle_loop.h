// One cycle of a captured walk or run made a loop, as a game's cycle is, for the tests of
// motion/loop.h (and make_static_root_bvh --loop).
#pragma once

#include "motiongraph/motion/motion.h"

namespace mg::test {

// One cycle of a periodic clip made a loop, as a game's cycle is: frames first to
// first + period - 1, each joint's rotation (and translation, but the root's over the floor)
// corrected a little more each frame by what frame first + period lacks of frame first, so the
// cycle ends where it starts; with repeat_first, the first pose is repeated as the last frame
// (frame first + period corrected), the root moved on. Its root heading does not turn.
Clip loop_of(const Clip& clip, int first, int period, bool repeat_first);

}  // namespace mg::test
