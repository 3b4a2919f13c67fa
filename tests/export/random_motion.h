// A motion of random rotations (uniform over all rotations; end sites at identity) and random
// translations (about a metre up) in every frame: the hardest input for a writer's keys.
#pragma once

#include <random>

#include "motiongraph/motion/motion.h"

namespace mg::test {

inline Motion random_motion(const Skeleton& skeleton, int frames, double fps, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Motion motion(skeleton, frames, fps);
  for (int f = 0; f < motion.frame_count; ++f) {
    for (int j = 0; j < motion.joint_count; ++j) {
      Quat q(normal(rng), normal(rng), normal(rng), normal(rng));
      q.normalize();
      if (skeleton.joint(j).end_site) q = Quat::Identity();
      motion.rotations(f)[j] = q;
    }
    for (auto& t : motion.translations(f)) t = Vec3(normal(rng), 1.0 + normal(rng), normal(rng));
  }
  return motion;
}

}  // namespace mg::test
