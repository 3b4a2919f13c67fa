// Which way a library's clips turn as they travel: the degrees they turn left and right.
// A studio's small library often turns one way only (a walk_turn_left and no right turn), and a
// path or steering asking to turn the other way then has nothing to play; mirrored clips
// (motion/mirror.h) turn both ways.
//
// A frame travels when its root goes kTravelMps or faster over the half second before it and the
// half second after; it turns when the direction of travel over the second changes by
// kTurnDegPerS or more a second, left (anticlockwise seen from above) or right, and adds its
// frame's share of the turn to that side.
#pragma once

#include <algorithm>

#include "motiongraph/database/motion_database.h"

namespace mg {

struct TurningBalance {
  static constexpr double kTravelMps = 0.5;
  static constexpr double kTurnDegPerS = 20.0;
  // A library turns one way when it turns kMinTurnDeg or more that way, the other way less than
  // kLopsidedShare of that.
  static constexpr double kMinTurnDeg = 60.0;
  static constexpr double kLopsidedShare = 1.0 / 3.0;

  double travel_s = 0.0;   // of the frames that travel
  double left_deg = 0.0;   // turned left by those that turn
  double right_deg = 0.0;  // ... and right

  bool lopsided() const {
    const double most = std::max(left_deg, right_deg), least = std::min(left_deg, right_deg);
    return most >= kMinTurnDeg && least < kLopsidedShare * most;
  }
};

// Over the clips' root joints (joint 0's translation; a clip whose root has none does not travel).
TurningBalance turning_balance(const MotionDatabase& db);

}  // namespace mg
