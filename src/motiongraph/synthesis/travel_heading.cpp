#include "motiongraph/synthesis/travel_heading.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "motiongraph/core/parallel_for.h"

namespace mg {

double travel_share(const HeadingEditSettings& settings, const Vec2& facing, const Vec2& travel, double seconds,
                    double spanned) {
  if (!settings.hold_travel || seconds <= 0.0 || facing.norm() <= 1e-6 || travel.norm() <= 1e-9) return 0.0;
  const double whole = std::clamp((spanned - 0.75) / 0.25, 0.0, 1.0);
  const double speed = travel.norm() / seconds;
  const double by_speed =
      std::clamp((speed - settings.travel_from_mps) / (settings.travel_full_mps - settings.travel_from_mps), 0.0, 1.0);
  const double cosine = facing.normalized().dot(travel.normalized());
  const double lo = std::cos(45.0 * std::numbers::pi / 180.0), hi = std::cos(20.0 * std::numbers::pi / 180.0);
  return whole * by_speed * std::clamp((cosine - lo) / (hi - lo), 0.0, 1.0);
}

std::vector<float> travel_turns(const MotionDatabase& db, const MotionAssembler& assembler, const Vec3& forward_axis,
                                const HeadingEditSettings& settings) {
  std::vector<float> turns(static_cast<size_t>(db.frame_count()), 0.0f);
  if (!settings.hold_travel) return turns;
  const int half = std::max(0, static_cast<int>(std::lround(0.5 * settings.window_s * db.fps)));
  parallel_for(static_cast<long long>(db.clips.size()), worker_threads(0), 1, [&](int, long long c) {
    const DatabaseClip& clip = db.clips[static_cast<size_t>(c)];
    const int n = clip.frame_count;
    std::vector<Vec2> roots(static_cast<size_t>(n));
    std::vector<Vec2> facing_sums(static_cast<size_t>(n) + 1, Vec2::Zero());
    for (int i = 0; i < n; ++i) {
      const RootPose root = assembler.root_pose(clip.first_frame + i, FloorTransform{});
      roots[static_cast<size_t>(i)] = Vec2(root.position.x(), root.position.z());
      facing_sums[static_cast<size_t>(i) + 1] =
          facing_sums[static_cast<size_t>(i)] + facing_on_floor(root.rotation, forward_axis);
    }
    for (int i = 0; i < n; ++i) {
      const int lo = std::max(0, i - half), hi = std::min(n, i + half + 1);
      const Vec2 mean = facing_sums[static_cast<size_t>(hi)] - facing_sums[static_cast<size_t>(lo)];
      const Vec2 travel = roots[static_cast<size_t>(hi - 1)] - roots[static_cast<size_t>(lo)];
      const int spanned = hi - 1 - lo;
      const double share = travel_share(settings, mean, travel, spanned / db.fps,
                                        half > 0 ? spanned / (2.0 * half) : 1.0);
      if (share <= 0.0) continue;
      const Vec2 judged = (1.0 - share) * mean.normalized() + share * travel.normalized();
      if (judged.norm() <= 1e-9) continue;
      turns[static_cast<size_t>(clip.first_frame + i)] = static_cast<float>(yaw_between(mean.normalized(), judged));
    }
  });
  return turns;
}

}  // namespace mg
