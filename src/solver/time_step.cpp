#include "ddaslope/solver/time_step.hpp"

#include <algorithm>

namespace ddaslope::solver {

double StepSizeController::proposal(double remaining) const {
  // A last step shorter than 1e-9 of Δt is merged into this one rather than taken alone.
  if (remaining <= next_ * (1 + 1e-9)) return remaining;
  return next_;
}

double StepSizeController::cut(double failedDt) {
  if (failedDt > nominal_) {
    ceiling_ = std::max(nominal_, failedDt / 1.5);
    atCeiling_ = 0;
  }
  return failedDt * cut_;
}

void StepSizeController::accepted(double dt, bool wasCut) {
  if (wasCut) next_ = dt;
  next_ = std::min(nominal_, std::max(next_, dt) * (wasCut ? 1.0 : 1.5));
}

void StepSizeController::acceptedQuiet(double dt) {
  next_ = std::min(std::max(ceiling_, nominal_), std::max(next_, dt) * 1.5);
  if (cap_ > 0 && dt >= ceiling_ * (1 - 1e-9) && ++atCeiling_ >= kQuietStepsToRaise) {
    ceiling_ = std::min(cap_, 1.5 * ceiling_);
    atCeiling_ = 0;
  }
}

}  // namespace ddaslope::solver
