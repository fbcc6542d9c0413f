#pragma once
// Work of one forward run shared among threads without changing its result: the items are split
// into contiguous chunks in index order and every item writes only its own output, so the
// outcome is the same as the serial loop's bit for bit, whatever the thread count.
#include <algorithm>
#include <functional>
#include <vector>

#include "ddaslope/core/thread_pool.hpp"

namespace ddaslope {

/// Below this many items a loop runs on the calling thread: waking a worker costs microseconds,
/// more than the loops of a small scene take.
inline constexpr int kParallelMinItems = 512;

/// Calls body(begin, end, chunk) for `chunks` contiguous chunks of [0, n), chunk 0 on the caller's
/// thread and the others on the process's thread pool. chunks = min(threads, …); 1 when
/// n < kParallelMinItems.
template <class Body>
int parallelChunks(int n, int threads, Body&& body) {
  const int chunks = n < kParallelMinItems ? 1 : std::clamp(threads, 1, n);
  if (chunks == 1) {
    body(0, n, 0);
    return 1;
  }
  const auto bounds = [&](int k) { return static_cast<int>(static_cast<long long>(n) * k / chunks); };
  std::vector<std::function<void()>> tasks;
  tasks.reserve(static_cast<size_t>(chunks));
  for (int k = 0; k < chunks; ++k) tasks.emplace_back([&, k] { body(bounds(k), bounds(k + 1), k); });
  ThreadPool::instance(chunks - 1).runAll(tasks);
  return chunks;
}

/// body(i) for every i in [0, n), shared as parallelChunks() does.
template <class Body>
void parallelFor(int n, int threads, Body&& body) {
  parallelChunks(n, threads, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) body(i);
  });
}

}  // namespace ddaslope
