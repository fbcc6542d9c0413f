#pragma once
// A process-wide pool of worker threads for the chunks of parallelChunks(): started once and kept,
// so a loop shared between threads costs a wake-up (microseconds), not a thread start (tens of
// microseconds) each time, and a step's three or four shared loops can pay on two cores.
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace ddaslope {

class ThreadPool {
 public:
  /// The pool, with at least `workers` threads (it grows on demand, never shrinks).
  static ThreadPool& instance(int workers);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// Runs every task, the first on the calling thread and the others on workers, and returns when
  /// all have finished. Tasks must not wait for one another. Safe to call from several threads at
  /// once (forward runs of a search in parallel, each sharing its own loops).
  void runAll(const std::vector<std::function<void()>>& tasks);

 private:
  ThreadPool() = default;
  void grow(int workers);
  void work();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
  std::vector<std::thread> threads_;
  bool stopping_ = false;
};

}  // namespace ddaslope
