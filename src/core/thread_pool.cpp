#include "ddaslope/core/thread_pool.hpp"

#include <exception>

namespace ddaslope {

ThreadPool& ThreadPool::instance(int workers) {
  static ThreadPool pool;
  pool.grow(workers);
  return pool;
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void ThreadPool::grow(int workers) {
  std::lock_guard<std::mutex> lock(mutex_);
  while (static_cast<int>(threads_.size()) < workers) threads_.emplace_back([this] { work(); });
}

void ThreadPool::work() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, nothing left
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    task();
  }
}

void ThreadPool::runAll(const std::vector<std::function<void()>>& tasks) {
  if (tasks.empty()) return;
  // One latch per call, so that calls from several threads at once wait only for their own tasks.
  // A task's exception is carried to the caller, after every task has finished (the queued tasks
  // refer to this frame).
  struct Latch {
    std::mutex mutex;
    std::condition_variable done;
    int remaining = 0;
    std::exception_ptr error;
  } latch;
  latch.remaining = static_cast<int>(tasks.size()) - 1;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t k = 1; k < tasks.size(); ++k)
      queue_.emplace_back([&latch, &task = tasks[k]] {
        std::exception_ptr error;
        try {
          task();
        } catch (...) {
          error = std::current_exception();
        }
        std::lock_guard<std::mutex> l(latch.mutex);
        if (error && !latch.error) latch.error = error;
        if (--latch.remaining == 0) latch.done.notify_one();
      });
  }
  wake_.notify_all();
  std::exception_ptr first;
  try {
    tasks[0]();
  } catch (...) {
    first = std::current_exception();
  }
  std::unique_lock<std::mutex> lock(latch.mutex);
  latch.done.wait(lock, [&latch] { return latch.remaining == 0; });
  if (first) std::rethrow_exception(first);
  if (latch.error) std::rethrow_exception(latch.error);
}

}  // namespace ddaslope
