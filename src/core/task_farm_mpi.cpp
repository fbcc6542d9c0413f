// The task farm over MPI ranks (the only file that includes mpi.h; built when CMake finds MPI).
// Rank 0 deals task indices and receives results; every rank, rank 0 included, runs tasks on
// its own threads. Only each rank's main thread calls MPI (MPI_THREAD_FUNNELED).
//
// Protocol, per worker slot (kDepth per thread): the worker sends READY once, then RESULT after
// each task; each of those messages is answered by one TASK message with the next index, or −1
// (STOP) when none is left or an error stopped the farm. A worker is done when each of its slots
// got STOP.
// MPI's C interface only (the deprecated C++ bindings need a library Debian does not link).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

#include "ddaslope/core/byte_record.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/task_farm.hpp"

namespace ddaslope {

namespace {

bool started = false;
int worldRank = 0, worldSize = 1;

enum Tag : int { kReady = 1, kResult = 2, kTask = 3, kEnding = 4 };
/// Set when a farm run ended with a task's error on every rank (errorSharedByAllProcesses()).
bool sharedError = false;
constexpr int kStop = -1;
/// How often an idle main thread looks for messages and finished tasks.
constexpr auto kPoll = std::chrono::microseconds(500);
/// Tasks dealt per worker thread: one running and one waiting, so a thread never waits for the
/// next index to travel (up to kPoll plus a message) between tasks. The cost: at the end of a
/// study a rank may hold one waiting task per thread while another rank has finished.
constexpr int kDepth = 2;

bool launchedByMpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK");
}

/// What a task ended with: its result, or an error of one of the kinds the CLI reports
/// differently (core/errors.hpp), rethrown as such on the root.
enum Outcome : char { kDone = 'R', kBadInput = 'I', kBudget = 'B', kNonConvergence = 'N', kFailure = 'E' };

/// RESULT message: index, outcome, then the result's bytes (or the error, packed).
std::string packResult(int index, char outcome, const std::string& bytes) {
  std::string m(sizeof(int) + 1, '\0');
  std::memcpy(m.data(), &index, sizeof(int));
  m[sizeof(int)] = outcome;
  return m + bytes;
}

[[noreturn]] void rethrow(char outcome, const std::string& bytes) {
  ByteUnpacker b(bytes);
  switch (outcome) {
    case kBadInput: {
      const std::string file = b.getString(), path = b.getString();
      throw InputError(file, path, b.getString());
    }
    case kBudget:
      throw BudgetExceededError(b.getString());
    case kNonConvergence:
      throw NonConvergenceError(b.getString());
    default:
      throw std::runtime_error(b.getString());
  }
}

/// Tasks of this rank, run by `threads` local threads from a queue the main thread fills.
class LocalWorkers {
 public:
  struct Done {
    int index;
    char outcome;
    std::string bytes;
  };
  LocalWorkers(int threads, const TaskFarm::Task& task) : task_(task) {
    for (int t = 0; t < threads; ++t) pool_.emplace_back([this] { work(); });
  }
  ~LocalWorkers() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      closing_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : pool_) t.join();
  }
  void push(int index) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      queue_.push_back(index);
    }
    wake_.notify_one();
  }
  /// Finished tasks since the last call; waits up to kPoll for one if there are none.
  std::vector<Done> collect() {
    std::unique_lock<std::mutex> lock(mutex_);
    if (done_.empty()) finished_.wait_for(lock, kPoll);
    std::vector<Done> out;
    out.swap(done_);
    return out;
  }
  bool idle() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return queue_.empty() && running_ == 0 && done_.empty();
  }

 private:
  void work() {
    for (;;) {
      int index;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [this] { return closing_ || !queue_.empty(); });
        if (queue_.empty()) return;
        index = queue_.front();
        queue_.pop_front();
        ++running_;
      }
      Done d{index, kDone, {}};
      try {
        d.bytes = task_(index);
      } catch (const InputError& e) {
        d.outcome = kBadInput;
        d.bytes = BytePacker().put(e.file()).put(e.jsonPath()).put(e.message()).bytes();
      } catch (const BudgetExceededError& e) {
        d.outcome = kBudget;
        d.bytes = BytePacker().put(std::string(e.what())).bytes();
      } catch (const NonConvergenceError& e) {
        d.outcome = kNonConvergence;
        d.bytes = BytePacker().put(std::string(e.what())).bytes();
      } catch (const std::exception& e) {
        d.outcome = kFailure;
        d.bytes = BytePacker().put(std::string(e.what())).bytes();
      } catch (...) {
        d.outcome = kFailure;
        d.bytes = BytePacker().put(std::string("unknown error")).bytes();
      }
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        --running_;
        done_.push_back(std::move(d));
      }
      finished_.notify_one();
    }
  }

  const TaskFarm::Task& task_;
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::deque<int> queue_;
  std::vector<Done> done_;
  int running_ = 0;
  bool closing_ = false;
  std::vector<std::thread> pool_;
};

class MpiFarm final : public TaskFarm {
 public:
  explicit MpiFarm(int threads) : threads_(std::max(1, threads)) {}

  void run(const std::vector<int>& indices, const Task& task, const Sink& sink) override {
    if (worldRank == 0)
      runRoot(indices, task, sink);
    else
      runWorker(task);
  }
  bool isRoot() const override { return worldRank == 0; }
  bool another(bool more) override {
    int flag = worldRank == 0 && more ? 1 : 0;
    MPI_Bcast(&flag, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return flag != 0;
  }
  int slots() const override { return threads_ * worldSize; }
  std::string describe() const override {
    return std::to_string(worldSize) + " ranks × " + std::to_string(threads_) + (threads_ == 1 ? " thread" : " threads");
  }

 private:
  void runRoot(const std::vector<int>& indices, const Task& task, const Sink& sink) {
    size_t next = 0;
    bool stopping = false;
    char errorOutcome = kDone;
    std::string error;
    std::exception_ptr sinkError;
    const auto nextIndex = [&] { return stopping || next >= indices.size() ? kStop : indices[next++]; };
    const auto deliver = [&](int index, char outcome, const std::string& bytes) {
      if (outcome != kDone) {
        if (errorOutcome == kDone && !sinkError) errorOutcome = outcome, error = bytes;
        stopping = true;
        return;
      }
      try {
        sink(index, bytes);
      } catch (...) {
        if (errorOutcome == kDone && !sinkError) sinkError = std::current_exception();
        stopping = true;
      }
    };
    LocalWorkers local(threads_, task);
    int localQueued = 0;  // root's own tasks dealt and not yet collected
    const auto feedLocal = [&] {
      while (localQueued < kDepth * threads_) {
        const int i = nextIndex();
        if (i == kStop) return;
        local.push(i);
        ++localQueued;
      }
    };
    feedLocal();
    int stopsOwed = (worldSize - 1) * kDepth * threads_;
    for (;;) {
      for (const LocalWorkers::Done& d : local.collect()) {
        --localQueued;
        deliver(d.index, d.outcome, d.bytes);
      }
      feedLocal();
      for (;;) {
        int flag = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
        if (!flag) break;
        int count = 0;
        MPI_Get_count(&status, MPI_BYTE, &count);
        std::string message(static_cast<size_t>(count), '\0');
        MPI_Recv(message.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (status.MPI_TAG == kResult && count >= static_cast<int>(sizeof(int)) + 1) {
          int index;
          std::memcpy(&index, message.data(), sizeof(int));
          deliver(index, message[sizeof(int)], message.substr(sizeof(int) + 1));
        }
        int give = nextIndex();
        MPI_Send(&give, 1, MPI_INT, status.MPI_SOURCE, kTask, MPI_COMM_WORLD);
        if (give == kStop) --stopsOwed;
      }
      if (stopsOwed == 0 && localQueued == 0 && (stopping || next >= indices.size())) break;
    }
    // Every worker learns how the run ended: a task's error ends every rank the same way (each
    // rethrows it, and all finalise MPI and exit with its code). MPI_Abort for such an error
    // raced with the workers' own finalisation in Open MPI 4.1's mpirun, which then crashed or
    // hung now and then (the MPI test under load). An error of the root's own sink (its output)
    // is not shared: the workers go on, and the root aborts them.
    const bool shared = errorOutcome != kDone && !sinkError;
    std::string ending(1, shared ? errorOutcome : static_cast<char>(kDone));
    if (shared) ending.append(error);
    for (int r = 1; r < worldSize; ++r)
      MPI_Send(ending.data(), static_cast<int>(ending.size()), MPI_BYTE, r, kEnding, MPI_COMM_WORLD);
    if (sinkError) std::rethrow_exception(sinkError);
    if (shared) {
      sharedError = true;
      rethrow(errorOutcome, error);
    }
  }

  void runWorker(const Task& task) {
    LocalWorkers local(threads_, task);
    for (int t = 0; t < kDepth * threads_; ++t) MPI_Send(nullptr, 0, MPI_BYTE, 0, kReady, MPI_COMM_WORLD);
    int stops = 0, running = 0;
    while (stops < kDepth * threads_ || running > 0) {
      for (const LocalWorkers::Done& d : local.collect()) {
        --running;
        const std::string m = packResult(d.index, d.outcome, d.bytes);
        MPI_Send(m.data(), static_cast<int>(m.size()), MPI_BYTE, 0, kResult, MPI_COMM_WORLD);
      }
      for (;;) {
        int flag = 0;
        MPI_Iprobe(0, kTask, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
        if (!flag) break;
        int index = kStop;
        MPI_Recv(&index, 1, MPI_INT, 0, kTask, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (index == kStop) {
          ++stops;
        } else {
          local.push(index);
          ++running;
        }
      }
    }
    MPI_Status status;
    MPI_Probe(0, kEnding, MPI_COMM_WORLD, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    std::string ending(static_cast<size_t>(count), '\0');
    MPI_Recv(ending.data(), count, MPI_BYTE, 0, kEnding, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!ending.empty() && ending[0] != kDone) {
      sharedError = true;
      rethrow(ending[0], ending.substr(1));
    }
  }

  int threads_;
};

}  // namespace

void startProcesses(int& argc, char**& argv) {
  if (started || !launchedByMpirun()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  started = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &worldRank);
  MPI_Comm_size(MPI_COMM_WORLD, &worldSize);
}

void stopProcesses() {
  if (!started) return;
  MPI_Finalize();
  started = false;
}

int processRank() { return worldRank; }
int processCount() { return worldSize; }

bool errorSharedByAllProcesses() { return sharedError; }
void declareErrorShared() { sharedError = true; }

void abortProcesses(int code) {
  if (started && worldSize > 1) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

std::string processSupport() {
  char version[MPI_MAX_LIBRARY_VERSION_STRING];
  int length = 0;
  MPI_Get_library_version(version, &length);
  std::string v(version, static_cast<size_t>(length));
  const size_t end = v.find_first_of(",\n");
  return "with MPI (" + v.substr(0, end) + ")";
}

std::unique_ptr<TaskFarm> makeTaskFarm(int threads) {
  if (started && worldSize > 1) return std::make_unique<MpiFarm>(threads);
  return makeThreadFarm(threads);
}

}  // namespace ddaslope
