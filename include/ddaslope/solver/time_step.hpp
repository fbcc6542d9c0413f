#pragma once
// Δt control: cut a failed step, then grow back towards the nominal Δt.
#include <algorithm>

namespace ddaslope::solver {

class StepSizeController {
 public:
  StepSizeController(double nominal, double cutFactor) : nominal_(nominal), cut_(cutFactor), next_(nominal) {}
  /// Δt for the next attempt, never past `remaining` (so the run ends on its duration).
  double proposal(double remaining) const;
  double cut(double failedDt) const { return failedDt * cut_; }
  /// After an accepted step of dt: grow by 1.5× per step, up to the nominal value.
  void accepted(double dt, bool wasCut);
  /// After a quiet step of dt (AnalysisSettings::timeStepGrowth): grow by 1.5×, up to `cap`,
  /// which may lie above the nominal Δt.
  void acceptedQuiet(double dt, double cap) { next_ = std::min(std::max(cap, nominal_), std::max(next_, dt) * 1.5); }

 private:
  double nominal_;
  double cut_;
  double next_;
};

}  // namespace ddaslope::solver
