#include "motiongraph/motion/clip_summary.h"

#include <algorithm>
#include <limits>

#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

ClipSummary summarize(const Skeleton& skeleton, const Motion& motion) {
  ClipSummary s;
  for (const JointDef& joint : skeleton.joints()) (joint.end_site ? s.end_sites : s.joints)++;
  s.frames = motion.frame_count;
  s.fps = motion.fps;
  s.duration_s = motion.duration_s();
  if (motion.frame_count == 0) return s;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 low(kInf, kInf, kInf);
  Vec3 high = -low;
  const size_t joints = static_cast<size_t>(skeleton.joint_count());
  std::vector<Vec3> positions(joints);
  std::vector<Quat> rotations(joints);
  Vec3 previous_root = Vec3::Zero();
  for (int f = 0; f < motion.frame_count; ++f) {
    forward_kinematics(skeleton, motion, f, positions, rotations);
    for (const Vec3& p : positions) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    if (f > 0) {
      Vec3 step = positions[0] - previous_root;
      step.y() = 0.0;
      s.root_path_m += step.norm();
    }
    previous_root = positions[0];
  }
  s.floor_min_x_m = low.x();
  s.floor_max_x_m = high.x();
  s.floor_min_z_m = low.z();
  s.floor_max_z_m = high.z();
  s.min_height_m = low.y();
  s.max_height_m = high.y();
  return s;
}

}  // namespace mg
