#include "motiongraph/database/turning_balance.h"

#include <cmath>
#include <numbers>

namespace mg {

TurningBalance turning_balance(const MotionDatabase& db) {
  TurningBalance out;
  const double fps = db.fps > 0.0 ? db.fps : 30.0;
  const int half = std::max(1, static_cast<int>(std::lround(0.5 * fps)));
  const double half_s = half / fps, frame_s = 1.0 / fps;
  for (const DatabaseClip& clip : db.clips) {
    const Skeleton& skeleton = db.skeletons[static_cast<size_t>(clip.skeleton)];
    const int slot = skeleton.translation_slot(0);
    if (slot < 0) continue;
    auto at = [&](int f) {
      const Vec3& p = clip.motion.translations(f)[static_cast<size_t>(slot)];
      return std::pair{p.x(), p.z()};
    };
    for (int f = half; f + half < clip.motion.frame_count; ++f) {
      const auto [x0, z0] = at(f - half);
      const auto [x1, z1] = at(f);
      const auto [x2, z2] = at(f + half);
      const double ax = x1 - x0, az = z1 - z0, bx = x2 - x1, bz = z2 - z1;
      const double travel = TurningBalance::kTravelMps * half_s;
      if (std::hypot(ax, az) < travel || std::hypot(bx, bz) < travel) continue;
      out.travel_s += frame_s;
      // Anticlockwise seen from above (y up, x east, z south): heading north (-z), west (-x) is left.
      const double turn = std::atan2(az * bx - ax * bz, ax * bx + az * bz) * 180.0 / std::numbers::pi;
      const double rate = turn / half_s;
      if (rate >= TurningBalance::kTurnDegPerS) out.left_deg += rate * frame_s;
      if (rate <= -TurningBalance::kTurnDegPerS) out.right_deg -= rate * frame_s;
    }
  }
  return out;
}

}  // namespace mg
