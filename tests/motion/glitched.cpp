#include "motion/glitched.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "motiongraph/motion/forward_kinematics.h"

namespace mg::test {

double largest_step(const Skeleton& skeleton, const Motion& motion, int f) {
  const std::vector<Vec3> p = world_positions(skeleton, motion.slice(f, 2));
  const int joints = skeleton.joint_count();
  double most = 0.0;
  for (int j = 0; j < joints; ++j) most = std::max(most, (p[joints + j] - p[j]).norm());
  return most;
}

Motion every_nth_frame(const Clip& clip, int n, double fps) {
  Motion out(clip.skeleton, clip.motion.frame_count / n, fps);
  for (int f = 0; f < out.frame_count; ++f) {
    std::copy_n(clip.motion.rotations(n * f).begin(), out.joint_count, out.rotations(f).begin());
    std::copy_n(clip.motion.translations(n * f).begin(), out.translated_count, out.translations(f).begin());
  }
  return out;
}

Clip first_frames(Clip clip, int frames) {
  clip.motion = clip.motion.slice(0, frames);
  return clip;
}

Clip with_turn(Clip clip, const std::string& name, int first, int last, double radians) {
  const std::optional<int> found = clip.skeleton.find(name);
  EXPECT_TRUE(found.has_value()) << name;
  const int j = found.value_or(0);
  for (int f = first; f <= last; ++f) {
    Quat& q = clip.motion.rotations(f)[j];
    q = (q * Quat(Eigen::AngleAxisd(radians, Vec3::UnitX()))).normalized();
  }
  return clip;
}

}  // namespace mg::test
