// Point clouds for the frame distance (Kovar et al. 2002, section 3.1; DESIGN.md section 3).
//
// A frame is compared through a cloud of points that move rigidly with the skeleton:
//  - bone rings (default, as in the seed): along every bone, rings of points at a spacing,
//    each ring a few points around the bone at a radius, fixed in the bone's parent frame;
//  - joints only: one point per joint.
// The layout (which bone, where along it as a fraction of its length, which angle around it)
// is made once from a reference skeleton, so clips of other subjects with the same topology
// get the same points, placed on their own bones. Points are in metres, world space, y up.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct PointCloudSettings {
  enum class Kind { kBoneRings, kJoints };
  Kind kind = Kind::kBoneRings;
  double ring_spacing_m = 0.25;  // distance between rings along a bone
  double ring_radius_m = 0.06;   // distance of a ring's points from the bone
  int points_per_ring = 4;
  // Weight of the points on the bone ending at a joint (by joint name); others weigh 1.
  std::vector<std::pair<std::string, double>> joint_weights;

  Status validate() const;
};

struct CloudLayout {
  // Per point: the joint whose frame carries it (the bone's parent joint), the bone's end
  // joint, how far along the bone (0 = parent joint, 1 = end joint), angle around the bone,
  // radius (metres), and its weight.
  std::vector<int> parent_joint;
  std::vector<int> end_joint;
  std::vector<double> along;
  std::vector<double> angle_rad;
  std::vector<double> radius_m;
  std::vector<float> weight;
  int point_count() const { return static_cast<int>(weight.size()); }
};

// The layout for a skeleton; fails on bad settings or a skeleton without bones.
// The most points a cloud may have (the default rings put about 160 on a CMU skeleton).
inline constexpr int kMaxCloudPoints = 10000;

Result<CloudLayout> make_cloud_layout(const Skeleton& reference, const PointCloudSettings& settings);

// Whether `skeleton` has the topology the layout was made for.
bool layout_fits(const CloudLayout& layout, const Skeleton& skeleton);

// Places a layout's points on one skeleton; evaluates them frame by frame (double precision).
class CloudEvaluator {
 public:
  CloudEvaluator(const Skeleton& skeleton, const CloudLayout& layout);
  // World positions (metres) of the cloud of one frame; `out` holds layout.point_count().
  void points(const Motion& motion, int frame, std::span<Vec3> out);

 private:
  const Skeleton& skeleton_;
  const CloudLayout& layout_;
  std::vector<Vec3> local_;  // each point in its parent joint's frame
  std::vector<Vec3> positions_;
  std::vector<Quat> rotations_;
};

// World positions of the cloud of every frame: frame_count x point_count x 3 floats (x, y, z).
std::vector<float> compute_clouds(const Skeleton& skeleton, const Motion& motion, const CloudLayout& layout);

}  // namespace mg
