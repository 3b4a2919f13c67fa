// The distance cache: its key follows the motion and the settings; the file cache gives back
// exactly what it stored, has no entry for another key, and reports a damaged entry.
#include "motiongraph/pipeline/distance_cache.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "motiongraph/graph/graph_file.h"
#include "motiongraph/io/file.h"
#include "test_data.h"

namespace mg {
namespace {

CandidateSearch sample_candidates() {
  CandidateSearch c;
  c.window = 10;
  c.continuation_radius = 10;
  c.minima = {{3, 50, 0.5f, 0.1f, 1.0f, -2.0f}, {7, 60, 0.25f, -0.3f, 0.0f, 4.0f}};
  c.histogram.add(0.5f);
  c.picture = {1.0f, 2.0f, 3.0f, 4.0f};
  c.picture_side = 2;
  c.picture_block = 40;
  return c;
}

TEST(DistanceCacheKey, FollowsMotionAndSettings) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  const std::uint64_t key = distance_cache_key(db, R"({"window":10})");
  EXPECT_EQ(key, distance_cache_key(test::small_database({"cmu/16/16_15.amc"}), R"({"window":10})"));
  EXPECT_NE(key, distance_cache_key(db, R"({"window":11})"));
  MotionDatabase moved = db;
  moved.clips[0].motion.local_translations_m[5].x() += 1e-6;
  EXPECT_NE(key, distance_cache_key(moved, R"({"window":10})"));
  EXPECT_NE(key, distance_cache_key(test::small_database({"cmu/16/16_15.amc"}, false, 0.0, Vec3::Zero(), 60.0),
                                    R"({"window":10})"));
}

TEST(FileDistanceCache, StoresFindsAndReportsDamage) {
  const std::string folder = testing::TempDir() + "motiongraph-distance-cache-test/sub";
  std::filesystem::remove_all(folder);
  FileDistanceCache cache(folder);
  auto none = cache.find(42);
  ASSERT_TRUE(none);
  EXPECT_FALSE(*none);

  const CandidateSearch stored = sample_candidates();
  ASSERT_TRUE(cache.store(42, stored));  // creates the folder
  EXPECT_EQ(cache.location(42), (std::filesystem::path(folder) / "000000000000002a.mgcache").string());
  auto found = cache.find(42);
  ASSERT_TRUE(found) << found.error().to_string();
  ASSERT_TRUE(*found);
  EXPECT_EQ(serialize_distance_cache(42, **found), serialize_distance_cache(42, stored));
  auto other = cache.find(43);
  ASSERT_TRUE(other);
  EXPECT_FALSE(*other);

  // A damaged entry is an error (the build computes again), not a miss.
  ASSERT_TRUE(write_file_atomic(cache.location(42), "MGCACHE but not really"));
  EXPECT_FALSE(cache.find(42));
  std::filesystem::remove_all(testing::TempDir() + "motiongraph-distance-cache-test");
}

}  // namespace
}  // namespace mg
