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
    size_t next = 0;
    std::exception_ptr error;
    const auto work = [&] {
      for (;;) {
        int index;
        {
          const std::lock_guard<std::mutex> lock(mutex);
          if (error || next >= indices.size()) return;
          index = indices[next++];
        }
        try {
          const TaskResult result = task(index);
          const std::lock_guard<std::mutex> lock(mutex);
          sink(index, result);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(mutex);
          if (!error) error = std::current_exception();
        }
      }
    };
    const int n = static_cast<int>(std::min<size_t>(threads_, indices.size()));
    std::vector<std::thread> pool;
    for (int t = 1; t < n; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    if (error) std::rethrow_exception(error);
  }
  bool isRoot() const override { return true; }
  int slots() const override { return threads_; }
  std::string describe() const override { return std::to_string(threads_) + (threads_ == 1 ? " thread" : " threads"); }

 private:
  int threads_;
};

}  // namespace

std::unique_ptr<TaskFarm> makeThreadFarm(int threads) { return std::make_unique<ThreadFarm>(threads); }

}  // namespace ddaslope
