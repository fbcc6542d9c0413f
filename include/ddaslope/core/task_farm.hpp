#pragma once
// Independent forward runs behind one interface: a probability study's samples, a
// sweep's values, a critical curve's points. The caller lists the task indices; the farm runs
// each exactly once on its workers and hands every result to a sink on the root process. One
// process: a thread per worker. Under mpirun (when built with MPI): every rank runs its threads,
// and the root deals indices one at a time as workers free up (dynamic balance: a failing run
// ends early, so a static split would leave ranks idle).
//
// Results cross between processes as bytes, and a task's result must depend on its index only
// (never on the rank, thread or order): callers sort what the sink received by index, so the
// answer is the same whatever the farm.
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ddaslope {

/// A task's result as bytes (what an MPI message carries).
using TaskResult = std::string;

class TaskFarm {
 public:
  using Task = std::function<TaskResult(int index)>;
  using Sink = std::function<void(int index, const TaskResult& result)>;
  virtual ~TaskFarm() = default;
  /// Runs task(i) once for every i of `indices` and calls sink(i, result) on the root process,
  /// one call at a time, in the order the tasks finish. Every process calls run with the same
  /// indices (they come from the same command line); only the root's sink is called.
  /// If a task or the sink throws, no further task starts, the running ones finish (and reach
  /// the sink), and the first error is rethrown on the root (on the others: run returns).
  virtual void run(const std::vector<int>& indices, const Task& task, const Sink& sink) = 0;
  /// True on the process that writes results: always without MPI, rank 0 under mpirun.
  virtual bool isRoot() const = 0;
  /// For a study whose runs depend on the results before them (active learning): the root
  /// decides each run of the farm as it goes, and the other processes serve runs until it says
  /// none follows. Returns the root's `more` on every process (the others' argument is ignored):
  ///   root:   while (...) { farm.another(true); farm.run(indices, task, sink); } farm.another(false);
  ///   others: while (farm.another(false)) farm.run({}, task, {});
  virtual bool another(bool more) = 0;
  /// Tasks that can run at once: threads per process × processes.
  virtual int slots() const = 0;
  /// "2 threads", "3 ranks × 2 threads": for reports.
  virtual std::string describe() const = 0;
};

/// `threads` workers in this process.
std::unique_ptr<TaskFarm> makeThreadFarm(int threads);

/// work(i) once for every i in [0, n), on min(threads, n) threads of this process (the caller's
/// among them), each taking the next index as it frees up. An exception of a task never leaves
/// its thread: no further task starts, the running ones finish, and the first error is rethrown
/// on the caller. Every thread loop of the program that runs user-driven work goes through here
/// (or through ThreadPool::runAll), so a bad input met in a worker is reported, not an abort.
void runOnThreads(int n, int threads, const std::function<void(int)>& work);

/// Under mpirun with more than one rank: the MPI farm, `threads` per rank; else makeThreadFarm.
std::unique_ptr<TaskFarm> makeTaskFarm(int threads);

/// The processes a command runs on. `startProcesses` joins MPI when the program was started by
/// mpirun (and was built with MPI); otherwise it does nothing and the program is one process.
void startProcesses(int& argc, char**& argv);
void stopProcesses();
int processRank();   ///< 0 without MPI
int processCount();  ///< 1 without MPI
/// Ends every process with `code` (an error on one rank must not leave the others waiting).
[[noreturn]] void abortProcesses(int code);
/// True once a farm run ended with a task's error that every rank rethrew: each can then finish
/// normally (stopProcesses) with that error's exit code, and only the root reports it.
bool errorSharedByAllProcesses();
/// The error about to be thrown is met by every rank alike (a decision on the command line that
/// each rank takes the same way): errorSharedByAllProcesses() from now on.
void declareErrorShared();
/// "with MPI (Open MPI 4.1.4)" or "without MPI": for --version and reports.
std::string processSupport();

}  // namespace ddaslope
