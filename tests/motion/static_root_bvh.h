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

// An engine's root motion carrying the translation alone, built from any clip whose root is its
// hips: a joint "root_motion" above them on the floor under them, turned by `turn` and by
// `yaw_per_frame` radians more each frame, the clip's root below it where it was in the world;
// with `ik`, a helper joint ("ik_foot_l") hanging off root_motion beside the body.
Clip translation_root_clip(const Clip& clip, const Quat& turn, double yaw_per_frame, bool ik);

}  // namespace mg::test
