#pragma once
// A minimal parallel loop over independent items (image rows, azimuth steps).
// Each item writes only its own output, so the result is independent of the
// number of threads.

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace l2s::sim::detail {

inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

/// Calls body(i) for i in [0, count) on up to `threads` threads; items are
/// handed out in chunks through an atomic counter (rows differ in cost).
template <class Body>
void parallel_for(int count, int threads, Body&& body, int chunk = 8) {
  threads = std::max(1, std::min(resolve_threads(threads), (count + chunk - 1) / chunk));
  if (threads == 1) {
    for (int i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<int> next{0};
  const auto worker = [&]() {
    for (;;) {
      const int begin = next.fetch_add(chunk);
      if (begin >= count) return;
      const int end = std::min(count, begin + chunk);
      for (int i = begin; i < end; ++i) body(i);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& thread : pool) thread.join();
}

}  // namespace l2s::sim::detail
