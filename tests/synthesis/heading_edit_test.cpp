#include "motiongraph/synthesis/heading_edit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "motiongraph/skeleton/rotation.h"
#include "motiongraph/synthesis/controller.h"
#include "synthesis/floor_motions.h"

namespace mg {
namespace {

using test::added_yaw;
using test::motion_along;
using test::root_of;
using test::straight_walk;

constexpr double kDeg = std::numbers::pi / 180.0;
const Vec3 kForward(0.0, 0.0, -1.0);  // motion_along's figures face their root's -z

// Plays `original` through the edit as the controller does: `chunk` frames a decision, each
// placed by the moves folded so far, the plan being the original's next `plan` frames (a second)
// under them.
Motion play_edited(const Motion& original, int chunk, const Vec2& direction, HeadingEdit& edit, int plan = 30) {
  Motion out = original;
  out.frame_count = 0;
  out.local_rotations.clear();
  out.local_translations_m.clear();
  FloorTransform folded;
  for (int first = 0; first < original.frame_count; first += chunk) {
    const int end = std::min(original.frame_count, first + chunk);
    for (int f = first; f < end; ++f) {
      out.local_rotations.insert(out.local_rotations.end(), original.rotations(f).begin(), original.rotations(f).end());
      out.local_translations_m.push_back(folded.apply(original.translations(f)[0]));
      out.rotations(f)[0] = (folded.rotation() * original.rotations(f)[0]).normalized();
      ++out.frame_count;
    }
    std::vector<Vec2> planned, planned_roots;
    for (int f = first; f < std::min(original.frame_count, first + plan); ++f) {
      planned.push_back(turn(folded, facing_on_floor(original.rotations(f)[0], kForward)));
      planned_roots.push_back(place(folded, root_of(original, f)));
    }
    const Vec2 previous = first > 0 ? root_of(out, first - 1) : Vec2::Zero();
    const FloorTransform move = edit.apply(out, first, first > 0 ? &previous : nullptr, planned, planned_roots, direction);
    folded = move * folded;
  }
  return out;
}

double bearing_of(const Vec2& d) { return std::atan2(d.x(), -d.y()) / kDeg; }

TEST(HeadingEdit, TurnsAStraightWalkOntoTheHeadingAskedForAndHoldsIt) {
  const Motion original = motion_along(straight_walk(12.0, 1.3, 0.04));
  HeadingEdit edit({}, original.fps, kForward);
  const Motion edited = play_edited(original, 6, bearing_direction(30.0), edit);
  test::expect_only_root_moved_on_floor(edited, original);
  const HeadingEditSettings defaults;
  double last_yaw = 0.0;
  // While the window is whole (at the end the figure's facing swings with its sway).
  for (int f = 1; f + 45 <= edited.frame_count; ++f) {
    // Each frame travels as far as the capture's, and turns at most the limit more per metre.
    const double step = (root_of(original, f) - root_of(original, f - 1)).norm();
    EXPECT_NEAR((root_of(edited, f) - root_of(edited, f - 1)).norm(), step, 1e-9) << f;
    const double yaw = added_yaw(edited, original, f);
    // The step is the capture's, turned by the frame's added angle.
    const Vec2 own = root_of(original, f) - root_of(original, f - 1);
    const Vec2 turned = turn(FloorTransform{yaw, 0.0, 0.0}, own);
    EXPECT_LT((root_of(edited, f) - root_of(edited, f - 1) - turned).norm(), 1e-9) << f;
    EXPECT_LE(std::abs(yaw - last_yaw), defaults.max_turn_deg_per_m * kDeg * step + 1e-9) << f;
    // Toward north-east (FloorTransform's sense: negative yaw), never past it.
    EXPECT_LE(yaw, 1e-12) << f;
    EXPECT_GE(yaw, -30.0 * kDeg - 1e-9) << f;
    last_yaw = yaw;
  }
  // After 3 s (about 4 m) it faces and walks the heading: its mean facing over each second.
  for (int f = 90; f + 30 <= edited.frame_count; f += 15) {
    Vec2 mean = Vec2::Zero();
    for (int g = f; g < f + 30; ++g) mean += facing_on_floor(edited.rotations(g)[0], kForward);
    EXPECT_NEAR(bearing_of(mean), 30.0, 1.0) << f;
    EXPECT_NEAR(bearing_of(root_of(edited, f + 30) - root_of(edited, f)), 30.0, 1.5) << f;
  }
  EXPECT_EQ(edit.stats().frames, edited.frame_count);
  EXPECT_NEAR(edit.stats().added_turn_rad, 30.0 * kDeg, 1.0 * kDeg);  // one way: no overshoot
  // 30 degrees off at first: taken out over 0.5 m it would be 60 degrees a metre.
  EXPECT_NEAR(edit.stats().max_rate_deg_per_m, defaults.max_turn_deg_per_m, 1e-9);
}

// A walk that weaves (its heading swinging +-20 degrees over 10 s) is held to its mean heading,
// the closer the shorter the turning distance.
TEST(HeadingEdit, AWeavingWalkIsHeldStraight) {
  std::vector<Vec2> roots{Vec2::Zero()};
  const double period_s = 10.0;
  for (int f = 1; f <= 20 * 30; ++f) {
    const double heading = 20.0 * kDeg * std::sin(2.0 * std::numbers::pi * f / (period_s * 30.0));
    roots.push_back(roots.back() + 1.3 / 30.0 * Vec2(std::sin(heading), -std::cos(heading)));
  }
  const Motion original = motion_along(roots);
  // The direction of travel over each second, from north: RMS after the first 2 s.
  auto swing_deg = [](const Motion& m) {
    double sum = 0.0;
    int n = 0;
    for (int f = 60; f + 30 < m.frame_count; ++f, ++n) sum += std::pow(bearing_of(root_of(m, f + 30) - root_of(m, f)), 2);
    return std::sqrt(sum / n);
  };
  auto swing_edited = [&](double distance) {
    HeadingEdit edit({.turn_distance_m = distance}, original.fps, kForward);
    return swing_deg(play_edited(original, 6, bearing_direction(0.0), edit));
  };
  EXPECT_GT(swing_deg(original), 10.0);
  // A first-order follower over 0.5 m at 1.3 m/s (0.38 s) of a swing over 10 s: about a quarter.
  EXPECT_LT(swing_edited(HeadingEditSettings{}.turn_distance_m), 0.35 * swing_deg(original));
  EXPECT_LT(swing_edited(0.25), swing_edited(0.5));
  EXPECT_LT(swing_edited(0.5), swing_edited(1.0));
  // Without the plan past the frames committed the window trails them, and the edit lags.
  HeadingEdit trailing({}, original.fps, kForward);
  const double lagging = swing_deg(play_edited(original, 6, bearing_direction(0.0), trailing, 6));
  EXPECT_LT(swing_edited(HeadingEditSettings{}.turn_distance_m), 0.75 * lagging);  // 2.8 and 4.4 degrees
}

TEST(HeadingEdit, AMotionThatDoesNotTravelOrMayNotTurnIsLeftAsItIs) {
  const Motion standing = motion_along(std::vector<Vec2>(90, Vec2(0.3, -0.2)));
  HeadingEdit edit({}, standing.fps, kForward);
  const Motion played = play_edited(standing, 6, bearing_direction(90.0), edit);
  EXPECT_EQ(played.local_translations_m, standing.local_translations_m);
  for (int f = 0; f < played.frame_count; ++f) EXPECT_NEAR(added_yaw(played, standing, f), 0.0, 1e-12);
  EXPECT_EQ(edit.stats().added_turn_rad, 0.0);

  const Motion walking = motion_along(straight_walk(5.0, 1.3, 0.03));
  HeadingEdit off({.max_turn_deg_per_m = 0.0}, walking.fps, kForward);
  const Motion unturned = play_edited(walking, 6, bearing_direction(90.0), off);
  for (int f = 0; f < walking.frame_count; ++f) {
    EXPECT_LT((root_of(unturned, f) - root_of(walking, f)).norm(), 1e-9) << f;
    EXPECT_NEAR(added_yaw(unturned, walking, f), 0.0, 1e-12) << f;
  }
}

// A small error is taken out over about turn_distance_m, not at the limit: each frame turns by
// the error left times its step over turn_distance_m, so that after n equal steps ds the turn
// is e (1 - (1 - ds / turn_distance_m)^n).
TEST(HeadingEdit, ASmallErrorTurnsInProportion) {
  const Motion original = motion_along(straight_walk(39.0 / 30.0, 1.3, 0.0));  // 40 frames, 10 edited
  ASSERT_EQ(original.frame_count, 40);
  for (double distance : {0.5, 1.0, 2.0}) {
    HeadingEdit edit({.turn_distance_m = distance}, original.fps, kForward);
    Motion out = original;
    std::vector<Vec2> planned(31, Vec2(0.0, -1.0)), roots;  // north, as the walk
    for (int f = 30; f < 40; ++f) roots.push_back(root_of(original, f));  // travelling north too
    const Vec2 previous = root_of(out, 29);
    const FloorTransform move = edit.apply(out, 30, &previous, planned, roots, bearing_direction(5.0));
    const double ds = 1.3 / 30.0;
    EXPECT_NEAR(-move.yaw_rad, 5.0 * kDeg * (1.0 - std::pow(1.0 - ds / distance, 10)), 1e-9) << distance;
    EXPECT_NEAR(added_yaw(out, original, out.frame_count - 1), move.yaw_rad, 1e-9);
    // The frames before the first edited stay.
    for (int f = 0; f < 30; ++f) EXPECT_EQ(root_of(out, f), root_of(original, f));
  }
}

// A walk that travels 8 degrees right of where it faces (each clip has such an offset of its
// own) is turned, with hold_travel, so that it travels the heading asked; by default, so that it
// faces it. A sidestep (travel 90 degrees off the facing) keeps its facing held either way.
TEST(HeadingEdit, HoldsTheTravelOfAWalkButTheFacingOfASidestep) {
  const Motion straight = motion_along(straight_walk(8.0, 1.3, 0.03));
  auto facing_off = [&](double degrees) {
    Motion m = straight;
    const Quat yaw = axis_rotation(Axis::kY, degrees * kDeg);
    for (int f = 0; f < m.frame_count; ++f) m.rotations(f)[0] = (yaw * m.rotations(f)[0]).normalized();
    return m;
  };
  // Over the last 3 s: the bearing of the travel and the mean facing.
  auto bearings = [](const Motion& m) {
    const int from = m.frame_count - 90, to = m.frame_count - 1;
    Vec2 facing = Vec2::Zero();
    for (int f = from; f <= to; ++f) facing += facing_on_floor(m.rotations(f)[0], kForward);
    return std::pair(bearing_of(root_of(m, to) - root_of(m, from)), bearing_of(facing));
  };
  const Motion walk = facing_off(8.0);
  const auto [travel0, facing0] = bearings(walk);
  ASSERT_NEAR(travel0, 0.0, 0.5);
  ASSERT_NEAR(std::abs(facing0), 8.0, 0.5);
  HeadingEdit travel({.hold_travel = true}, walk.fps, kForward), facing({}, walk.fps, kForward);
  const auto [travel_t, facing_t] = bearings(play_edited(walk, 6, bearing_direction(30.0), travel));
  EXPECT_NEAR(travel_t, 30.0, 0.5);
  EXPECT_NEAR(std::abs(facing_t - 30.0), 8.0, 0.5);
  EXPECT_GT(travel.stats().travel_share, 0.9 * static_cast<double>(travel.stats().frames));
  const auto [travel_f, facing_f] = bearings(play_edited(walk, 6, bearing_direction(30.0), facing));
  EXPECT_NEAR(facing_f, 30.0, 0.5);
  EXPECT_NEAR(std::abs(travel_f - 30.0), 8.0, 0.5);
  EXPECT_EQ(facing.stats().travel_share, 0.0);

  // In between, the travel's share: a walk at 0.45 m/s (half way from 0.3 to 0.6) is held by the
  // bisector of its facing and travel, 4 degrees each side; one 30 degrees off its facing (share
  // (cos 30 - cos 45) / (cos 20 - cos 45) = 0.68 of the direction judged) travels about 9.5 off
  // (10.5 measured: the facing judged is a mean over a swaying stride).
  auto slow = motion_along(straight_walk(8.0, 0.45, 0.0));
  const Quat eight = axis_rotation(Axis::kY, 8.0 * kDeg);
  for (int f = 0; f < slow.frame_count; ++f) slow.rotations(f)[0] = (eight * slow.rotations(f)[0]).normalized();
  HeadingEdit half({.hold_travel = true}, slow.fps, kForward);
  EXPECT_NEAR(std::abs(bearings(play_edited(slow, 6, bearing_direction(30.0), half)).first - 30.0), 4.0, 0.5);
  HeadingEdit thirty({.hold_travel = true}, walk.fps, kForward);
  const double judged = std::atan2(0.32 * std::sin(30.0 * kDeg), 0.68 + 0.32 * std::cos(30.0 * kDeg)) / kDeg;
  EXPECT_NEAR(std::abs(bearings(play_edited(facing_off(30.0), 6, bearing_direction(30.0), thirty)).first - 30.0), judged, 1.5);

  const Motion sidestep = facing_off(90.0);
  HeadingEdit side({.hold_travel = true}, sidestep.fps, kForward);
  const auto [travel_s, facing_s] = bearings(play_edited(sidestep, 6, bearing_direction(30.0), side));
  EXPECT_NEAR(facing_s, 30.0, 0.5);
  EXPECT_NEAR(std::abs(travel_s - 30.0), 90.0, 0.5);
  EXPECT_EQ(side.stats().travel_share, 0.0);
}

TEST(HeadingEdit, BadSettingsAreErrors) {
  EXPECT_TRUE(HeadingEditSettings{}.validate().ok());
  for (auto bad : {HeadingEditSettings{.max_turn_deg_per_m = -1.0}, HeadingEditSettings{.max_turn_deg_per_m = std::nan("")},
                   HeadingEditSettings{.turn_distance_m = 0.0}, HeadingEditSettings{.window_s = -1.0},
                   HeadingEditSettings{.travel_from_mps = 0.6, .travel_full_mps = 0.6},
                   HeadingEditSettings{.travel_full_mps = std::nan("")}}) {
    EXPECT_FALSE(bad.validate().ok());
    ControllerSettings controller;
    controller.heading_edit = bad;
    EXPECT_FALSE(controller.validate().ok());
  }
}

}  // namespace
}  // namespace mg
