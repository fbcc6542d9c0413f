#pragma once
// Δt control: cut a failed step, then grow back towards the nominal Δt; quiet steps may grow past
// it (AnalysisSettings::timeStepGrowth).
#include <algorithm>

namespace ddaslope::solver {

class StepSizeController {
 public:
  StepSizeController(double nominal, double cutFactor) : nominal_(nominal), cut_(cutFactor), next_(nominal) {}
  /// Quiet steps may grow up to `cap` (> the nominal Δt).
  void allowGrowthTo(double cap) { cap_ = ceiling_ = cap; }
  /// The largest Δt a quiet step may grow to, or 0 if steps never grow past the nominal Δt.
  double growthCap() const { return cap_; }
  /// Δt for the next attempt, never past `remaining` (so the run ends on its duration).
  double proposal(double remaining) const;
  /// Δt to try after an attempt of `failedDt` failed. A grown Δt that failed lowers the ceiling
  /// of later growth below it: a scene whose contacts cycle at that Δt does not grow straight
  /// back into the cycle.
  double cut(double failedDt);
  /// After an accepted step of dt: grow by 1.5× per step, up to the nominal value.
  void accepted(double dt, bool wasCut);
  /// After a quiet step of dt: grow by 1.5×, up to the ceiling (the cap, or below it after a
  /// grown step failed; kQuietStepsToRaise quiet steps in a row at it raise it by 1.5× again).
  void acceptedQuiet(double dt);

 private:
  static constexpr int kQuietStepsToRaise = 20;
  double nominal_;
  double cut_;
  double next_;
  double cap_ = 0;
  double ceiling_ = 0;
  int atCeiling_ = 0;  ///< quiet steps in a row at the ceiling since it last moved
};

}  // namespace ddaslope::solver
