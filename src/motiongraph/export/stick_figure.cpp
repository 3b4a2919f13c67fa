#include "motiongraph/export/stick_figure.h"

#include <algorithm>
#include <array>

namespace mg {

namespace {

// The octahedral bone from `head` to `tail`: 8 flat faces, 24 vertices with their face normals;
// the tail's apex bound to `child`, the rest to `joint`.
void add_bone(const Vec3& head, const Vec3& tail, int joint, int child, StickFigure& figure) {
  const Vec3 axis = tail - head;
  const double length = axis.norm();
  const Vec3 d = axis / length;
  const Vec3 u = d.unitOrthogonal();
  const Vec3 v = d.cross(u);
  const double radius = std::min(0.1 * length, 0.03);
  const Vec3 middle = head + 0.2 * axis;
  const std::array<Vec3, 4> ring{middle + radius * u, middle + radius * v, middle - radius * u, middle - radius * v};
  for (int i = 0; i < 4; ++i) {
    for (int end = 0; end < 2; ++end) {
      const Vec3& apex = end == 0 ? head : tail;
      std::array<Vec3, 3> corner{apex, ring[i], ring[(i + 1) % 4]};
      Vec3 normal = (corner[1] - corner[0]).cross(corner[2] - corner[0]).normalized();
      // Counter-clockwise seen from outside: the normal points away from the axis.
      if (normal.dot((corner[0] + corner[1] + corner[2]) / 3.0 - middle) < 0.0) {
        std::swap(corner[1], corner[2]);
        normal = -normal;
      }
      for (int c = 0; c < 3; ++c) {
        figure.positions.push_back(corner[c]);
        figure.normals.push_back(normal);
        figure.joints.push_back(c == 0 && end == 1 ? child : joint);  // corner 0 is the apex
      }
    }
  }
}

}  // namespace

StickFigure stick_figure(const Skeleton& skeleton, std::span<const Vec3> rest_world_m) {
  StickFigure figure;
  for (int j = 1; j < skeleton.joint_count(); ++j) {
    const int parent = skeleton.parent(j);
    const Vec3& head = rest_world_m[static_cast<size_t>(parent)];
    const Vec3& tail = rest_world_m[static_cast<size_t>(j)];
    if ((tail - head).norm() < 1e-3) continue;  // no bone to draw
    add_bone(head, tail, parent, j, figure);
  }
  return figure;
}

}  // namespace mg
