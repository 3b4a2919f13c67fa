// How fast flights fall: exact on ballistic flights made here, at the capture's clock and at a
// wrong one; runs without contact that are not flights are left out; real captures fall at about
// g, and the bundled BVH whose Frame Time is 4x too long at g / 16.
#include "motiongraph/motion/flight_fall.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "motiongraph/motion/clip_doubts.h"
#include "motiongraph/motion/foot_contacts.h"
#include "test_data.h"

namespace mg {
namespace {

constexpr ContactMask kPlanted = contact_bit(FootSide::kLeft, FootPart::kAnkle);

// A figure of two joints (one at the height h, one 1 m above it) standing, then for each entry
// of `airs` in the air for that many seconds along a ballistic arc (falling at g), then standing;
// sampled at `fps`.
struct Jumps {
  std::vector<Vec3> positions;
  std::vector<ContactMask> contacts;
};

Jumps jumps(double fps, const std::vector<double>& airs, double g = kGravityMps2) {
  Jumps out;
  auto add = [&](double h, bool planted) {
    out.positions.emplace_back(0.0, h, 0.0);
    out.positions.emplace_back(0.0, h + 1.0, 0.0);
    out.contacts.push_back(planted ? kPlanted : 0);
  };
  for (int f = 0; f < 10; ++f) add(0.0, true);
  for (const double air : airs) {
    const int n = static_cast<int>(std::round(air * fps));
    const double v = g * air / 2.0;  // leaving the floor at t = 0, back at t = air
    for (int f = 1; f < n; ++f) {
      const double t = f / fps;
      add(v * t - 0.5 * g * t * t, false);
    }
    for (int f = 0; f < 10; ++f) add(0.0, true);
  }
  return out;
}

TEST(FlightFall, BallisticFlightsFallAtGravityAndAWrongClockShowsAsASlowdown) {
  const Jumps j = jumps(30.0, {0.5, 0.4});
  const FlightFall right = measure_flight_fall(j.positions, 2, 30.0, j.contacts);
  EXPECT_EQ(right.flights, 2);
  EXPECT_NEAR(right.fall_mps2, kGravityMps2, 1e-6);
  EXPECT_NEAR(right.slowdown(), 1.0, 1e-6);
  // Its rise: the highest frame in the air above the first (1/30 s after leaving).
  double highest = 0.0;
  for (int f = 1; f < 15; ++f) highest = std::max(highest, kGravityMps2 * 0.25 * f / 30.0 - 0.5 * kGravityMps2 * f * f / 900.0);
  EXPECT_NEAR(right.highest_rise_m, highest - (kGravityMps2 * 0.25 / 30.0 - 0.5 * kGravityMps2 / 900.0), 1e-9);
  // The same frames said to be 4x longer (a 120 fps capture labelled 30 fps): they fall at g / 16.
  const FlightFall slow = measure_flight_fall(j.positions, 2, 7.5, j.contacts);
  EXPECT_NEAR(slow.fall_mps2, kGravityMps2 / 16.0, 1e-6);
  EXPECT_NEAR(slow.slowdown(), 4.0, 1e-6);
  EXPECT_NEAR(measure_flight_fall(j.positions, 2, 60.0, j.contacts).slowdown(), 0.5, 1e-6);
  // Unknown feet: nothing measured.
  EXPECT_FALSE(measure_flight_fall(j.positions, 2, 30.0, {}).measured());
  EXPECT_EQ(FlightFall{}.slowdown(), 0.0);
}

TEST(FlightFall, OneSmallFlightIsNotEnoughButTwoAreAndOneJumpIs) {
  // 0.2 s in the air rises 4.9 cm: one such flight could be a foot on a step; two agree.
  EXPECT_EQ(measure_flight_fall(jumps(30.0, {0.2}).positions, 2, 30.0, jumps(30.0, {0.2}).contacts).flights, 1);
  EXPECT_FALSE(measure_flight_fall(jumps(30.0, {0.2}).positions, 2, 30.0, jumps(30.0, {0.2}).contacts).measured());
  const Jumps two = jumps(30.0, {0.2, 0.22});
  EXPECT_TRUE(measure_flight_fall(two.positions, 2, 30.0, two.contacts).measured());
  const Jumps jump = jumps(30.0, {0.4});  // rises 14 cm above its first frame in the air
  EXPECT_TRUE(measure_flight_fall(jump.positions, 2, 30.0, jump.contacts).measured());
  // Too few frames in the air to fit: not a flight.
  const Jumps brief = jumps(30.0, {0.15, 0.15});
  EXPECT_EQ(measure_flight_fall(brief.positions, 2, 30.0, brief.contacts).flights, 0);
}

TEST(FlightFall, RunsWithoutContactThatAreNoFlightsAreLeftOut) {
  // Up onto a step 0.3 m high, standing there 2 s (no foot on the floor: no contact), down again:
  // no parabola. A body rising only (its apex at the run's end) is no flight either.
  Jumps step;
  auto add = [&](double h, bool planted) {
    step.positions.emplace_back(0.0, h, 0.0);
    step.positions.emplace_back(0.0, h + 1.0, 0.0);
    step.contacts.push_back(planted ? kPlanted : 0);
  };
  for (int round = 0; round < 2; ++round) {
    for (int f = 0; f < 10; ++f) add(0.0, true);
    for (int f = 0; f < 15; ++f) add(0.3 * f / 14.0, false);
    for (int f = 0; f < 60; ++f) add(0.3, false);
    for (int f = 0; f < 15; ++f) add(0.3 * (14 - f) / 14.0, false);
  }
  for (int f = 0; f < 10; ++f) add(0.0, true);
  EXPECT_EQ(measure_flight_fall(step.positions, 2, 30.0, step.contacts).flights, 0);
  Jumps rising;
  for (int f = 0; f < 10; ++f) {
    rising.positions.emplace_back(0.0, 0.0, 0.0);
    rising.positions.emplace_back(0.0, 1.0, 0.0);
    rising.contacts.push_back(kPlanted);
  }
  for (int f = 0; f < 8; ++f) {  // the apex, 0.31 s after leaving at 3 m/s, comes after the clip's end
    const double t = f / 30.0;
    rising.positions.emplace_back(0.0, 3.0 * t - 0.5 * kGravityMps2 * t * t, 0.0);
    rising.positions.emplace_back(0.0, 1.0 + 3.0 * t - 0.5 * kGravityMps2 * t * t, 0.0);
    rising.contacts.push_back(0);
  }
  EXPECT_EQ(measure_flight_fall(rising.positions, 2, 30.0, rising.contacts).flights, 0);
  // Falling only, the apex before the run's start (CMU 05_20 and 14_22 have such runs, and fit
  // them at 0.3 g): no flight either.
  Jumps falling;
  for (int f = 0; f < 10; ++f) {
    const double t = (f + 10) / 30.0;  // from 0.33 s after leaving at 3 m/s, past the apex
    falling.positions.emplace_back(0.0, 1.0 + 3.0 * t - 0.5 * kGravityMps2 * t * t, 0.0);
    falling.positions.emplace_back(0.0, 2.0 + 3.0 * t - 0.5 * kGravityMps2 * t * t, 0.0);
    falling.contacts.push_back(0);
  }
  for (int f = 0; f < 10; ++f) {
    falling.positions.emplace_back(0.0, 0.0, 0.0);
    falling.positions.emplace_back(0.0, 1.0, 0.0);
    falling.contacts.push_back(kPlanted);
  }
  EXPECT_EQ(measure_flight_fall(falling.positions, 2, 30.0, falling.contacts).flights, 0);
  // Arcs of a centimetre (a body swaying over feet on a step) rise too little to be judged,
  // however well they fit.
  const Jumps sways = jumps(30.0, {0.3, 0.3, 0.3}, 1.0);
  EXPECT_EQ(measure_flight_fall(sways.positions, 2, 30.0, sways.contacts).flights, 0);
  EXPECT_EQ(measure_flight_fall(jumps(30.0, {0.3, 0.3, 0.3}, 4.0).positions, 2, 30.0, sways.contacts).flights, 3);
}

TEST(FlightFall, TheFallIsTheMedianOfTheFlights) {
  // Three flights of 0.5 s falling at g, 0.8 g and 1.3 g: the clip falls at g.
  Jumps j = jumps(30.0, {0.5}, kGravityMps2);
  for (const double g : {0.8 * kGravityMps2, 1.3 * kGravityMps2}) {
    const Jumps more = jumps(30.0, {0.5}, g);
    j.positions.insert(j.positions.end(), more.positions.begin(), more.positions.end());
    j.contacts.insert(j.contacts.end(), more.contacts.begin(), more.contacts.end());
  }
  const FlightFall f = measure_flight_fall(j.positions, 2, 30.0, j.contacts);
  EXPECT_EQ(f.flights, 3);
  EXPECT_NEAR(f.fall_mps2, kGravityMps2, 1e-6);
}

// The clip's own joints and contacts, at the rate it is read at: what info judges its clock on.
FlightFall fall_of(const Clip& clip) { return clip_doubts(clip.skeleton, clip.motion).flight_fall; }

TEST(FlightFall, CapturesFallAtGravityAndTheBvhReadFourTimesSlowAtASixteenth) {
  for (const char* file : {"cmu/16/16_01.amc", "cmu/16/16_37.amc", "cmu/16/16_43.amc"}) {
    const FlightFall f = fall_of(test::load_data_clip(file));
    ASSERT_TRUE(f.measured()) << file;
    EXPECT_GT(f.slowdown(), 1.0 / 1.3) << file;
    EXPECT_LT(f.slowdown(), 1.3) << file;
  }
  // The same jump as amc2bvh wrote it: 120 fps frames labelled 30 fps.
  const FlightFall bvh = fall_of(test::load_data_clip("bvh/16_01.bvh"));
  ASSERT_TRUE(bvh.measured());
  EXPECT_NEAR(bvh.slowdown(), 4.0, 0.4);
  const FlightFall read_right = fall_of(test::load_data_clip("bvh/16_01.bvh", std::nullopt, 120.0));
  ASSERT_TRUE(read_right.measured());
  EXPECT_NEAR(read_right.slowdown(), 1.0, 0.2);
}

}  // namespace
}  // namespace mg
