#include "motiongraph/export/root_rotation_order.h"

namespace mg {

ComposeOrder root_rotation_order(const Skeleton& skeleton) {
  const Vec3 up = skeleton.static_ancestor_rotation().conjugate() * Vec3::UnitY();
  int a = 0;
  up.cwiseAbs().maxCoeff(&a);
  return {static_cast<Axis>(a), static_cast<Axis>((a + 2) % 3), static_cast<Axis>((a + 1) % 3)};
}

}  // namespace mg
