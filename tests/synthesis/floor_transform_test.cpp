#include "motiongraph/synthesis/floor_transform.h"

#include <gtest/gtest.h>

#include <random>

namespace mg {
namespace {

FloorTransform random_transform(std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(-4.0, 4.0), shift(-20.0, 20.0);
  return {angle(rng), shift(rng), shift(rng)};
}

TEST(FloorTransform, ComposesAsFunctionsAndInverts) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-5.0, 5.0);
  for (int i = 0; i < 200; ++i) {
    const FloorTransform a = random_transform(rng), b = random_transform(rng);
    const Vec3 p(coord(rng), coord(rng), coord(rng));
    EXPECT_LT(((a * b).apply(p) - a.apply(b.apply(p))).norm(), 1e-9);
    EXPECT_LT((a.inverse().apply(a.apply(p)) - p).norm(), 1e-9);
    EXPECT_DOUBLE_EQ(a.apply(p).y(), p.y());  // the floor's rigid motions keep heights
    // The quaternion turns vectors as rotate() does.
    EXPECT_LT((a.rotation() * p - a.rotate(p)).norm(), 1e-9);
  }
}

TEST(FloorTransform, YawTurnsAsTheFloorAlignmentDoes) {
  // A quarter turn takes +x to -z (x' = c x + s z, z' = -s x + c z), as FloorAlignment::apply.
  const FloorTransform quarter{std::acos(0.0), 1.0, 2.0};
  const Vec3 q = quarter.apply(Vec3(1.0, 0.5, 0.0));
  EXPECT_NEAR(q.x(), 1.0, 1e-12);
  EXPECT_NEAR(q.z(), 1.0, 1e-12);
  EXPECT_NEAR(q.y(), 0.5, 1e-12);
}

}  // namespace
}  // namespace mg
