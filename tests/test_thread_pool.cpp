// The thread pool behind parallelChunks(): every task runs exactly once, the caller returns only
// after all have finished, errors reach the caller, and calls from several threads at once each
// get their own tasks back.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>

#include "ddaslope/core/parallel.hpp"
#include "ddaslope/core/thread_pool.hpp"

using namespace ddaslope;

// Closed form: Σ i over [0, n) = n(n − 1)/2, each item written by exactly one chunk.
TEST(ThreadPool, EveryItemOnceWhateverTheThreads) {
  constexpr int n = 100000;
  for (int threads : {1, 2, 3, 8}) {
    std::vector<long long> seen(n, 0);
    parallelFor(n, threads, [&](int i) { seen[static_cast<size_t>(i)] += i; });
    long long sum = 0;
    for (int i = 0; i < n; ++i) {
      ASSERT_EQ(seen[static_cast<size_t>(i)], i) << "item " << i << " with " << threads << " threads";
      sum += seen[static_cast<size_t>(i)];
    }
    EXPECT_EQ(sum, static_cast<long long>(n) * (n - 1) / 2);
  }
}

TEST(ThreadPool, ErrorsReachTheCallerAfterEveryTaskFinished) {
  std::atomic<int> finished{0};
  std::vector<std::function<void()>> tasks;
  for (int k = 0; k < 4; ++k)
    tasks.emplace_back([&finished, k] {
      std::this_thread::sleep_for(std::chrono::milliseconds(k == 3 ? 20 : 0));
      ++finished;
      if (k == 1) throw std::runtime_error("task 1");
    });
  EXPECT_THROW(ThreadPool::instance(3).runAll(tasks), std::runtime_error);
  EXPECT_EQ(finished.load(), 4);
}

// Two searches' forward runs share the pool: each call's sum is its own, n(n − 1)/2 · (caller + 1).
TEST(ThreadPool, ConcurrentCallersGetTheirOwnResults) {
  constexpr int n = 20000;
  std::vector<long long> sums(4, 0);
  std::vector<std::thread> callers;
  for (int c = 0; c < 4; ++c)
    callers.emplace_back([&sums, c] {
      for (int round = 0; round < 20; ++round) {
        std::vector<long long> part(2, 0);
        parallelChunks(n, 2, [&](int begin, int end, int chunk) {
          for (int i = begin; i < end; ++i) part[static_cast<size_t>(chunk)] += static_cast<long long>(i) * (c + 1);
        });
        sums[static_cast<size_t>(c)] = part[0] + part[1];
      }
    });
  for (std::thread& t : callers) t.join();
  for (int c = 0; c < 4; ++c) EXPECT_EQ(sums[static_cast<size_t>(c)], static_cast<long long>(n) * (n - 1) / 2 * (c + 1));
}
