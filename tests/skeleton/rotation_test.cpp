#include "motiongraph/skeleton/rotation.h"

#include <numbers>
#include <random>

#include <gtest/gtest.h>

namespace mg {
namespace {

constexpr double kPi = std::numbers::pi;

std::vector<ComposeOrder> all_tait_bryan_orders() {
  std::vector<ComposeOrder> orders;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      for (int c = 0; c < 3; ++c) {
        if (a != b && b != c && a != c) orders.push_back({Axis(a), Axis(b), Axis(c)});
      }
    }
  }
  return orders;
}

Eigen::Matrix3d elementary(Axis axis, double angle) {
  // Written out by hand, independent of Eigen's AngleAxis.
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix3d m;
  switch (axis) {
    case Axis::kX: m << 1, 0, 0, 0, c, -s, 0, s, c; break;
    case Axis::kY: m << c, 0, s, 0, 1, 0, -s, 0, c; break;
    case Axis::kZ: m << c, -s, 0, s, c, 0, 0, 0, 1; break;
  }
  return m;
}

TEST(ComposeEuler, IsTheMatrixProductInListedOrder) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (const auto& order : all_tait_bryan_orders()) {
    const Vec3 a(angle(rng), angle(rng), angle(rng));
    const Eigen::Matrix3d expected = elementary(order[0], a[0]) * elementary(order[1], a[1]) * elementary(order[2], a[2]);
    EXPECT_TRUE(compose_euler(order, a).toRotationMatrix().isApprox(expected, 1e-12));
  }
}

TEST(DecomposeEuler, InvertsComposeForEveryOrder) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (const auto& order : all_tait_bryan_orders()) {
    for (int trial = 0; trial < 500; ++trial) {
      const Quat q = compose_euler(order, Vec3(angle(rng), angle(rng), angle(rng)));
      const Vec3 angles = decompose_euler(order, q);
      EXPECT_LE(std::abs(angles[1]), kPi / 2 + 1e-12);
      EXPECT_LT(compose_euler(order, angles).angularDistance(q), 1e-9);
    }
  }
}

TEST(DecomposeEuler, HandlesGimbalLock) {
  for (const auto& order : all_tait_bryan_orders()) {
    for (double middle : {kPi / 2, -kPi / 2}) {
      const Quat q = compose_euler(order, Vec3(0.3, middle, -1.1));
      EXPECT_LT(compose_euler(order, decompose_euler(order, q)).angularDistance(q), 1e-9);
    }
  }
}

TEST(DecomposeEuler, StaysNearThePreviousFrame) {
  // A rotation turning steadily past 180 degrees: unwrapped angles keep growing.
  const ComposeOrder order{Axis::kZ, Axis::kX, Axis::kY};
  std::optional<Vec3> previous;
  for (int step = 0; step <= 400; ++step) {
    const double z = step * 0.02;
    const Quat q = compose_euler(order, Vec3(z, 0.2, -0.1));
    const Vec3 angles = decompose_euler(order, q, previous);
    EXPECT_LT(compose_euler(order, angles).angularDistance(q), 1e-9);
    if (previous) {
      EXPECT_LT((angles - *previous).norm(), 0.05) << "step " << step;
    }
    previous = angles;
  }
  EXPECT_NEAR((*previous)[0], 8.0, 1e-9);
}

TEST(AxisStrings, AcclaimOrderIsAppliedFirstToLast) {
  auto axes = parse_axis_string("XYZ");
  ASSERT_TRUE(axes);
  const ComposeOrder compose = acclaim_compose_order(*axes);
  EXPECT_EQ(compose, (ComposeOrder{Axis::kZ, Axis::kY, Axis::kX}));
  EXPECT_TRUE(parse_axis_string("zxy"));
  for (const char* bad : {"XXY", "XY", "XYZW", "ABC", ""}) EXPECT_FALSE(parse_axis_string(bad)) << bad;
}

}  // namespace
}  // namespace mg
