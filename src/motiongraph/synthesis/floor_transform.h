// A rigid motion of the floor: rotation about the vertical (+y) axis by yaw_rad, then a
// translation (x_m, z_m) on the floor. Walks are placed in the world by composing these:
// each clip piece keeps the placement it starts with, each transition composes its floor
// alignment (metric/reference_distance.h FloorAlignment: arrival window onto departure
// window) onto it (Kovar et al. 2002, section 3.1 and 4).
#pragma once

#include <cmath>

#include "motiongraph/skeleton/rotation.h"

namespace mg {

struct FloorTransform {
  double yaw_rad = 0.0;
  double x_m = 0.0;
  double z_m = 0.0;

  // Rotation about +y: x' = c x + s z, z' = -s x + c z (as FloorAlignment::apply).
  Vec3 apply(const Vec3& p) const {
    const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
    return {c * p.x() + s * p.z() + x_m, p.y(), -s * p.x() + c * p.z() + z_m};
  }
  Vec3 rotate(const Vec3& v) const {
    const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
    return {c * v.x() + s * v.z(), v.y(), -s * v.x() + c * v.z()};
  }
  Quat rotation() const { return Quat(Eigen::AngleAxisd(yaw_rad, Vec3::UnitY())); }

  // (this * other)(p) = this(other(p)).
  FloorTransform operator*(const FloorTransform& other) const {
    const Vec3 t = rotate(Vec3(other.x_m, 0.0, other.z_m));
    return {yaw_rad + other.yaw_rad, t.x() + x_m, t.z() + z_m};
  }
  FloorTransform inverse() const {
    const FloorTransform r{-yaw_rad, 0.0, 0.0};
    const Vec3 t = r.rotate(Vec3(-x_m, 0.0, -z_m));
    return {-yaw_rad, t.x(), t.z()};
  }
};

// A floor point ((x, z)) placed by w, and a floor direction turned by it.
inline Eigen::Vector2d place(const FloorTransform& w, const Eigen::Vector2d& p) {
  const Vec3 q = w.apply(Vec3(p.x(), 0.0, p.y()));
  return {q.x(), q.z()};
}
inline Eigen::Vector2d turn(const FloorTransform& w, const Eigen::Vector2d& d) {
  const Vec3 q = w.rotate(Vec3(d.x(), 0.0, d.y()));
  return {q.x(), q.z()};
}

// The yaw (FloorTransform's sense) that turns floor direction u onto v ((x, z) each), in
// [-pi, pi].
inline double yaw_between(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  const double cross = u.x() * v.y() - u.y() * v.x();
  return std::atan2(-cross, u.dot(v));
}

// A floor transform with its cosine, sine and rotation worked out once, for placing many
// frames under it: apply() and rotation give FloorTransform's values bit for bit.
struct PreparedFloorTransform {
  explicit PreparedFloorTransform(const FloorTransform& w)
      : c(std::cos(w.yaw_rad)), s(std::sin(w.yaw_rad)), x_m(w.x_m), z_m(w.z_m), rotation(w.rotation()) {}

  Vec3 apply(const Vec3& p) const { return {c * p.x() + s * p.z() + x_m, p.y(), -s * p.x() + c * p.z() + z_m}; }

  double c, s, x_m, z_m;
  Quat rotation;
};

}  // namespace mg
