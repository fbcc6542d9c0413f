#pragma once
// Bound-constrained minimisation through NLopt (only minimiser.cpp includes NLopt).
#include <functional>
#include <string>
#include <vector>

namespace ddaslope::calibration {

struct MinimiserResult {
  std::vector<double> x;  ///< best point found (unit box)
  double value = 0;
  int evaluations = 0;
  std::string status;     ///< NLopt's result code, as text
};

/// Minimises f over the unit box [0, 1]^n from x0 with the named NLopt algorithm (e.g.
/// "GN_DIRECT_L", "LN_BOBYQA", "LN_NELDERMEAD"). Throws InputError for an unknown name.
MinimiserResult minimise(const std::string& algorithm, const std::function<double(const std::vector<double>&)>& f,
                         const std::vector<double>& x0, int maxEvaluations, double xtolRel);

}  // namespace ddaslope::calibration
