#include "motiongraph/synthesis/synthesis_context.h"

#include <gtest/gtest.h>

#include <vector>

namespace mg {
namespace {

TagCostCache::Key key_priced(double per_frame) {
  TagCostCache::Key key;
  key.tag = 1;
  key.per_frame = per_frame;
  return key;
}

// A key asked again is not made again; a new one is.
TEST(TagCostCache, MakesEachKeyOnce) {
  TagCostCache cache;
  int made = 0;
  auto make = [&] {
    ++made;
    return std::vector<double>{static_cast<double>(made)};
  };
  auto a = cache.get(key_priced(1.0), make);
  auto b = cache.get(key_priced(1.0), make);
  EXPECT_EQ(made, 1);
  EXPECT_EQ(a, b);
  auto c = cache.get(key_priced(2.0), make);
  EXPECT_EQ(made, 2);
  EXPECT_EQ((*c)[0], 2.0);
  EXPECT_EQ(cache.size(), 2u);
}

// A script sweeping a price keeps the cache at kKept entries: the least recently asked go, the
// ones asked again stay, and what a search holds stays valid after its entry went.
TEST(TagCostCache, KeepsTheMostRecentlyAsked) {
  TagCostCache cache;
  int made = 0;
  auto make_for = [&](double value) {
    return [&made, value] {
      ++made;
      return std::vector<double>(1000, value);
    };
  };
  const auto held = cache.get(key_priced(0.0), make_for(0.0));
  const auto kept = cache.get(key_priced(0.5), make_for(0.5));
  const int n = static_cast<int>(TagCostCache::kKept) * 3;
  for (int i = 1; i <= n; ++i) {
    cache.get(key_priced(i), make_for(i));
    cache.get(key_priced(0.5), make_for(0.5));  // asked again each time: stays
    EXPECT_LE(cache.size(), TagCostCache::kKept);
  }
  EXPECT_EQ(cache.size(), TagCostCache::kKept);
  EXPECT_EQ(made, n + 2);
  // The one asked throughout is still there; the first one went, but its holder still reads it.
  EXPECT_EQ(cache.get(key_priced(0.5), make_for(-1.0)), kept);
  EXPECT_EQ(made, n + 2);
  EXPECT_EQ(held->size(), 1000u);
  EXPECT_EQ(held->back(), 0.0);
  auto again = cache.get(key_priced(0.0), make_for(7.0));
  EXPECT_EQ(made, n + 3);
  EXPECT_NE(again, held);
  EXPECT_EQ(again->front(), 7.0);
  // The latest ones asked are there, the ones before the last kKept are not.
  const int before = made;
  cache.get(key_priced(n), make_for(n));
  EXPECT_EQ(made, before);
  cache.get(key_priced(1.0), make_for(1.0));
  EXPECT_EQ(made, before + 1);
}

// The travelling marks are kept the same way, per pace.
TEST(TagCostCache, KeepsTheMarksOfTheLatestPaces) {
  TagCostCache cache;
  int made = 0;
  auto make = [&] {
    ++made;
    return std::vector<TagMask>(10, 1);
  };
  const auto first = cache.travelling(0.5, make);
  EXPECT_EQ(cache.travelling(0.5, make), first);
  EXPECT_EQ(made, 1);
  for (size_t i = 1; i <= TagCostCache::kKept; ++i) cache.travelling(0.5 + static_cast<double>(i), make);
  EXPECT_EQ(made, 1 + static_cast<int>(TagCostCache::kKept));
  EXPECT_NE(cache.travelling(0.5, make), first);  // gone, made again
  EXPECT_EQ(made, 2 + static_cast<int>(TagCostCache::kKept));
  EXPECT_EQ(first->size(), 10u);
}

}  // namespace
}  // namespace mg
