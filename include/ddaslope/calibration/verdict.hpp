#pragma once
// Stability verdict of one forward run: the function the bisection and back-analysis loops search.
#include "ddaslope/model/scene.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::calibration {

/// A run is failing when (a) a monitor moves more than `failureDisplacement` from where it is at
/// t = 0, after the equilibrium (the quasi-static adjustment of a marginal slope while it comes to
/// rest is not failure; the run stops there: its verdict is certain), or (b) at the end of the run a monitor still moves faster
/// than `restingSpeed` and is not slowing down (its speed at the end is at least 90 % of its
/// speed at half the duration). (b) catches slopes just past failure, whose acceleration is too
/// small to reach (a) within the run; a stable scene is brought to rest before t = 0, so its
/// speed is at round-off level, and a decaying transient fails the "not slowing down" test.
/// Neither rule depends on Δt: sliding at constant acceleration is integrated exactly by
/// Newmark β = 1/2, γ = 1, whose numerical damping acts on oscillations only.
struct VerdictSettings {
  /// m; ≤ 0: 1e-3 of the model half-size w0.
  double failureDisplacement = 0;
  /// m/s; ≤ 0: 1e-4 of failureDisplacement per second.
  double restingSpeed = 0;
};

struct TrialResult {
  bool stable = true;
  double maxDisplacement = 0;  ///< largest monitor displacement after t = 0 (m)
  double finalSpeed = 0;       ///< largest monitor speed at the end of the run (m/s)
  double timeReached = 0;      ///< simulated time when the trial stopped (s)
  bool converged = true;       ///< false if the run hit non-convergence (counted as failing)
  const char* reason = "";     ///< which rule decided a failing verdict
};

/// Runs the scene (equilibrium first, from `shared` when given: see solver::HeldEquilibrium)
/// until its duration or until rule (a) fires.
TrialResult judgeStability(const model::Scene& scene, const VerdictSettings& settings = {},
                           const solver::HeldEquilibrium* shared = nullptr);

}  // namespace ddaslope::calibration
