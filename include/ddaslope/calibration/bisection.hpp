#pragma once
// Bisection for the critical value of one parameter between a stable and a failing trial.
#include <functional>
#include <string>

namespace ddaslope::calibration {

struct BisectionResult {
  bool bracketed = false;  ///< false: both ends gave the same verdict (see `message`)
  double critical = 0;     ///< midpoint of the final bracket
  double stableEnd = 0;    ///< the bracket end that is stable
  double failingEnd = 0;   ///< the bracket end that fails
  int runs = 0;            ///< forward runs spent
  std::string message;
};

/// Finds where `stableAt` switches between `lo` and `hi` until the bracket is narrower than
/// `width` (absolute). Exactly one end must be stable; the verdict is assumed monotone between.
BisectionResult bisect(const std::function<bool(double)>& stableAt, double lo, double hi, double width);

}  // namespace ddaslope::calibration
