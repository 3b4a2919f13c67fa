#include "motiongraph/motion/rest_frame.h"

#include <algorithm>
#include <vector>

namespace mg {

double pose_change_rad(const Motion& motion, int frame_a, int frame_b) {
  const auto a = motion.rotations(frame_a);
  const auto b = motion.rotations(frame_b);
  double largest = 0.0;
  for (size_t j = 0; j < a.size(); ++j) largest = std::max(largest, a[j].angularDistance(b[j]));
  return largest;
}

namespace {

double root_step_m(const Motion& motion, int frame_a, int frame_b) {
  if (motion.translated_count == 0) return 0.0;
  return (motion.translations(frame_a)[0] - motion.translations(frame_b)[0]).norm();
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace

int leading_added_frames(const Motion& motion) {
  constexpr int kMaxAdded = 5;
  constexpr int kReferenceFrames = 120;
  constexpr double kRatio = 3.0;
  auto zero_root = [&](int f) {
    return motion.rotations(f)[0].coeffs() == Quat::Identity().coeffs();
  };
  int added = 0;
  while (added < motion.frame_count && added <= kMaxAdded && zero_root(added)) ++added;
  if (added == 0 || added > kMaxAdded || added + 3 > motion.frame_count) return 0;
  std::vector<double> pose_changes;
  std::vector<double> root_steps;
  for (int f = added; f + 1 < motion.frame_count && f < added + kReferenceFrames; ++f) {
    if (zero_root(f)) return 0;  // a clip that really does not turn its root
    pose_changes.push_back(pose_change_rad(motion, f, f + 1));
    root_steps.push_back(root_step_m(motion, f, f + 1));
  }
  const bool pose_jump = pose_change_rad(motion, added - 1, added) > kRatio * median(pose_changes);
  const bool root_jump = root_step_m(motion, added - 1, added) > kRatio * median(root_steps);
  return pose_jump || root_jump ? added : 0;
}

}  // namespace mg
