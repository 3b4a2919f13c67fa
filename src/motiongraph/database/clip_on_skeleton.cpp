#include "motiongraph/database/clip_on_skeleton.h"

#include <fmt/format.h>

namespace mg {

double leg_scale(const Skeleton& target, const Skeleton& other) {
  const double target_leg = target.leg_length_m();
  const double leg = other.leg_length_m();
  return leg > 0.0 && target_leg > 0.0 ? target_leg / leg : 1.0;
}

Result<Motion> clip_on_skeleton(const MotionDatabase& db, int clip, int target) {
  if (target < 0 || target >= static_cast<int>(db.skeletons.size())) {
    return Error{"", 0, fmt::format("skeleton {} does not exist (the library has {})", target, db.skeletons.size())};
  }
  const DatabaseClip& c = db.clips.at(static_cast<size_t>(clip));
  const Skeleton& to = db.skeletons[static_cast<size_t>(target)];
  const Skeleton& from = db.skeletons[static_cast<size_t>(c.skeleton)];
  if (from.joint_count() != to.joint_count() || from.translated_joints().size() != to.translated_joints().size()) {
    return Error{"", 0, fmt::format("skeletons '{}' and '{}' differ in joints or translated joints",
                                    db.skeleton_names[static_cast<size_t>(c.skeleton)],
                                    db.skeleton_names[static_cast<size_t>(target)])};
  }
  Motion motion = c.motion;
  if (c.skeleton == target) return motion;
  const double scale = leg_scale(to, from);
  for (int f = 0; f < motion.frame_count; ++f) {
    for (Vec3& t : motion.translations(f)) t *= scale;
  }
  return motion;
}

}  // namespace mg
