#include "motiongraph/synthesis/path_edit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "motiongraph/synthesis/floor_transform.h"
#include "synthesis/floor_motions.h"

namespace mg {
namespace {

using test::added_yaw;
using test::expect_only_root_moved_on_floor;
using test::motion_along;
using test::root_of;
using test::straight_walk;
constexpr double kFps = test::kFloorMotionFps;

TEST(PathEdit, AMotionOnThePathStaysAsItIs) {
  auto path = make_shape("line:20");
  ASSERT_TRUE(path.ok());
  const Motion original = motion_along(straight_walk(10.0, 1.3, 0.0));
  Motion edited = original;
  auto stats = edit_onto_path(edited, *path);
  ASSERT_TRUE(stats.ok()) << stats.error().to_string();
  EXPECT_TRUE(stats->edited);
  EXPECT_EQ(stats->limited_share, 0.0);
  for (int f = 0; f < edited.frame_count; ++f) {
    EXPECT_LT((root_of(edited, f) - root_of(original, f)).norm(), 1e-9) << f;
    EXPECT_NEAR(added_yaw(edited, original, f), 0.0, 1e-9) << f;
  }
}

TEST(PathEdit, BendsAStraightWalkOntoACircleKeepingItsSwayAndSpeed) {
  auto path = make_shape("circle:10");  // turning 5.7 degrees a metre
  ASSERT_TRUE(path.ok());
  const double sway = 0.03;
  const Motion original = motion_along(straight_walk(40.0, 1.3, sway));
  double before = 0.0;
  for (int f = 0; f < original.frame_count; ++f) before += path->distance_to(root_of(original, f));
  Motion edited = original;
  auto stats = edit_onto_path(edited, *path);
  ASSERT_TRUE(stats.ok());
  expect_only_root_moved_on_floor(edited, original);
  EXPECT_LT(stats->limited_share, 0.01);
  // Off the circle by its sway (a mean of 2 sway / pi), not by the metres the straight walk was.
  double after = 0.0, travel_before = 0.0, travel_after = 0.0, worst_facing = 0.0;
  for (int f = 0; f < edited.frame_count; ++f) {
    after += path->distance_to(root_of(edited, f));
    if (f > 0) {
      travel_before += (root_of(original, f) - root_of(original, f - 1)).norm();
      travel_after += (root_of(edited, f) - root_of(edited, f - 1)).norm();
    }
    // It faces along the circle, as the walk faced along its line (its facing turned by the edit).
    const double t = f / kFps;
    if (t > 2.0 && 1.3 * t < path->length_m() - 1.0) {
      const Vec3 facing = edited.rotations(f)[0] * Quat(Eigen::AngleAxisd(0.1, Vec3::UnitX())).conjugate() *
                          Vec3(0.0, 0.0, -1.0);
      // The point of the circle nearest the root, and the circle's direction there (clockwise).
      const Vec2 centre(10.0, 0.0);
      const Vec2 out = (root_of(edited, f) - centre).normalized();
      const Vec2 along(-out.y(), out.x());
      worst_facing = std::max(worst_facing, std::acos(std::clamp(Vec2(facing.x(), facing.z()).dot(along), -1.0, 1.0)));
    }
  }
  before /= original.frame_count;
  after /= edited.frame_count;
  EXPECT_GT(before, 3.0);
  EXPECT_LT(after, 2.0 * sway / std::numbers::pi + 0.015);
  EXPECT_NEAR(travel_after, travel_before, 0.005 * travel_before);
  EXPECT_LT(worst_facing * 180.0 / std::numbers::pi, 3.0);
  EXPECT_GT(stats->max_added_turn_deg, 180.0);  // more than half the circle: the walk went 52 m
}

TEST(PathEdit, NeverAddsMoreTurningThanAllowed) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    // A wandering walk: its heading drifts at random, its speed varies, it sometimes stops.
    std::vector<Vec2> roots{Vec2::Zero()};
    double heading = 0.0;
    for (int f = 1; f < 900; ++f) {
      heading += (unit(rng) - 0.5) * 0.2;
      const double speed = (f / 90) % 4 == 3 ? 0.0 : 0.5 + 1.5 * unit(rng);
      roots.push_back(roots.back() + speed / kFps * Vec2(std::sin(heading), -std::cos(heading)));
    }
    const Motion original = motion_along(roots);
    const char* shapes[] = {"s-curve:40", "circle:3", "figure8:4", "line:30"};
    auto path = make_shape(shapes[trial % 4]);
    ASSERT_TRUE(path.ok());
    PathEditSettings settings;
    settings.max_turn_deg_per_m = 5.0 + 40.0 * unit(rng);
    settings.smooth_s = 0.5 + unit(rng);
    Motion edited = original;
    auto stats = edit_onto_path(edited, *path, settings);
    ASSERT_TRUE(stats.ok());
    expect_only_root_moved_on_floor(edited, original);
    // The motion's own path, as the edit defines it, and the turn added from frame to frame.
    const int half = static_cast<int>(std::lround(settings.smooth_s * kFps / 2.0));
    const int n = original.frame_count;
    Vec2 last = Vec2::Zero();
    for (int f = 0; f < n; ++f) {
      const int h = std::min({half, f, n - 1 - f});
      Vec2 q = Vec2::Zero();
      for (int g = f - h; g <= f + h; ++g) q += root_of(original, g);
      q /= 2 * h + 1;
      if (f > 0) {
        const double step = (q - last).norm();
        const double turn = std::remainder(added_yaw(edited, original, f) - added_yaw(edited, original, f - 1),
                                           2.0 * std::numbers::pi);
        EXPECT_LE(std::abs(turn), settings.max_turn_deg_per_m * std::numbers::pi / 180.0 * step + 1e-9)
            << "trial " << trial << " frame " << f;
      }
      last = q;
    }
  }
}

// A straight walk that goes on past a corner is bent onto the next leg and along it, forward,
// however sharp the corner: at a corner of 90 degrees or more the walk crosses the next leg
// square or against it, which is not going back along the path (it was taken for that, and
// the walk was steered back the way it came: CMU 29's zigzag delivered 30 of its 48 m, then
// went back to 15 m).
TEST(PathEdit, FollowsASharpCornerForwardAlongTheNextLeg) {
  for (const double corner_deg : {60.0, 90.0, 110.0, 135.0, 160.0}) {
    const double turn = corner_deg * std::numbers::pi / 180.0;
    const Vec2 corner(0.0, -10.0);
    auto path = FloorPath::create({Vec2::Zero(), corner, corner + 10.0 * Vec2(std::sin(turn), -std::cos(turn))});
    ASSERT_TRUE(path.ok());
    const Motion original = motion_along(straight_walk(16.0, 1.3, 0.03));  // 20.8 m
    Motion edited = original;
    auto stats = edit_onto_path(edited, *path);
    ASSERT_TRUE(stats.ok());
    std::vector<Vec2> roots;
    for (int f = 0; f < edited.frame_count; ++f) roots.push_back(root_of(edited, f));
    const std::vector<double> arcs = path->followed_arcs(roots);
    // It never goes back along the path by more than its sway (at a hairpin of 160 degrees,
    // cut inside, the first leg's nearest point lies a little back along it); and up to 135
    // degrees its 20.8 m carry it to the end of the 20 m path, less what the corner cuts (the
    // edit turns 45 degrees a metre at most: a hairpin swings 2-3 m wide).
    double furthest = 0.0;
    for (double a : arcs) {
      furthest = std::max(furthest, a);
      EXPECT_GT(a, furthest - (corner_deg > 135.0 ? 0.5 : 0.1)) << corner_deg;
    }
    if (corner_deg > 135.0) continue;
    EXPECT_GT(arcs.back(), path->length_m() - 2.5) << corner_deg;
    double mean = 0.0;
    for (const Vec2& r : roots) mean += path->distance_to(r);
    EXPECT_LT(mean / static_cast<double>(roots.size()), 0.5) << corner_deg;
  }
}

// The same on zigzags: legs of 6 m whose corners turn 42-117 degrees either way, walked by a
// motion whose heading wanders and turns once by up to 86 degrees of its own. The edited motion
// never goes back along the path by more than a step (11 of these 400 went back 1.5-8 m with
// the rule before, which took heading against the path's direction for going back).
TEST(PathEdit, ZigzagsAreFollowedForwardNeverBackTheWayTheMotionCame) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    const double turn = (60.0 + 30.0 * unit(rng)) * std::numbers::pi / 180.0 * (unit(rng) < 0.5 ? -1.0 : 1.0);
    std::vector<Vec2> points{Vec2::Zero()};
    double heading = 0.0;
    for (int leg = 0; leg < 5; ++leg) {
      points.push_back(points.back() + 6.0 * Vec2(std::sin(heading), -std::cos(heading)));
      heading += (leg % 2 == 0 ? turn : -turn) * (0.7 + 0.6 * unit(rng));
    }
    auto path = FloorPath::create(points);
    ASSERT_TRUE(path.ok());
    std::vector<Vec2> roots{Vec2::Zero()};
    heading = 0.0;
    const double own_turn_at = 2.0 + 16.0 * unit(rng), own_turn = (unit(rng) - 0.5) * 3.0;
    for (int f = 1; f < 900; ++f) {
      const double t = f / kFps;
      if (t > own_turn_at && t < own_turn_at + 1.0) heading += own_turn / kFps;
      heading += (unit(rng) - 0.5) * 0.15;
      roots.push_back(roots.back() + 1.3 / kFps * Vec2(std::sin(heading), -std::cos(heading)));
    }
    Motion edited = motion_along(roots);
    auto stats = edit_onto_path(edited, *path);
    ASSERT_TRUE(stats.ok());
    std::vector<Vec2> delivered;
    for (int f = 0; f < edited.frame_count; ++f) delivered.push_back(root_of(edited, f));
    const std::vector<double> arcs = path->followed_arcs(delivered);
    double furthest = 0.0, back = 0.0;
    for (double a : arcs) {
      furthest = std::max(furthest, a);
      back = std::max(back, furthest - a);
    }
    EXPECT_LT(back, 1.5) << "trial " << trial;
  }
}

// The rounded path: a line stays as it is, a bend wider than the window stays within millimetres
// (twicing), a corner is cut evenly, the ends stay.
TEST(PathEdit, RoundedCornersKeepLinesAndBendsAndCutCorners) {
  auto line = make_shape("line:20");
  ASSERT_TRUE(line.ok());
  const FloorPath straight = round_corners(*line, 1.5);
  for (const Vec2& p : straight.points()) EXPECT_LT(line->distance_to(p), 1e-9);
  EXPECT_NEAR(straight.length_m(), 20.0, 1e-9);

  auto circle = make_shape("circle:5");
  ASSERT_TRUE(circle.ok());
  const FloorPath bend = round_corners(*circle, 1.5);
  // Away from its ends (the circle's start, where the window shrinks) within millimetres; near
  // them within 3 cm.
  for (const Vec2& p : bend.points()) EXPECT_LT(circle->distance_to(p), p.norm() > 3.0 ? 0.005 : 0.03);

  const Vec2 corner(0.0, -10.0);
  auto square = FloorPath::create({Vec2::Zero(), corner, Vec2(10.0, -10.0)});
  ASSERT_TRUE(square.ok());
  const FloorPath cut = round_corners(*square, 1.5);
  double nearest = 1e9;
  for (const Vec2& p : cut.points()) nearest = std::min(nearest, (p - corner).norm());
  EXPECT_GT(nearest, 0.2);   // the corner is cut...
  EXPECT_LT(nearest, 1.0);   // ...within the window
  // ... evenly: the cut path is symmetric about the corner's bisector ((x, z) -> (z + 10, x - 10)
  // swaps the legs).
  for (const Vec2& p : cut.points()) EXPECT_LT(cut.distance_to(Vec2(p.y() + 10.0, p.x() - 10.0)), 0.01);
  EXPECT_LT((cut.points().front() - square->points().front()).norm(), 1e-9);
  EXPECT_LT((cut.points().back() - square->points().back()).norm(), 1e-9);
  // Nothing to round: the path itself.
  EXPECT_EQ(round_corners(*square, 0.0).points(), square->points());
}

// A walk bent onto a zigzag follows it closer steering for the rounded path than for the sharp
// one, which it overshot at each corner (it turned only once there).
TEST(PathEdit, RoundedCornersAreFollowedCloserThanSharpOnes) {
  auto path = make_shape("zigzag:6");
  ASSERT_TRUE(path.ok());
  const Motion original = motion_along(straight_walk(40.0, 1.3, 0.03));
  double mean[2] = {};
  for (const int rounded : {0, 1}) {
    PathEditSettings settings;
    if (rounded == 0) settings.round_corners_m = 0.0;
    Motion edited = original;
    auto stats = edit_onto_path(edited, *path, settings);
    ASSERT_TRUE(stats.ok());
    const int end = static_cast<int>(path->length_m() / 1.3 * kFps);
    for (int f = 0; f < end; ++f) mean[rounded] += path->distance_to(root_of(edited, f)) / end;
  }
  EXPECT_LT(mean[1], 0.7 * mean[0]);
  EXPECT_LT(mean[1], 0.15);
}

// A motion that steps back goes back along the path: it is not turned round.
TEST(PathEdit, AStepBackGoesBackAlongThePath) {
  auto path = make_shape("line:20");
  ASSERT_TRUE(path.ok());
  std::vector<Vec2> roots;
  for (int f = 0; f <= 300; ++f) {
    const double t = f / kFps;  // 4 s north, 2 s back south (facing north), 4 s north, at 1 m/s
    const double along = t < 4.0 ? t : t < 6.0 ? 8.0 - t : t - 4.0;
    roots.emplace_back(0.0, -along);
  }
  Motion original = motion_along(roots);
  for (int f = 0; f < original.frame_count; ++f) original.rotations(f)[0] = Quat::Identity();  // facing north
  Motion edited = original;
  auto stats = edit_onto_path(edited, *path);
  ASSERT_TRUE(stats.ok());
  for (int f = 0; f < edited.frame_count; ++f) {
    EXPECT_LT(path->distance_to(root_of(edited, f)), 0.05) << f;
    EXPECT_LT(std::abs(added_yaw(edited, original, f)) * 180.0 / std::numbers::pi, 5.0) << f;
  }
}

TEST(PathEdit, NoTurningAllowedLeavesTheMotionAsItIs) {
  auto path = make_shape("s-curve:40");
  ASSERT_TRUE(path.ok());
  const Motion original = motion_along(straight_walk(20.0, 1.3, 0.03));
  Motion edited = original;
  PathEditSettings settings;
  settings.max_turn_deg_per_m = 0.0;
  auto stats = edit_onto_path(edited, *path, settings);
  ASSERT_TRUE(stats.ok());
  EXPECT_GT(stats->limited_share, 0.5);
  for (int f = 0; f < edited.frame_count; ++f) {
    EXPECT_LT((root_of(edited, f) - root_of(original, f)).norm(), 1e-9) << f;
  }
}

TEST(PathEdit, AMotionThatDoesNotTravelIsLeftAlone) {
  auto path = make_shape("line:10");
  ASSERT_TRUE(path.ok());
  const Motion original = motion_along(std::vector<Vec2>(60, Vec2(0.01, 0.0)));
  Motion edited = original;
  auto stats = edit_onto_path(edited, *path);
  ASSERT_TRUE(stats.ok());
  EXPECT_FALSE(stats->edited);
  EXPECT_EQ(edited.local_translations_m, original.local_translations_m);
}

TEST(PathEdit, BadSettingsAreErrors) {
  auto path = make_shape("line:10");
  ASSERT_TRUE(path.ok());
  Motion m = motion_along(straight_walk(5.0, 1.0, 0.0));
  for (auto bad : {PathEditSettings{.smooth_s = -1.0}, PathEditSettings{.tangent_m = 0.0},
                   PathEditSettings{.max_turn_deg_per_m = -1.0}, PathEditSettings{.lookahead_m = 0.0},
                   PathEditSettings{.max_turn_deg_per_m = std::nan("")}, PathEditSettings{.round_corners_m = -1.0}}) {
    EXPECT_FALSE(bad.validate().ok());
    EXPECT_FALSE(edit_onto_path(m, *path, bad).ok());
  }
}

}  // namespace
}  // namespace mg
