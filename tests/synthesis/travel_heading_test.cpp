// The direction a walk goes: the travel's share of it by speed, angle and window (the rule as the
// header states it), and each database frame's turn against a brute-force reading of its own
// clip: a walk travelling 8 degrees off its facing turned onto its travel, a sidestep and a
// motion on the spot left alone, windows kept within their clip.
#include "motiongraph/synthesis/travel_heading.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "motiongraph/skeleton/rotation.h"
#include "synthesis/floor_motions.h"

namespace mg {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const Vec3 kForward(0.0, 0.0, -1.0);  // motion_along's figures face their root's -z

TEST(TravelHeading, TheTravelsShareBySpeedAngleAndWindow) {
  HeadingEditSettings on;
  on.hold_travel = true;
  const Vec2 north(0.0, -1.0);
  auto along = [&](double degrees, double metres) {
    return Vec2(std::sin(degrees * kDeg) * metres, -std::cos(degrees * kDeg) * metres);
  };
  // A second's walk at 1 m/s along the facing: all of it; the facing's length does not matter.
  EXPECT_DOUBLE_EQ(travel_share(on, north, along(0.0, 1.0), 1.0, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(travel_share(on, 3.0 * north, along(0.0, 1.0), 1.0, 1.0), 1.0);
  EXPECT_EQ(travel_share(HeadingEditSettings{}, north, along(0.0, 1.0), 1.0, 1.0), 0.0);  // not held
  // By speed: none at 0.3 m/s and below, half at 0.45, all from 0.6.
  EXPECT_EQ(travel_share(on, north, along(0.0, 0.2), 1.0, 1.0), 0.0);
  EXPECT_NEAR(travel_share(on, north, along(0.0, 0.45), 1.0, 1.0), 0.5, 1e-12);
  EXPECT_NEAR(travel_share(on, north, along(0.0, 0.9), 1.5, 1.0), 1.0, 1e-12);  // 0.6 m/s
  // By angle: all within 20 degrees, none beyond 45, linear in the cosine between.
  EXPECT_DOUBLE_EQ(travel_share(on, north, along(-19.0, 1.0), 1.0, 1.0), 1.0);
  const double thirty = (std::cos(30.0 * kDeg) - std::cos(45.0 * kDeg)) / (std::cos(20.0 * kDeg) - std::cos(45.0 * kDeg));
  EXPECT_NEAR(travel_share(on, north, along(30.0, 1.0), 1.0, 1.0), thirty, 1e-12);
  EXPECT_EQ(travel_share(on, north, along(50.0, 1.0), 1.0, 1.0), 0.0);
  EXPECT_EQ(travel_share(on, north, along(180.0, 1.0), 1.0, 1.0), 0.0);  // walking backwards
  // By window: whole from a whole one, none at three quarters and below.
  EXPECT_NEAR(travel_share(on, north, along(0.0, 0.875), 0.875, 0.875), 0.5, 1e-12);
  EXPECT_EQ(travel_share(on, north, along(0.0, 0.7), 0.7, 0.7), 0.0);
  // Nothing to judge: no facing, no travel, no time.
  EXPECT_EQ(travel_share(on, Vec2::Zero(), along(0.0, 1.0), 1.0, 1.0), 0.0);
  EXPECT_EQ(travel_share(on, north, Vec2::Zero(), 1.0, 1.0), 0.0);
  EXPECT_EQ(travel_share(on, north, along(0.0, 1.0), 0.0, 1.0), 0.0);
}

Motion facing_off(Motion m, double degrees) {
  const Quat yaw = axis_rotation(Axis::kY, degrees * kDeg);
  for (int f = 0; f < m.frame_count; ++f) m.rotations(f)[0] = (yaw * m.rotations(f)[0]).normalized();
  return m;
}

// Frame i of a clip judged by brute force: the frames within half a second of it in its clip,
// their mean facing and the root's travel from the first to the last.
struct Window {
  Vec2 mean_facing = Vec2::Zero();
  Vec2 travel = Vec2::Zero();
  int frames = 0;
};
Window window_at(const Motion& m, int i) {
  Window w;
  int first = -1, last = -1;
  for (int j = 0; j < m.frame_count; ++j) {
    if (std::abs(j - i) > 15) continue;
    w.mean_facing += facing_on_floor(m.rotations(j)[0], kForward);
    if (first < 0) first = j;
    last = j;
    ++w.frames;
  }
  w.travel = test::root_of(m, last) - test::root_of(m, first);
  return w;
}

TEST(TravelHeading, EachFrameTurnedOntoItsClipsTravelWhereItWalks) {
  const Motion walk = facing_off(test::motion_along(test::straight_walk(6.0, 1.3, 0.03)), 8.0);
  const Motion sidestep = facing_off(walk, 90.0 - 8.0);
  const Motion standing = test::motion_along(std::vector<Vec2>(120, Vec2(0.5, -0.2)));
  // The walk after the sidestep: a window crossing into the clip before would judge its travel.
  const MotionDatabase db = test::floor_motion_database({sidestep, walk, standing});
  const MotionGraph graph;
  auto assembler = MotionAssembler::create(db, graph, 0);
  ASSERT_TRUE(assembler.ok()) << assembler.error().to_string();
  HeadingEditSettings held;
  held.hold_travel = true;
  const std::vector<float> turns = travel_turns(db, *assembler, kForward, held);
  ASSERT_EQ(turns.size(), static_cast<size_t>(db.frame_count()));

  // Across the body or on the spot: the facing stands.
  for (int f = 0; f < db.clips[0].frame_count; ++f) EXPECT_EQ(turns[static_cast<size_t>(f)], 0.0f) << f;
  for (int f = 0; f < db.clips[2].frame_count; ++f) EXPECT_EQ(turns[db.clips[2].first_frame + f], 0.0f) << f;

  // The walk: where the window is whole, its mean facing turned onto its travel (8 degrees,
  // less the stride's sway); none within three eighths of a window of its ends; in between a
  // share of it.
  const int n = db.clips[1].frame_count;
  int partial = 0;
  for (int i = 0; i < n; ++i) {
    const double t = turns[static_cast<size_t>(db.clips[1].first_frame + i)];
    const Window w = window_at(walk, i);
    const double full = yaw_between(w.mean_facing, w.travel);
    if (i <= 7 || i >= n - 8) {
      EXPECT_EQ(t, 0.0) << i;
    } else if (i >= 15 && i < n - 15) {
      EXPECT_NEAR(t, full, 1e-6) << i;  // float
      // (motion_along's facings sway within a second of the clip's ends)
      if (i >= 30 && i < n - 30) {
        EXPECT_NEAR(std::abs(t), 8.0 * kDeg, 0.5 * kDeg) << i;
      }
      const Vec2 judged = turn(FloorTransform{t, 0.0, 0.0}, w.mean_facing.normalized());
      EXPECT_NEAR(judged.dot(w.travel.normalized()), 1.0, 1e-9) << i;
    } else {
      EXPECT_LE(std::abs(t), std::abs(full) + 1e-6) << i;
      EXPECT_GE(t * full, 0.0) << i;  // the same way
      if (std::abs(t) > 1e-4 && std::abs(t) < std::abs(full) - 1e-4) ++partial;
    }
  }
  EXPECT_GE(partial, 8);  // 7 frames at either end, each a share between 0 and 1

  // Not held: no turn anywhere.
  for (float t : travel_turns(db, *assembler, kForward, HeadingEditSettings{})) ASSERT_EQ(t, 0.0f);
}

}  // namespace
}  // namespace mg
