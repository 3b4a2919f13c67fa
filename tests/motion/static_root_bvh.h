// A BVH like Bandai Namco Research's motion datasets, built from any clip for the tests: a
// static root joint ("joint_Root") above the clip's root (the hips), every joint with 6
// channels (its translation and its rotation), lengths in centimetres. The static root stands
// at `root_translation_m` turned by `root_rotation` in every frame; the hips' channels are
// their transform relative to it, so every world position is the clip's.
#pragma once

#include <string>

#include "motiongraph/motion/motion.h"

namespace mg::test {

inline constexpr const char* kStaticRootName = "joint_Root";

std::string static_root_bvh(const Clip& clip, const Vec3& root_translation_m = Vec3::Zero(),
                            const Quat& root_rotation = Quat::Identity(), double units_per_metre = 100.0);

}  // namespace mg::test
