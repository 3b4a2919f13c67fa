// Shares of the distance stage's work items: every pending item goes to exactly one process,
// the shares are balanced by frame pairs, and every process computes the same shares; chunks
// keep the share's order and hold at least the pairs asked for.
#include "motiongraph/parallel/tile_share.h"

#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

namespace mg {
namespace {

TileItems grid(int frames, int tile) {
  TileItems items;
  items.frames = frames;
  items.tile = tile;
  items.per_side = (frames + tile - 1) / tile;
  return items;
}

TEST(TileItems, NumbersEveryPairOfTileRowsOnce) {
  const TileItems items = grid(1000, 64);  // 16 per side, the last tile 40 frames
  ASSERT_EQ(items.count(), 16 * 17 / 2);
  long long item = 0, pairs = 0;
  for (int i = 0; i < items.per_side; ++i) {
    for (int j = i; j < items.per_side; ++j, ++item) {
      EXPECT_EQ(items.tiles_of(item), std::make_pair(i, j)) << item;
      EXPECT_EQ(items.tile_count(item), i == j ? 1 : 2);
      pairs += items.pairs(item);
    }
  }
  EXPECT_EQ(pairs, 1000LL * 1000);  // every frame pair in exactly one tile
  EXPECT_EQ(items.pairs(items.count() - 1), 40 * 40);
}

TEST(TileShare, EveryItemOnceAndBalancedByPairs) {
  const TileItems items = grid(5000, 256);  // 20 per side, edge tiles of 136 frames
  std::vector<long long> pending(static_cast<size_t>(items.count()));
  std::iota(pending.begin(), pending.end(), 0);
  pending.erase(pending.begin() + 10, pending.begin() + 40);  // as if restored from a checkpoint
  for (int processes : {1, 2, 3, 7}) {
    std::vector<long long> all;
    long long most = 0, fewest = -1, largest_item = 0;
    for (long long item : pending) largest_item = std::max(largest_item, items.pairs(item));
    for (int rank = 0; rank < processes; ++rank) {
      const std::vector<long long> mine = items_of_process(items, pending, processes, rank);
      EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end()));
      EXPECT_EQ(mine, items_of_process(items, pending, processes, rank));  // the same on every process
      long long pairs = 0;
      for (long long item : mine) pairs += items.pairs(item);
      most = std::max(most, pairs);
      fewest = fewest < 0 ? pairs : std::min(fewest, pairs);
      all.insert(all.end(), mine.begin(), mine.end());
    }
    std::sort(all.begin(), all.end());
    EXPECT_EQ(all, pending) << processes;
    // Largest first onto the least loaded: no two shares differ by more than one item.
    EXPECT_LE(most - fewest, largest_item) << processes;
  }
}

TEST(TileShare, ChunksKeepOrderAndHoldThePairsAsked) {
  const TileItems items = grid(3000, 128);
  std::vector<long long> share;
  for (long long item = 0; item < items.count(); item += 3) share.push_back(item);
  const long long wanted = 100000;
  const auto chunks = chunks_of(items, share, wanted);
  std::vector<long long> joined;
  for (size_t c = 0; c < chunks.size(); ++c) {
    long long pairs = 0;
    for (long long item : chunks[c]) pairs += items.pairs(item);
    if (c + 1 < chunks.size()) {
      EXPECT_GE(pairs, wanted);
    }
    pairs -= items.pairs(chunks[c].back());
    EXPECT_LT(pairs, wanted);  // it ends as soon as it holds enough
    joined.insert(joined.end(), chunks[c].begin(), chunks[c].end());
  }
  EXPECT_EQ(joined, share);
  EXPECT_TRUE(chunks_of(items, {}, wanted).empty());
}

}  // namespace
}  // namespace mg
