// The self-consistency measure from its definition on tracks built in code, its invariance
// to turning and moving a clip on the floor, and a transition that merely continues its clip
// measuring exactly what the clip's own frames do.
#include "motiongraph/evaluation/self_consistency.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "motiongraph/skeleton/rotation.h"
#include "test_data.h"

namespace mg {
namespace {

// A root moving along +x at `speed` m/s for n frames at 30 fps, its rotation turning the
// forward axis +z by yaw_rad about +y.
struct Track {
  std::vector<Quat> rotations;
  std::vector<Vec2> roots;
};

Track straight_track(int n, double speed, double yaw_rad) {
  Track t;
  for (int f = 0; f < n; ++f) {
    t.rotations.push_back(axis_rotation(Axis::kY, yaw_rad));
    t.roots.emplace_back(speed * f / 30.0, 0.0);
  }
  return t;
}

TEST(SelfConsistency, AnglesFromTheirDefinition) {
  const Vec3 forward = Vec3::UnitZ();
  const double quarter = std::numbers::pi / 2;
  // +z turned by +90 degrees about +y is +x: facing along the travel.
  Track along = straight_track(40, 1.5, quarter);
  ConsistencySum s = consistency_over(along.rotations, along.roots, forward, 30.0, 0, 39);
  EXPECT_EQ(s.frames, 40 - kTravelLookaheadFrames);  // the last frames see no lookahead
  EXPECT_NEAR(s.rms_deg(), 0.0, 1e-6);
  // Facing +z while moving along +x: 90 degrees; facing -x: 180.
  Track sideways = straight_track(40, 1.5, 0.0);
  EXPECT_NEAR(consistency_over(sideways.rotations, sideways.roots, forward, 30.0, 0, 39).rms_deg(), 90.0, 1e-6);
  Track backwards = straight_track(40, 1.5, -quarter);
  EXPECT_NEAR(consistency_over(backwards.rotations, backwards.roots, forward, 30.0, 0, 39).rms_deg(), 180.0, 1e-6);
  // Half the frames at 0 degrees and half at 90: RMS = 90 / sqrt(2).
  Track mixed = straight_track(20, 1.5, quarter);
  for (int f = 0; f < 10; ++f) mixed.rotations[f] = Quat::Identity();
  EXPECT_NEAR(consistency_over(mixed.rotations, mixed.roots, forward, 30.0, 0, 9).rms_deg(), 90.0, 1e-6);
  EXPECT_NEAR(consistency_over(mixed.rotations, mixed.roots, forward, 30.0, 0, 19).rms_deg(), 90.0, 1e-6);
  ConsistencySum half = consistency_over(mixed.rotations, mixed.roots, forward, 30.0, 0, 9);
  half.add(consistency_over(along.rotations, along.roots, forward, 30.0, 0, 9));
  EXPECT_NEAR(half.rms_deg(), 90.0 / std::sqrt(2.0), 1e-6);
  // Standing still (slower than kMovingSpeedMps) or a vertical forward axis: nothing measured.
  Track still = straight_track(40, 0.5 * kMovingSpeedMps, quarter);
  EXPECT_EQ(consistency_over(still.rotations, still.roots, forward, 30.0, 0, 39).frames, 0);
  EXPECT_TRUE(std::isnan(consistency_over(along.rotations, along.roots, Vec3::UnitY(), 30.0, 0, 39).rms_deg()));
}

TEST(SelfConsistency, UnchangedByTurningAndMovingAClipOnTheFloor) {
  const MotionDatabase one = test::small_database({"cmu/16/16_15.amc"});
  const MotionDatabase two = test::small_database({"cmu/16/16_15.amc"}, true, 1.1, Vec3(3.0, 0.0, -2.0));
  const std::vector<Vec3> axes = learn_travel_axes(one);
  const ConsistencySum a = database_consistency(one, axes);
  const ConsistencySum b = database_consistency(two, axes);
  ASSERT_GT(a.frames, 50);
  EXPECT_EQ(b.frames, 2 * a.frames);
  EXPECT_NEAR(b.rms_deg(), a.rms_deg(), 1e-6);
  // A straight walk faces where it goes: the forward axis is learnt from such frames.
  EXPECT_LT(a.rms_deg(), 20.0);
}

TEST(SelfConsistency, ATransitionContinuingItsClipMeasuresTheClipsFrames) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  const int k = 10, a = 40;
  // From a to a + k - 1 in the same clip with no floor change: the blend mixes each frame with
  // itself, so the motion around it is the clip's own.
  const std::vector<Transition> transitions = {Transition{a, a + k - 1, 0.0f, 0.0f, 0.0f, 0.0f}};
  auto graph = build_motion_graph(db, transitions, k);
  ASSERT_TRUE(graph) << graph.error().to_string();
  auto assembler = MotionAssembler::create(db, *graph, 0);
  ASSERT_TRUE(assembler) << assembler.error().to_string();
  const Vec3 axis = learn_travel_axes(db)[0];
  const ConsistencySum around = transition_consistency(db, *graph, *assembler, axis);

  const Motion& clip = db.clips[0].motion;
  std::vector<Quat> rotations;
  std::vector<Vec2> roots;
  for (int f = 0; f < clip.frame_count; ++f) {
    rotations.push_back(clip.rotations(f)[0]);
    roots.emplace_back(clip.translations(f)[0].x(), clip.translations(f)[0].z());
  }
  const ConsistencySum own = consistency_over(rotations, roots, axis, db.fps, a - kTravelLookaheadFrames, a + k - 2);
  ASSERT_EQ(around.frames, own.frames);
  EXPECT_EQ(around.frames, kTravelLookaheadFrames + k - 1);
  EXPECT_NEAR(around.rms_deg(), own.rms_deg(), 1e-3);
}

}  // namespace
}  // namespace mg
