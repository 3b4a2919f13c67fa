#include "motiongraph/database/turning_balance.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "synthesis/floor_motions.h"

namespace mg {
namespace {

constexpr double kPi = std::numbers::pi;

// A root travelling `speed` m/s: 1 s straight north, then turning `turn_deg` (positive left) at
// `rate_deg` a second, then 1 s straight; mirrored (x negated) when asked.
Motion travel(double speed, double turn_deg, double rate_deg, bool mirrored = false) {
  const double fps = test::kFloorMotionFps;
  const double turn_s = std::abs(turn_deg) / rate_deg;
  const int frames = static_cast<int>(std::round((2.0 + turn_s) * fps)) + 1;
  std::vector<Vec2> roots;
  double x = 0.0, z = 0.0, heading = 0.0;  // from north (-z) towards east (+x)
  for (int f = 0; f < frames; ++f) {
    roots.emplace_back(mirrored ? -x : x, z);
    const double t = f / fps;
    if (t >= 1.0 && t < 1.0 + turn_s) heading -= std::copysign(rate_deg, turn_deg) * kPi / 180.0 / fps;
    x += std::sin(heading) * speed / fps;
    z -= std::cos(heading) * speed / fps;
  }
  return test::motion_along(roots);
}

TurningBalance of(const std::vector<Motion>& motions) { return turning_balance(test::floor_motion_database(motions)); }

TEST(TurningBalance, AWalkTurningLeftIsLopsidedUntilItsMirrorTurnsRight) {
  const Motion left = travel(1.2, 90.0, 45.0);
  const TurningBalance one = of({left});
  EXPECT_NEAR(one.left_deg, 90.0, 10.0);
  EXPECT_EQ(one.right_deg, 0.0);
  EXPECT_NEAR(one.travel_s, left.duration_s() - 1.0, 0.1);  // but for the half second at either end
  EXPECT_TRUE(one.lopsided());
  // With the same turn mirrored, it turns as far right.
  const TurningBalance both = of({left, travel(1.2, 90.0, 45.0, true)});
  EXPECT_NEAR(both.right_deg, one.left_deg, 1e-9);
  EXPECT_NEAR(both.left_deg, one.left_deg, 1e-9);
  EXPECT_FALSE(both.lopsided());
  // A turn right a third as far is still lopsided; one half as far is not.
  EXPECT_TRUE(of({left, travel(1.2, -25.0, 45.0)}).lopsided());
  EXPECT_FALSE(of({left, travel(1.2, -50.0, 45.0)}).lopsided());
  // Too little turning, too slow a turn, too slow a walk, or none: not lopsided.
  EXPECT_FALSE(of({travel(1.2, 50.0, 45.0)}).lopsided());
  EXPECT_EQ(of({travel(1.2, 90.0, 10.0)}).left_deg, 0.0);
  const TurningBalance dawdle = of({travel(0.3, 90.0, 45.0)});
  EXPECT_EQ(dawdle.travel_s, 0.0);
  EXPECT_EQ(dawdle.left_deg, 0.0);
  const TurningBalance straight = of({travel(1.2, 0.0, 45.0)});
  EXPECT_EQ(straight.left_deg + straight.right_deg, 0.0);
  EXPECT_FALSE(straight.lopsided());
}

}  // namespace
}  // namespace mg
