#include "motiongraph/synthesis/facing.h"

namespace mg {

Vec2 travel_direction(const std::vector<Vec2>& roots, int i, int lookahead, double fps, double min_speed_mps) {
  if (i + lookahead >= static_cast<int>(roots.size())) return Vec2::Zero();
  const Vec2 d = roots[i + lookahead] - roots[i];
  const double n = d.norm();
  if (n * fps / lookahead < min_speed_mps || n == 0.0) return Vec2::Zero();
  return d / n;
}

std::vector<Vec3> learn_forward_axes(const MotionDatabase& db) {
  std::vector<Vec3> sums(db.skeletons.size(), Vec3::Zero());
  for (const DatabaseClip& clip : db.clips) {
    std::vector<Vec2> roots(static_cast<size_t>(clip.frame_count));
    for (int f = 0; f < clip.frame_count; ++f) {
      const Vec3& p = clip.motion.translations(f)[0];
      roots[f] = Vec2(p.x(), p.z());
    }
    for (int f = 0; f < clip.frame_count; ++f) {
      const Vec2 d = travel_direction(roots, f, kTravelLookaheadFrames, db.fps, kMovingSpeedMps);
      if (d.isZero()) continue;
      sums[clip.skeleton] += clip.motion.rotations(f)[0].conjugate() * Vec3(d.x(), 0.0, d.y());
    }
  }
  std::vector<Vec3> axes;
  axes.reserve(sums.size());
  for (const Vec3& s : sums) axes.push_back(s.norm() > 0.0 ? Vec3(s.normalized()) : Vec3(Vec3::UnitZ()));
  return axes;
}

Vec2 facing_on_floor(const Quat& root_world_rotation, const Vec3& forward_axis) {
  const Vec3 f = root_world_rotation * forward_axis;
  const Vec2 d(f.x(), f.z());
  const double n = d.norm();
  return n > 1e-9 ? Vec2(d / n) : Vec2(Vec2::Zero());
}

}  // namespace mg
