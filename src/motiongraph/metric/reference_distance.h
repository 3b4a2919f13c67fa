// The frame distance computed pair by pair, straight from its definition (DESIGN.md 3.1):
// the closed-form floor alignment (theta by atan2, translation from the weighted centroids),
// then the weighted sum of squared distances between the aligned clouds, summed explicitly.
// O(k P) per pair. Kept as the reference the fast tiled path is tested against, and used to
// compute the alignment of the transitions that are kept.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/database/motion_database.h"
#include "motiongraph/metric/point_cloud.h"
#include "motiongraph/skeleton/rotation.h"

namespace mg {

struct FloorAlignment {
  double yaw_rad = 0.0;  // rotation about +y applied to the arrival window's points
  double x_m = 0.0;      // then this translation on the floor
  double z_m = 0.0;
  Vec3 apply(const Vec3& q) const;
};

struct ReferenceDistance {
  double distance = 0.0;
  FloorAlignment alignment;
};

// The clouds of every frame of the database, in double: frames x points world positions
// (metres), what the reference takes. Memory: 24 bytes per point and frame.
std::vector<Vec3> database_clouds(const MotionDatabase& db, const CloudLayout& layout);

// clouds: frames x points world positions (metres). Pairs frame a+t with frame b-k+1+t,
// weight taper[t] * point_weights[i]. The caller makes sure both windows exist.
ReferenceDistance reference_distance(std::span<const Vec3> clouds, int points, std::span<const double> point_weights,
                                     std::span<const double> taper, int a, int b);

}  // namespace mg
