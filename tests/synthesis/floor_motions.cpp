#include "synthesis/floor_motions.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mg::test {

Motion motion_along(const std::vector<Vec2>& roots) {
  Motion m;
  m.fps = kFloorMotionFps;
  m.frame_count = static_cast<int>(roots.size());
  m.joint_count = 2;
  m.translated_count = 1;
  m.local_rotations.resize(roots.size() * 2);
  m.local_translations_m.resize(roots.size());
  for (int f = 0; f < m.frame_count; ++f) {
    const Vec2 ahead = roots[std::min<size_t>(roots.size() - 1, f + 15)] - roots[std::max(0, f - 15)];
    // Yaw turning north (0, -1) onto `ahead` (FloorTransform's sense).
    const double yaw = ahead.norm() > 0.0 ? std::atan2(-ahead.x(), -ahead.y()) : 0.0;
    m.translations(f)[0] = Vec3(roots[f].x(), 0.9 + 0.02 * std::sin(f * 0.4), roots[f].y());
    m.rotations(f)[0] = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitY())) * Quat(Eigen::AngleAxisd(0.1, Vec3::UnitX()));
    m.rotations(f)[1] = Quat(Eigen::AngleAxisd(0.01 * f, Vec3(1.0, 2.0, 3.0).normalized()));
  }
  return m;
}

std::vector<Vec2> straight_walk(double seconds, double speed, double sway) {
  std::vector<Vec2> roots;
  for (int f = 0; f <= static_cast<int>(seconds * kFloorMotionFps); ++f) {
    const double t = f / kFloorMotionFps;
    roots.emplace_back(sway * std::sin(2.0 * std::numbers::pi * t), -speed * t);
  }
  return roots;
}

MotionDatabase floor_motion_database(const std::vector<Motion>& motions) {
  MotionDatabase db;
  db.fps = kFloorMotionFps;
  JointDef root{.name = "root", .animated_translation = true};
  JointDef chest{.name = "chest", .parent = 0, .rest_offset_m = Vec3(0.0, 0.4, 0.0)};
  db.skeletons.emplace_back(std::vector<JointDef>{root, chest});
  db.skeleton_names.push_back("figure");
  for (const Motion& motion : motions) {
    DatabaseClip clip;
    clip.name = "clip" + std::to_string(db.clips.size());
    clip.first_frame = db.frame_count();
    clip.frame_count = motion.frame_count;
    clip.motion = motion;
    db.clips.push_back(std::move(clip));
  }
  return db;
}

Vec2 root_of(const Motion& m, int f) {
  const Vec3& p = m.translations(f)[0];
  return {p.x(), p.z()};
}

double added_yaw(const Motion& edited, const Motion& original, int f) {
  const Quat d = edited.rotations(f)[0] * original.rotations(f)[0].conjugate();
  return 2.0 * std::atan2(d.y(), d.w());
}

void expect_only_root_moved_on_floor(const Motion& edited, const Motion& original) {
  ASSERT_EQ(edited.frame_count, original.frame_count);
  for (int f = 0; f < edited.frame_count; ++f) {
    EXPECT_DOUBLE_EQ(edited.translations(f)[0].y(), original.translations(f)[0].y());
    const Quat d = edited.rotations(f)[0] * original.rotations(f)[0].conjugate();
    EXPECT_NEAR(std::hypot(d.x(), d.z()), 0.0, 1e-9) << f;  // a turn about the vertical only
    EXPECT_EQ(edited.rotations(f)[1].coeffs(), original.rotations(f)[1].coeffs());
  }
}

}  // namespace mg::test
