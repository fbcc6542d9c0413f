#include "ddaslope/solver/time_step.hpp"

#include <algorithm>

namespace ddaslope::solver {

double StepSizeController::proposal(double remaining) const {
  // A last step shorter than 1e-9 of Δt is merged into this one rather than taken alone.
  if (remaining <= next_ * (1 + 1e-9)) return remaining;
  return next_;
}

void StepSizeController::accepted(double dt, bool wasCut) {
  if (wasCut) next_ = dt;
  next_ = std::min(nominal_, std::max(next_, dt) * (wasCut ? 1.0 : 1.5));
}

}  // namespace ddaslope::solver
