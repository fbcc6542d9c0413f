#include "ddaslope/core/task_farm.hpp"

#include <algorithm>
#include <exception>
#include <mutex>
#include <thread>

namespace ddaslope {

namespace {

class ThreadFarm final : public TaskFarm {
 public:
  explicit ThreadFarm(int threads) : threads_(std::max(1, threads)) {}

  void run(const std::vector<int>& indices, const Task& task, const Sink& sink) override {
    std::mutex mutex;
    runOnThreads(static_cast<int>(indices.size()), threads_, [&](int k) {
      const TaskResult result = task(indices[static_cast<size_t>(k)]);
      const std::lock_guard<std::mutex> lock(mutex);
      sink(indices[static_cast<size_t>(k)], result);
    });
  }
  bool isRoot() const override { return true; }
  bool another(bool more) override { return more; }
  int slots() const override { return threads_; }
  std::string describe() const override { return std::to_string(threads_) + (threads_ == 1 ? " thread" : " threads"); }

 private:
  int threads_;
};

}  // namespace

std::unique_ptr<TaskFarm> makeThreadFarm(int threads) { return std::make_unique<ThreadFarm>(threads); }

void runOnThreads(int n, int threads, const std::function<void(int)>& work) {
  std::mutex mutex;
  int next = 0;
  std::exception_ptr error;
  const auto loop = [&] {
    for (;;) {
      int k;
      {
        const std::lock_guard<std::mutex> lock(mutex);
        if (error || next >= n) return;
        k = next++;
      }
      try {
        work(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  const int count = std::min(std::max(1, threads), n);
  try {
    for (int t = 1; t < count; ++t) pool.emplace_back(loop);
  } catch (...) {
    // No thread to start (std::system_error): the ones started still share the work.
  }
  loop();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace ddaslope
