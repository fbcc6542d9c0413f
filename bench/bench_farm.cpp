// The cost of dealing a task (core/task_farm.hpp): N tasks that each keep a core busy for W µs,
// on the farm of this process (threads) or of mpirun's ranks. The wall time beyond N·W/slots,
// per task, is what the farm adds to every forward run of a study (issue #18).
//   ddaslope_farm_bench [--tasks N] [--work-us W] [--threads T]
//   mpirun -np 2 ddaslope_farm_bench --threads 1
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "ddaslope/core/task_farm.hpp"

int main(int argc, char** argv) {
  ddaslope::startProcesses(argc, argv);
  int tasks = 20000, threads = 1;
  double workUs = 500;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--tasks") && i + 1 < argc) tasks = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--work-us") && i + 1 < argc) workUs = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: ddaslope_farm_bench [--tasks N] [--work-us W] [--threads T]\n");
      return 2;
    }
  }
  const auto farm = ddaslope::makeTaskFarm(threads);
  std::vector<int> indices(static_cast<size_t>(tasks));
  for (int k = 0; k < tasks; ++k) indices[k] = k;
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  long received = 0;
  farm->run(
      indices,
      [&](int k) {
        const auto until = Clock::now() + std::chrono::duration<double, std::micro>(workUs);
        while (Clock::now() < until) {
        }
        return ddaslope::TaskResult(16, static_cast<char>(k));  // a sample's result is ~100 bytes
      },
      [&](int, const ddaslope::TaskResult&) { ++received; });
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  if (farm->isRoot()) {
    const double ideal = tasks * workUs * 1e-6 / farm->slots();
    std::printf("%s: %d tasks of %.0f µs in %.3f s (ideal %.3f s): %.1f µs added per task, %ld results\n",
                farm->describe().c_str(), tasks, workUs, wall, ideal, 1e6 * (wall - ideal) * farm->slots() / tasks,
                received);
  }
  ddaslope::stopProcesses();
  return 0;
}
