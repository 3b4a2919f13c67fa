// Which of the distance stage's work items (metric/distance_tiles.h TileItems) each process of
// a team runs, balanced by frame pairs: items from the most pairs to the fewest (ties by number),
// each to the process with the fewest pairs so far (ties to the lower rank). Edge tiles are
// smaller and diagonal items hold one tile, not two, so counting items would not balance. Every
// process computes the same shares from the same pending items, without talking.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/metric/distance_tiles.h"

namespace mg {

// The items of `pending` (item numbers, each once) that process `rank` of `processes` runs, in
// increasing order.
std::vector<long long> items_of_process(const TileItems& items, std::span<const long long> pending, int processes,
                                        int rank);

// `items` (of `share`) cut into runs of consecutive entries of at least `pairs` frame pairs each
// (the last may hold fewer): the chunks a checkpoint saves one by one.
std::vector<std::vector<long long>> chunks_of(const TileItems& items, std::span<const long long> share,
                                              long long pairs);

}  // namespace mg
