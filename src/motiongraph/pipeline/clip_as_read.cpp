// A file's clip judged as info says it.
#include "motiongraph/pipeline/clip_as_read.h"

#include <vector>

#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

Result<ClipAsRead> judge_clip_as_read(const Skeleton& skeleton, const Motion& motion, std::span<const Vec3> positions,
                                      double read_fps, const std::string& format, const FootJointNames& feet) {
  ClipAsRead out;
  auto contacts = clip_contacts(skeleton, motion, feet, out.feet_missing);
  if (!contacts) return contacts.error();
  out.contacts = std::move(*contacts);
  std::vector<Vec3> computed;
  if (positions.empty()) {
    computed = world_positions(skeleton, motion);
    positions = computed;
  }
  out.doubts = clip_doubts(positions, skeleton.joint_count(), motion.fps,
                           out.contacts ? std::span<const ContactMask>(out.contacts->masks)
                                        : std::span<const ContactMask>(),
                           {}, ClipClock{read_fps, format == "gltf" || format == "fbx"},
                           out.contacts ? out.contacts->feet : FootJoints{});
  return out;
}

}  // namespace mg
