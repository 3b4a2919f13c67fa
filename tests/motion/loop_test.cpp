#include "motiongraph/motion/loop.h"

#include <gtest/gtest.h>

#include "motion/cycle_loop.h"
#include "motion/static_root_bvh.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "test_data.h"

namespace mg {
namespace {

Clip at_30fps(const char* file) {
  Clip clip = test::load_data_clip(file);
  clip.motion = *resample(clip.motion, 30.0);
  return clip;
}

// The rigid floor motion (turn about +y, then a shift on the floor) that takes the points `a` to
// `b` in the least squares sense, and the largest distance it leaves.
double rigid_floor_residual(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  Vec3 ca = Vec3::Zero(), cb = Vec3::Zero();
  for (size_t i = 0; i < a.size(); ++i) {
    ca += a[i];
    cb += b[i];
  }
  ca /= static_cast<double>(a.size());
  cb /= static_cast<double>(b.size());
  double sin_sum = 0.0, cos_sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const Vec3 p = a[i] - ca, q = b[i] - cb;
    cos_sum += p.x() * q.x() + p.z() * q.z();
    sin_sum += p.z() * q.x() - p.x() * q.z();
  }
  const Quat turn(Eigen::AngleAxisd(std::atan2(sin_sum, cos_sum), Vec3::UnitY()));
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const Vec3 moved = turn * (a[i] - ca) + Vec3(cb.x(), ca.y(), cb.z());
    worst = std::max(worst, (moved - b[i]).norm());
  }
  return worst;
}

std::vector<Vec3> frame_positions(const std::vector<Vec3>& all, int joints, int frame) {
  return {all.begin() + static_cast<long>(frame) * joints, all.begin() + static_cast<long>(frame + 1) * joints};
}

TEST(Loop, CyclesLoopWhetherTheLastFrameRepeatsTheFirstOrNot) {
  for (const auto& [file, first, period] : {std::tuple{"cmu/16/16_15.amc", 32, 34},
                                            std::tuple{"cmu/16/16_16.amc", 15, 36},
                                            std::tuple{"cmu/16/16_35.amc", 0, 24}}) {
    const Clip clip = at_30fps(file);
    const LoopChoice repeated = find_loop(clip.skeleton, test::loop_of(clip, first, period, true).motion);
    EXPECT_TRUE(repeated.loops) << file;
    EXPECT_TRUE(repeated.last_repeats_first) << file;
    EXPECT_EQ(repeated.period, period) << file;
    EXPECT_LT(repeated.seam_ratio, 0.01) << file;
    const LoopChoice following = find_loop(clip.skeleton, test::loop_of(clip, first, period, false).motion);
    EXPECT_TRUE(following.loops) << file << " seam " << following.seam_ratio;
    EXPECT_FALSE(following.last_repeats_first) << file;
    EXPECT_EQ(following.period, period) << file;
    // Frames cut from the capture off its period do not loop (one cut at the period may: a
    // capture's cycle is nearly one).
    const LoopChoice cut = find_loop(clip.skeleton, clip.motion.slice(first, period - 5));
    EXPECT_FALSE(cut.loops) << file << " seam " << cut.seam_ratio;
    EXPECT_GT(cut.seam_ratio, kFollowingSeamRatio) << file;
  }
}

TEST(Loop, CapturesDoNotLoop) {
  // Every bundled capture, whole: its end is not its start (the 8-subject library's clips too,
  // measured: docs/performance.md).
  for (const char* file : {"cmu/16/16_01.amc", "cmu/16/16_05.amc", "cmu/16/16_11.amc", "cmu/16/16_13.amc",
                           "cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_17.amc", "cmu/16/16_19.amc",
                           "cmu/16/16_33.amc", "cmu/16/16_35.amc", "cmu/16/16_37.amc", "cmu/16/16_39.amc",
                           "cmu/16/16_41.amc", "cmu/16/16_43.amc", "cmu/16/16_57.amc", "bvh/07_01.bvh",
                           "bvh/07_12.bvh", "bvh/111_36.bvh", "bvh/131_01.bvh"}) {
    const Clip clip = at_30fps(file);
    const LoopChoice loop = find_loop(clip.skeleton, clip.motion);
    EXPECT_FALSE(loop.loops) << file;
    EXPECT_GT(loop.seam_ratio, 1.0) << file;
  }
  // Too short, or standing still, does not loop either.
  const Clip walk = at_30fps("cmu/16/16_15.amc");
  EXPECT_FALSE(find_loop(walk.skeleton, test::loop_of(walk, 32, 6, true).motion).loops);
  Motion still = walk.motion.slice(0, 40);
  for (int f = 1; f < still.frame_count; ++f) {
    std::copy(still.rotations(0).begin(), still.rotations(0).end(), still.rotations(f).begin());
    std::copy(still.translations(0).begin(), still.translations(0).end(), still.translations(f).begin());
  }
  EXPECT_FALSE(find_loop(walk.skeleton, still).loops);
}

TEST(Loop, UnrolledFramesAreTheCycleAgainOneCycleOn) {
  // Property: each frame added is the frame a period before it, every joint moved by one and
  // the same floor motion; the clip's own frames are unchanged. With a static root above the
  // hips (its channels on the joint below it) as well.
  const Clip walk = at_30fps("cmu/16/16_15.amc");
  const Clip static_root = [&] {
    Clip c = test::import_bvh(test::static_root_bvh(walk, Vec3(1.0, 0.0, -2.0),
                                                    Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()))));
    c.motion = *resample(c.motion, 30.0);
    return c;
  }();
  ASSERT_FALSE(static_root.skeleton.static_ancestors().empty());
  for (const Clip* clip : {&walk, &static_root}) {
    for (const bool repeat : {true, false}) {
      const Clip loop = test::loop_of(*clip, 32, 34, repeat);
      const LoopChoice choice = find_loop(loop.skeleton, loop.motion);
      ASSERT_TRUE(choice.loops);
      const Motion unrolled = unrolled_loop(loop.skeleton, loop.motion, choice, 12);
      ASSERT_EQ(unrolled.frame_count, loop.motion.frame_count + 12);
      const int joints = loop.skeleton.joint_count();
      const std::vector<Vec3> before = world_positions(loop.skeleton, loop.motion);
      const std::vector<Vec3> after = world_positions(loop.skeleton, unrolled);
      ASSERT_TRUE(std::equal(before.begin(), before.end(), after.begin()));
      std::vector<Vec3> earlier, later;
      for (int n = loop.motion.frame_count; n < unrolled.frame_count; ++n) {
        const std::vector<Vec3> a = frame_positions(after, joints, n - choice.period);
        const std::vector<Vec3> b = frame_positions(after, joints, n);
        EXPECT_LT(rigid_floor_residual(a, b), 1e-9) << n;
        earlier.insert(earlier.end(), a.begin(), a.end());
        later.insert(later.end(), b.begin(), b.end());
      }
      EXPECT_LT(rigid_floor_residual(earlier, later), 1e-9) << "one floor motion for every frame added";
      // Across the seam the root moves on as it does from frame to frame, no jump back.
      const int seam = loop.motion.frame_count;
      const double step = (after[static_cast<size_t>(seam * joints)] - after[static_cast<size_t>((seam - 1) * joints)])
                              .norm();
      const double typical = (after[static_cast<size_t>(joints)] - after[0]).norm();
      EXPECT_NEAR(step, typical, 0.5 * typical + 0.005) << "repeat " << repeat;
    }
  }
}

TEST(Loop, CyclesAtTheirCaptureRateLoopToo) {
  // The same cycles at 120 fps: poses are compared about 1/30 s apart at any rate.
  for (const auto& [file, first, period] : {std::tuple{"cmu/16/16_15.amc", 128, 136},
                                            std::tuple{"cmu/16/16_35.amc", 0, 96}}) {
    const Clip clip = test::load_data_clip(file);
    ASSERT_EQ(clip.motion.fps, 120.0);
    for (const bool repeat : {true, false}) {
      const LoopChoice loop = find_loop(clip.skeleton, test::loop_of(clip, first, period, repeat).motion);
      EXPECT_TRUE(loop.loops) << file << " repeat " << repeat << " seam " << loop.seam_ratio;
      EXPECT_EQ(loop.period, period) << file;
    }
    EXPECT_FALSE(find_loop(clip.skeleton, clip.motion).loops) << file;
  }
}

TEST(Loop, ATurningCycleGoesOnRoundItsCircle) {
  // A walk cycle turned onto a circle, 40 degrees a cycle: every frame the straight cycle's pose
  // (its travel taken out) turned by 40 t / P degrees about the circle's centre, so one cycle
  // on is exactly the cycle turned 40 degrees. The frames added are its continuation: exactly
  // when the last frame repeats the first, within a few centimetres when it is extrapolated.
  const Clip walk = at_30fps("cmu/16/16_15.amc");
  const int period = 34;
  const Clip straight_loop = test::loop_of(walk, 32, period, true);
  const LoopChoice straight = find_loop(straight_loop.skeleton, straight_loop.motion);
  ASSERT_TRUE(straight.loops);
  const Motion two_cycles = unrolled_loop(straight_loop.skeleton, straight_loop.motion, straight, period);
  const int slot = walk.skeleton.translation_slot(0);
  const Vec3 travel = two_cycles.translations(period)[static_cast<size_t>(slot)] -
                      two_cycles.translations(0)[static_cast<size_t>(slot)];
  const double turn = 40.0 * 3.141592653589793 / 180.0;
  const Vec3 along(travel.x(), 0.0, travel.z());
  const double radius = along.norm() / turn;
  const Vec3 start = two_cycles.translations(0)[static_cast<size_t>(slot)];
  const Vec3 centre = Vec3(start.x(), 0.0, start.z()) - radius * Vec3(-along.z(), 0.0, along.x()) / along.norm();
  Motion circle = two_cycles;
  for (int t = 0; t < circle.frame_count; ++t) {
    const Quat yaw(Eigen::AngleAxisd(turn * t / period, Vec3::UnitY()));
    Vec3& root = circle.translations(t)[static_cast<size_t>(slot)];
    root -= along * (static_cast<double>(t) / period);
    root = yaw * (root - centre) + centre;
    circle.rotations(t)[0] = yaw * circle.rotations(t)[0];
  }
  const int joints = walk.skeleton.joint_count();
  const std::vector<Vec3> truth = world_positions(walk.skeleton, circle);
  for (const bool repeat : {true, false}) {
    const Motion cycle = circle.slice(0, period + (repeat ? 1 : 0));
    const LoopChoice loop = find_loop(walk.skeleton, cycle);
    ASSERT_TRUE(loop.loops) << "repeat " << repeat << " seam " << loop.seam_ratio;
    ASSERT_EQ(loop.period, period);
    const Motion on = unrolled_loop(walk.skeleton, cycle, loop, 11);
    const std::vector<Vec3> played = world_positions(walk.skeleton, on);
    double worst = 0.0;
    for (int n = cycle.frame_count; n < on.frame_count; ++n) {
      for (int j = 0; j < joints; ++j) {
        const auto i = static_cast<size_t>(n * joints + j);
        worst = std::max(worst, (played[i] - truth[i]).norm());
      }
    }
    EXPECT_LT(worst, repeat ? 1e-9 : 0.05) << "repeat " << repeat;
  }
}

}  // namespace
}  // namespace mg
