#include "ddaslope/calibration/bisection.hpp"

#include <cmath>
#include <sstream>

#include "ddaslope/core/task_farm.hpp"

namespace ddaslope::calibration {

std::vector<bool> evaluateAll(const std::function<bool(double)>& stableAt, const std::vector<double>& values,
                              int threads) {
  std::vector<char> out(values.size());
  runOnThreads(static_cast<int>(values.size()), threads,
               [&](int i) { out[static_cast<size_t>(i)] = stableAt(values[static_cast<size_t>(i)]); });
  return {out.begin(), out.end()};
}

BisectionResult narrowBracket(const std::function<bool(double)>& stableAt, double stable, double failing,
                              double width, int threads) {
  BisectionResult r;
  const int k = std::max(1, threads);
  while (std::abs(failing - stable) > width) {
    std::vector<double> trial;
    for (int i = 1; i <= k; ++i) trial.push_back(stable + (failing - stable) * i / (k + 1));
    const std::vector<bool> ok = evaluateAll(stableAt, trial, k);
    r.runs += k;
    ++r.rounds;
    // The new bracket lies between the last stable trial and the first failing one.
    double s = stable, f = failing;
    for (int i = 0; i < k; ++i) {
      if (!ok[i]) {
        f = trial[i];
        break;
      }
      s = trial[i];
    }
    stable = s;
    failing = f;
  }
  r.bracketed = true;
  r.stableEnd = stable;
  r.failingEnd = failing;
  r.critical = 0.5 * (stable + failing);
  return r;
}

BisectionResult bisect(const std::function<bool(double)>& stableAt, double lo, double hi, double width,
                       int threads) {
  const std::vector<bool> ends = evaluateAll(stableAt, {lo, hi}, threads);
  if (ends[0] == ends[1]) {
    BisectionResult r;
    r.runs = 2;
    std::ostringstream m;
    m << "not bracketed: both ends (" << lo << ", " << hi << ") are " << (ends[0] ? "stable" : "failing");
    r.message = m.str();
    r.critical = ends[0] ? lo : hi;
    r.stableEnd = r.failingEnd = r.critical;
    return r;
  }
  BisectionResult r = narrowBracket(stableAt, ends[0] ? lo : hi, ends[0] ? hi : lo, width, threads);
  r.runs += 2;
  return r;
}

}  // namespace ddaslope::calibration
