// The task farm of independent forward runs (core/task_farm.hpp) in one process; three MPI ranks
// are tested end to end by scripts/test_mpi.sh.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <cmath>
#include <map>

#include "ddaslope/calibration/bisection.hpp"
#include "ddaslope/core/byte_record.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/task_farm.hpp"

using namespace ddaslope;

TEST(TaskFarm, RunsEveryIndexOnceAndHandsEachResultToTheSinkOneAtATime) {
  for (int threads : {1, 2, 5}) {
    const auto farm = makeThreadFarm(threads);
    std::vector<int> indices;
    for (int i = 0; i < 40; ++i) indices.push_back(3 * i);
    std::map<int, double> got;
    std::atomic<int> inSink{0};
    bool overlapped = false;
    farm->run(
        indices, [](int i) { return BytePacker().put(std::sqrt(double(i))).bytes(); },
        [&](int i, const TaskResult& r) {
          if (inSink++ != 0) overlapped = true;
          EXPECT_EQ(got.count(i), 0u) << "index " << i << " twice";
          got[i] = ByteUnpacker(r).get<double>();
          --inSink;
        });
    EXPECT_FALSE(overlapped);
    ASSERT_EQ(got.size(), indices.size()) << threads << " threads";
    // The result crosses as its bytes: the same double, bit for bit.
    for (int i : indices) EXPECT_EQ(got[i], std::sqrt(double(i)));
    EXPECT_TRUE(farm->isRoot());
    EXPECT_EQ(farm->slots(), threads);
  }
}

TEST(TaskFarm, AFailingTaskStopsTheFarmAndItsErrorReachesTheCallerAsItsKind) {
  const auto farm = makeThreadFarm(2);
  std::vector<int> indices(100);
  for (int i = 0; i < 100; ++i) indices[i] = i;
  std::atomic<int> started{0};
  const auto run = [&] {
    farm->run(
        indices,
        [&](int i) {
          ++started;
          if (i == 5) throw InputError("case.json", "joints.a.friction_angle", "expected [0, 90), found -1");
          std::this_thread::sleep_for(std::chrono::milliseconds(10));  // a forward run takes time
          return TaskResult{};
        },
        [](int, const TaskResult&) {});
  };
  EXPECT_THROW(run(), InputError);
  // No task starts after the error is recorded: the five before it, itself, and the one the other
  // thread is running (10 ms each, so it cannot get two ahead of an error raised at once).
  EXPECT_LE(started.load(), 5 + 1 + 1);
  EXPECT_GE(started.load(), 6);
}

// A search's trials run on threads of their own: an exception in one (bad input met while
// building a trial's scene, a broken invariant) must reach the caller, never end the program
// (std::terminate: "terminate called without an active exception", exit 134).
TEST(Bisection, AnEvaluationThatThrowsOnAWorkerThreadReachesTheCaller) {
  for (int threads : {2, 4}) {
    std::atomic<int> evaluated{0};
    const auto stableAt = [&](double v) -> bool {
      ++evaluated;
      if (v >= 1) throw InputError("case.json", "joints.a.cohesion", "expected a cohesion ≥ 0 Pa, found -1");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the caller's own trial is the slow one
      return true;
    };
    EXPECT_THROW(calibration::evaluateAll(stableAt, {0, 1, 2, 3, 4, 5, 6, 7}, threads), InputError) << threads;
    EXPECT_LT(evaluated.load(), 8) << "no trial starts after an error";
    EXPECT_THROW(calibration::bisect(stableAt, 0.5, 2, 0.01, threads), InputError) << threads;
  }
}

TEST(TaskFarm, RunOnThreadsRunsEachIndexOnceAndCarriesTheFirstError) {
  for (int threads : {1, 2, 3, 64}) {
    std::vector<std::atomic<int>> runs(50);
    runOnThreads(50, threads, [&](int k) { ++runs[static_cast<size_t>(k)]; });
    for (const auto& r : runs) EXPECT_EQ(r.load(), 1) << threads;
    std::atomic<int> started{0};
    const auto failing = [&] {
      runOnThreads(50, threads, [&](int k) {
        ++started;
        if (k == 3) throw NonConvergenceError("trial 3 did not converge");
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      });
    };
    EXPECT_THROW(failing(), NonConvergenceError) << threads;
    EXPECT_LE(started.load(), 4 + threads) << threads;
  }
  runOnThreads(0, 2, [](int) { FAIL() << "no index"; });
}

TEST(ByteRecord, PacksValuesAndTextInOrder) {
  BytePacker p;
  p.put(true).put(-1.25e-300).put(42).put(std::string("no bracket, F > 4")).put(std::string());
  const std::string bytes = p.bytes();
  ByteUnpacker u(bytes);
  EXPECT_TRUE(u.get<bool>());
  EXPECT_EQ(u.get<double>(), -1.25e-300);
  EXPECT_EQ(u.get<int>(), 42);
  EXPECT_EQ(u.getString(), "no bracket, F > 4");
  EXPECT_EQ(u.getString(), "");
  EXPECT_THROW(u.get<int>(), InternalError);  // read past the end: a bug, said so
}
