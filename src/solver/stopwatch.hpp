#pragma once
// Laps of wall time, for the phase times of RunStatistics (they do not steer the run).
#include <chrono>

namespace ddaslope::solver {

class Stopwatch {
 public:
  /// Seconds since the last lap (or since construction).
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace ddaslope::solver
