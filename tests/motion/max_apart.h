// The largest distance between the joints of two clips named alike, over every frame (a joint of
// `a` missing from `b` is a test failure): how far a clip read back is from the clip it was
// written from.
#pragma once

#include <algorithm>

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/motion.h"

namespace mg::test {

inline double max_apart(const Clip& a, const Clip& b) {
  EXPECT_EQ(a.motion.frame_count, b.motion.frame_count);
  const std::vector<Vec3> pa = world_positions(a.skeleton, a.motion), pb = world_positions(b.skeleton, b.motion);
  double worst = 0.0;
  for (int j = 0; j < a.skeleton.joint_count(); ++j) {
    const auto k = b.skeleton.find(a.skeleton.joint(j).name);
    if (!k) {
      ADD_FAILURE() << "no joint " << a.skeleton.joint(j).name;
      continue;
    }
    for (int f = 0; f < std::min(a.motion.frame_count, b.motion.frame_count); ++f) {
      worst = std::max(worst, (pa[static_cast<size_t>(f * a.skeleton.joint_count() + j)] -
                               pb[static_cast<size_t>(f * b.skeleton.joint_count() + *k)]).norm());
    }
  }
  return worst;
}

}  // namespace mg::test
