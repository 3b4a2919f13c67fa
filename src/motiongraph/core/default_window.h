// The default blend window: a third of a second at a frame rate, at least one frame. The
// distance stage's window k when none is given (metric/frame_features.h), and what a loop is
// played on for (database/database_loader.h), one rule for both.
#pragma once

#include <algorithm>
#include <cmath>

namespace mg {

inline int default_window_frames(double fps) { return std::max(1, static_cast<int>(std::lround(fps / 3.0))); }

}  // namespace mg
