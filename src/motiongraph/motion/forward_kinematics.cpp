#include "motiongraph/motion/forward_kinematics.h"

#include <cassert>

namespace mg {

void forward_kinematics(const Skeleton& skeleton, const Motion& motion, int frame,
                        std::span<Vec3> world_positions_m, std::span<Quat> world_rotations) {
  assert(static_cast<int>(world_positions_m.size()) == skeleton.joint_count());
  assert(static_cast<int>(world_rotations.size()) == skeleton.joint_count());
  const auto rotations = motion.rotations(frame);
  const auto translations = motion.translations(frame);
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    const JointDef& joint = skeleton.joint(j);
    const int slot = skeleton.translation_slot(j);
    const Vec3& local_translation = slot >= 0 ? translations[slot] : joint.rest_offset_m;
    if (joint.parent < 0) {
      world_positions_m[j] = local_translation;
      world_rotations[j] = rotations[j];
    } else {
      const Quat& parent_rotation = world_rotations[joint.parent];
      world_positions_m[j] = world_positions_m[joint.parent] + parent_rotation * local_translation;
      world_rotations[j] = parent_rotation * rotations[j];
    }
  }
}

std::vector<Vec3> world_positions(const Skeleton& skeleton, const Motion& motion) {
  const size_t joints = static_cast<size_t>(skeleton.joint_count());
  std::vector<Vec3> positions(static_cast<size_t>(motion.frame_count) * joints);
  std::vector<Quat> scratch(joints);
  for (int f = 0; f < motion.frame_count; ++f) {
    forward_kinematics(skeleton, motion, f, std::span(positions.data() + f * joints, joints), scratch);
  }
  return positions;
}

}  // namespace mg
