#include "motiongraph/parallel/tile_share.h"

#include <algorithm>
#include <functional>
#include <queue>
#include <utility>

namespace mg {

std::vector<long long> items_of_process(const TileItems& items, std::span<const long long> pending, int processes,
                                        int rank) {
  std::vector<std::pair<long long, long long>> by_size;  // (pairs, item)
  by_size.reserve(pending.size());
  for (long long item : pending) by_size.emplace_back(items.pairs(item), item);
  std::sort(by_size.begin(), by_size.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first > y.first : x.second < y.second;
  });
  // (pairs so far, rank), smallest first.
  using Load = std::pair<long long, int>;
  std::priority_queue<Load, std::vector<Load>, std::greater<>> loads;
  for (int r = 0; r < processes; ++r) loads.emplace(0, r);
  std::vector<long long> mine;
  for (const auto& [pairs, item] : by_size) {
    auto [load, r] = loads.top();
    loads.pop();
    if (r == rank) mine.push_back(item);
    loads.emplace(load + pairs, r);
  }
  std::sort(mine.begin(), mine.end());
  return mine;
}

std::vector<std::vector<long long>> chunks_of(const TileItems& items, std::span<const long long> share,
                                              long long pairs) {
  std::vector<std::vector<long long>> chunks;
  long long in_last = pairs;  // a full chunk: the next item starts a new one
  for (long long item : share) {
    if (in_last >= pairs) {
      chunks.emplace_back();
      in_last = 0;
    }
    chunks.back().push_back(item);
    in_last += items.pairs(item);
  }
  return chunks;
}

}  // namespace mg
