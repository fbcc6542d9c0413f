#pragma once
// Narrowing a bracket between a stable and a failing trial (bisection, or k-section when
// several forward runs can be evaluated at once).
#include <functional>
#include <string>
#include <vector>

namespace ddaslope::calibration {

struct BisectionResult {
  bool bracketed = false;  ///< false: both ends gave the same verdict (see `message`)
  double critical = 0;     ///< midpoint of the final bracket
  double stableEnd = 0;    ///< the bracket end that is stable
  double failingEnd = 0;   ///< the bracket end that fails
  int runs = 0;            ///< forward runs spent
  int rounds = 0;          ///< narrowing rounds
  std::string message;
};

/// Evaluates `stableAt` for every value, `threads` at a time; results in input order. An exception
/// of one evaluation is rethrown here, after the others running have finished.
std::vector<bool> evaluateAll(const std::function<bool(double)>& stableAt, const std::vector<double>& values,
                              int threads);

/// Narrows [stable, failing] (verdicts already known) to `width`: each round evaluates
/// `threads` equally spaced interior points at once, shrinking the bracket by threads + 1.
/// The verdict is assumed monotone between the ends.
BisectionResult narrowBracket(const std::function<bool(double)>& stableAt, double stable, double failing,
                              double width, int threads = 1);

/// Evaluates both ends, then narrows. Exactly one end must be stable.
BisectionResult bisect(const std::function<bool(double)>& stableAt, double lo, double hi, double width,
                       int threads = 1);

}  // namespace ddaslope::calibration
