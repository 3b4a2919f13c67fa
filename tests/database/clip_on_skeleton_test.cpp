// A clip played on another subject's skeleton: the same capture read in a unit 1.7 times larger
// (a taller subject), played on the smaller skeleton, is the smaller reading itself; and the other
// way round.
#include "motiongraph/database/clip_on_skeleton.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

double max_apart(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

TEST(ClipOnSkeleton, ATallerSubjectsClipOnTheSmallerSkeletonIsTheSmallerOnesClip) {
  const test::ScaledPair pair = test::scaled_pair(1.7, 20, 10);
  EXPECT_NEAR(leg_scale(pair.db.skeletons[0], pair.db.skeletons[1]), 1.0 / 1.7, 1e-12);
  auto large_on_small = clip_on_skeleton(pair.db, 1, 0);
  ASSERT_TRUE(large_on_small) << large_on_small.error().message;
  EXPECT_LT(max_apart(world_positions(pair.db.skeletons[0], *large_on_small),
                      world_positions(pair.small.skeleton, pair.small.motion)),
            1e-9);
  auto small_on_large = clip_on_skeleton(pair.db, 0, 1);
  ASSERT_TRUE(small_on_large);
  EXPECT_LT(max_apart(world_positions(pair.db.skeletons[1], *small_on_large),
                      world_positions(pair.large.skeleton, pair.large.motion)),
            1e-9);
  // On its own skeleton, the clip as it is.
  auto own = clip_on_skeleton(pair.db, 1, 1);
  ASSERT_TRUE(own);
  const Motion& as_read = pair.db.clips[1].motion;
  EXPECT_TRUE(std::equal(own->local_rotations.begin(), own->local_rotations.end(), as_read.local_rotations.begin(),
                         as_read.local_rotations.end(),
                         [](const Quat& a, const Quat& b) { return a.coeffs() == b.coeffs(); }));
  EXPECT_TRUE(own->local_translations_m == as_read.local_translations_m);
}

TEST(ClipOnSkeleton, NoSuchSkeletonOrOtherJointsIsAnError) {
  test::ScaledPair pair = test::scaled_pair(1.7, 20, 10);
  EXPECT_FALSE(clip_on_skeleton(pair.db, 0, 2));
  EXPECT_FALSE(clip_on_skeleton(pair.db, 0, -1));
  std::vector<JointDef> fewer(pair.db.skeletons[1].joints().begin(), pair.db.skeletons[1].joints().end() - 1);
  pair.db.skeletons[1] = Skeleton(fewer);
  const auto differ = clip_on_skeleton(pair.db, 0, 1);
  ASSERT_FALSE(differ);
  EXPECT_NE(differ.error().message.find("'small' and 'large' differ in joints"), std::string::npos)
      << differ.error().message;
}

}  // namespace
}  // namespace mg
