#pragma once
// Δt control: cut a failed step, then grow back towards the nominal Δt.

namespace ddaslope::solver {

class StepSizeController {
 public:
  StepSizeController(double nominal, double cutFactor) : nominal_(nominal), cut_(cutFactor), next_(nominal) {}
  /// Δt for the next attempt, never past `remaining` (so the run ends on its duration).
  double proposal(double remaining) const;
  double cut(double failedDt) const { return failedDt * cut_; }
  /// After an accepted step of dt: grow by 1.5× per step, up to the nominal value.
  void accepted(double dt, bool wasCut);

 private:
  double nominal_;
  double cut_;
  double next_;
};

}  // namespace ddaslope::solver
