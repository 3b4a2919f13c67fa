#include "motiongraph/core/huge_pages.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

namespace mg {
namespace {

// The advised range is exactly the whole huge pages inside the array, checked against a
// count page by page on random addresses and sizes.
TEST(HugePages, TheRangeIsTheWholeHugePagesInside) {
  std::mt19937_64 random(7);
  for (int trial = 0; trial < 2000; ++trial) {
    const std::uintptr_t address = (random() % 64) * 4096 + (trial % 3 == 0 ? kHugePageBytes * (random() % 8) : 0);
    const std::size_t bytes = random() % (6 * kHugePageBytes);
    const auto [begin, end] = whole_huge_pages(address, bytes);
    std::uintptr_t first = 0, last = 0;
    for (std::uintptr_t page = 0; page <= address + bytes; page += kHugePageBytes) {
      if (page >= address && page + kHugePageBytes <= address + bytes) {
        if (first == last) first = page;
        last = page + kHugePageBytes;
      }
    }
    EXPECT_EQ(end - begin, last - first) << address << " " << bytes;
    if (last > first) {
      EXPECT_EQ(begin, first) << address << " " << bytes;
    }
    EXPECT_LE(begin, end);
  }
}

TEST(HugePages, AReservedVectorFillsAndReadsAsAnyOther) {
  std::vector<double> values;
  reserve_huge(values, 3 * kHugePageBytes / sizeof(double) + 5);
  EXPECT_TRUE(values.empty());
  EXPECT_GE(values.capacity(), 3 * kHugePageBytes / sizeof(double) + 5);
  for (size_t i = 0; i < values.capacity(); ++i) values.push_back(static_cast<double>(i));
  double sum = 0.0;
  for (double v : values) sum += v;
  const double n = static_cast<double>(values.size());
  EXPECT_EQ(sum, n * (n - 1) / 2);
  std::vector<int> none;
  reserve_huge(none, 0);  // nothing to advise
  EXPECT_TRUE(none.empty());
}

// The arena hands out aligned pieces that do not overlap, inside its block and past it, and
// every byte written reads back.
TEST(HugePages, TheArenaHandsOutSeparateAlignedPieces) {
  std::mt19937 random(11);
  HugePageArena arena(1 << 20);
  struct Piece {
    std::byte* at;
    size_t bytes;
    unsigned char fill;
  };
  std::vector<Piece> pieces;
  size_t total = 0;
  while (total < (3u << 20)) {  // three times the block
    const size_t bytes = 1 + random() % 50000;
    const size_t alignment = size_t{1} << (random() % 7);
    auto* at = static_cast<std::byte*>(arena.resource()->allocate(bytes, alignment));
    ASSERT_EQ(reinterpret_cast<std::uintptr_t>(at) % alignment, 0u);
    const auto fill = static_cast<unsigned char>(pieces.size());
    std::memset(at, fill, bytes);
    pieces.push_back({at, bytes, fill});
    total += bytes;
  }
  for (const Piece& p : pieces) {
    for (size_t i = 0; i < p.bytes; i += 997) ASSERT_EQ(static_cast<unsigned char>(p.at[i]), p.fill);
  }
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.at < b.at; });
  for (size_t i = 1; i < pieces.size(); ++i) EXPECT_LE(pieces[i - 1].at + pieces[i - 1].bytes, pieces[i].at);
}

}  // namespace
}  // namespace mg
