// The one way the library spreads independent work over threads: each of `workers` threads
// (this one among them) takes the next `chunk` indices until none are left. Results must not
// depend on which thread ran what (callers index their outputs by item, or by worker and then
// combine in an order of their own).
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace mg {

// `requested` threads, or one per core when it is 0 (or less).
inline int worker_threads(int requested) {
  return requested > 0 ? requested : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// work(worker, i) for every i in [0, count), worker in [0, workers): never more workers than
// chunks; returns once all are done.
template <class Work>
void parallel_for(long long count, int workers, long long chunk, const Work& work) {
  chunk = std::max(1LL, chunk);
  workers = static_cast<int>(std::clamp<long long>((count + chunk - 1) / chunk, 1, std::max(1, workers)));
  std::atomic<long long> next{0};
  auto loop = [&](int worker) {
    for (long long first = next.fetch_add(chunk); first < count; first = next.fetch_add(chunk)) {
      for (long long i = first; i < std::min(count, first + chunk); ++i) work(worker, i);
    }
  };
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w) threads.emplace_back(loop, w);
  loop(0);
  for (std::thread& thread : threads) thread.join();
}

}  // namespace mg
