// The distance stage in parts: parts of any share of the tiles merge into exactly the search of
// all tiles (what rank 0 of an MPI job does with its processes' parts; the MPI runs themselves
// are tests/cli/cli_mpi_test.sh), and a checkpointed search started again, with some chunks
// gone as after a kill, skips the chunks it has and gives the same search.
#include "motiongraph/parallel/shared_candidates.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "motiongraph/graph/graph_file.h"
#include "motiongraph/parallel/tile_checkpoint.h"
#include "motiongraph/parallel/tile_share.h"
#include "test_data.h"

namespace mg {
namespace {

namespace fs = std::filesystem;

struct Fixture {
  MotionDatabase db;
  FrameFeatures features;
  DistanceSettings distance;
};

Fixture fixture() {
  Fixture x;
  x.db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_17.amc"});
  x.distance.tile_frames = 32;
  x.distance.threads = 2;
  auto layout = make_cloud_layout(x.db.skeletons[0], {});
  x.features = *make_frame_features(x.db, *layout, x.distance);
  return x;
}

// The search's bytes as the cache stores them, but for the time it took.
std::string bytes_of(CandidateSearch search) {
  search.tiles.seconds = 0.0;
  return serialize_distance_cache(1, search);
}

TEST(MergeCandidates, PartsOfAnyShareGiveTheWholeSearch) {
  const Fixture x = fixture();
  CandidateSettings settings;
  settings.picture_side = 64;  // blocks of several frames: pixels shared between tiles
  auto whole = find_candidates(x.features, x.distance, settings);
  ASSERT_TRUE(whole) << whole.error().to_string();
  ASSERT_GT(whole->minima.size(), 100u);
  const TileItems items = tile_items(x.features, x.distance);
  ASSERT_GT(items.count(), 20);
  std::vector<long long> all(static_cast<size_t>(items.count()));
  for (long long i = 0; i < items.count(); ++i) all[static_cast<size_t>(i)] = i;
  for (int processes : {2, 3}) {
    auto merged = empty_candidate_search(x.features, settings);
    ASSERT_TRUE(merged);
    // Merged from the last process to the first: the order does not matter.
    for (int rank = processes - 1; rank >= 0; --rank) {
      const auto mine = items_of_process(items, all, processes, rank);
      auto part = find_candidates(x.features, x.distance, settings, {}, mine);
      ASSERT_TRUE(part);
      EXPECT_LT(part->tiles.pairs, whole->tiles.pairs);
      ASSERT_TRUE(merge_candidates(*merged, *part));
    }
    EXPECT_EQ(merged->tiles.tiles, whole->tiles.tiles);
    EXPECT_EQ(merged->tiles.pairs, static_cast<long long>(x.features.frames) * x.features.frames);
    EXPECT_EQ(bytes_of(*merged), bytes_of(*whole)) << processes << " processes";
  }
  // A part of another picture does not fit, and changes nothing.
  CandidateSettings other = settings;
  other.picture_side = 32;
  auto foreign = find_candidates(x.features, x.distance, other, {}, std::vector<long long>{0});
  ASSERT_TRUE(foreign);
  CandidateSearch copy = *whole;
  EXPECT_FALSE(merge_candidates(copy, *foreign));
  EXPECT_EQ(bytes_of(copy), bytes_of(*whole));
}

TEST(SharedCandidates, OneProcessIsThePlainSearch) {
  const Fixture x = fixture();
  OneProcess team;
  auto plain = find_candidates(x.features, x.distance, {});
  auto shared = find_candidates_shared(x.features, x.distance, {}, 7, team, {});
  ASSERT_TRUE(plain);
  ASSERT_TRUE(shared) << shared.error().to_string();
  EXPECT_EQ(shared->processes, 1);
  EXPECT_EQ(shared->restored_tiles, 0);
  ASSERT_EQ(shared->peak_memory_mb.size(), 1u);
  EXPECT_GT(shared->peak_memory_mb[0], 1.0);
  ASSERT_EQ(shared->share_seconds.size(), 1u);
  EXPECT_EQ(shared->share_seconds[0], shared->search.tiles.seconds);
  EXPECT_EQ(bytes_of(shared->search), bytes_of(*plain));
}

TEST(SharedCandidates, ResumesFromACheckpointWithTheSameSearch) {
  const Fixture x = fixture();
  const std::string folder = testing::TempDir() + "motiongraph-checkpoint-test";
  fs::remove_all(folder);
  OneProcess team;
  SharedSearchSettings shared;
  shared.checkpoint_folder = folder;
  shared.checkpoint_pairs = 5000;
  auto plain = find_candidates(x.features, x.distance, {});
  ASSERT_TRUE(plain);
  auto first = find_candidates_shared(x.features, x.distance, {}, 7, team, shared);
  ASSERT_TRUE(first) << first.error().to_string();
  EXPECT_EQ(bytes_of(first->search), bytes_of(*plain));
  std::vector<fs::path> chunks;
  for (const auto& entry : fs::directory_iterator(folder)) chunks.push_back(entry.path());
  ASSERT_GT(chunks.size(), 4u);

  // As after a kill: some chunks never written, a temporary file left behind.
  std::sort(chunks.begin(), chunks.end());
  for (size_t i = 0; i < chunks.size(); i += 2) fs::remove(chunks[i]);
  std::ofstream(fs::path(folder) / ".0000000000000007-0000000099.mgtiles.tmp-1234") << "torn";
  auto again = find_candidates_shared(x.features, x.distance, {}, 7, team, shared);
  ASSERT_TRUE(again) << again.error().to_string();
  EXPECT_GT(again->restored_tiles, 0);
  EXPECT_LT(again->restored_tiles, plain->tiles.tiles);
  EXPECT_EQ(bytes_of(again->search), bytes_of(*plain));

  // All chunks there now: nothing computed, the same search.
  auto complete = find_candidates_shared(x.features, x.distance, {}, 7, team, shared);
  ASSERT_TRUE(complete);
  EXPECT_EQ(complete->restored_tiles, plain->tiles.tiles);
  EXPECT_EQ(bytes_of(complete->search), bytes_of(*plain));

  // The folder of another build (key), or of other tiles, is refused.
  auto other_key = find_candidates_shared(x.features, x.distance, {}, 8, team, shared);
  ASSERT_FALSE(other_key);
  EXPECT_NE(other_key.error().message.find("a checkpoint of another build"), std::string::npos)
      << other_key.error().to_string();
  DistanceSettings other_tiles = x.distance;
  other_tiles.tile_frames = 128;
  auto retiled = find_candidates_shared(x.features, other_tiles, {}, 7, team, shared);
  ASSERT_FALSE(retiled);
  EXPECT_NE(retiled.error().message.find("run again with --tile 32"), std::string::npos)
      << retiled.error().to_string();

  // The matrix is held by one process without a checkpoint only.
  CandidateSettings with_matrix;
  with_matrix.keep_matrix = true;
  auto matrix = find_candidates_shared(x.features, x.distance, with_matrix, 7, team, shared);
  ASSERT_FALSE(matrix);
  EXPECT_NE(matrix.error().message.find("--export-matrix"), std::string::npos);
  fs::remove_all(folder);
}

// A subset of the items (the pruned stage's plan): the same search as find_candidates given
// those items, on one process and from a checkpoint; an empty subset runs nothing.
TEST(SharedCandidates, RunsOnlyTheItemsGiven) {
  const Fixture x = fixture();
  const TileItems items = tile_items(x.features, x.distance);
  std::vector<long long> some;
  for (long long i = 0; i < items.count(); i += 3) some.push_back(i);
  auto plain = find_candidates(x.features, x.distance, {}, {}, some);
  ASSERT_TRUE(plain);
  OneProcess team;
  auto alone = find_candidates_shared(x.features, x.distance, {}, 7, team, {}, &some);
  ASSERT_TRUE(alone) << alone.error().to_string();
  EXPECT_EQ(bytes_of(alone->search), bytes_of(*plain));
  const std::string folder = testing::TempDir() + "motiongraph-checkpoint-subset-test";
  fs::remove_all(folder);
  SharedSearchSettings shared;
  shared.checkpoint_folder = folder;
  shared.checkpoint_pairs = 5000;
  auto checkpointed = find_candidates_shared(x.features, x.distance, {}, 7, team, shared, &some);
  ASSERT_TRUE(checkpointed) << checkpointed.error().to_string();
  EXPECT_EQ(bytes_of(checkpointed->search), bytes_of(*plain));
  auto resumed = find_candidates_shared(x.features, x.distance, {}, 7, team, shared, &some);
  ASSERT_TRUE(resumed);
  EXPECT_EQ(resumed->restored_tiles, plain->tiles.tiles);
  EXPECT_EQ(bytes_of(resumed->search), bytes_of(*plain));
  fs::remove_all(folder);
  const std::vector<long long> none;
  auto nothing = find_candidates_shared(x.features, x.distance, {}, 7, team, {}, &none);
  ASSERT_TRUE(nothing);
  EXPECT_TRUE(nothing->search.minima.empty());
  EXPECT_EQ(nothing->search.histogram.total(), 0u);
  EXPECT_EQ(nothing->search.tiles.tiles, 0);
}

TEST(CandidatePart, RoundTripsAndRejectsEveryPrefix) {
  const Fixture x = fixture();
  CandidateSettings settings;
  settings.picture_side = 64;
  auto search = find_candidates(x.features, x.distance, settings, {}, std::vector<long long>{0, 3, 5});
  ASSERT_TRUE(search);
  CandidatePart part;
  part.key = 0x1234;
  part.frames = x.features.frames;
  part.tile_frames = x.distance.tile_frames;
  part.items = {0, 3, 5};
  part.search = *search;
  part.peak_memory_mb = 12.5;
  const std::string bytes = serialize_candidate_part(part);
  auto back = parse_candidate_part(bytes, "part");
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back->key, part.key);
  EXPECT_EQ(back->items, part.items);
  EXPECT_EQ(back->peak_memory_mb, 12.5);
  EXPECT_EQ(serialize_candidate_part(*back), bytes);
  for (size_t n = 0; n < bytes.size(); n += 97) EXPECT_FALSE(parse_candidate_part(bytes.substr(0, n), "part")) << n;
}

}  // namespace
}  // namespace mg
