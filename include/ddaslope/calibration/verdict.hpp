#pragma once
// Stability verdict of one forward run: the function the bisection and back-analysis loops search.
#include "ddaslope/model/scene.hpp"

namespace ddaslope::calibration {

struct VerdictSettings {
  /// Failing once any monitor has moved more than this (m) from its initial position. The
  /// elastic settling of the contact springs is orders of magnitude smaller; a released block
  /// passes it within a fraction of a second. ≤ 0: 1e-3 of the model half-size w0.
  double failureDisplacement = 0;
};

struct TrialResult {
  bool stable = true;
  double maxDisplacement = 0;  ///< largest monitor displacement reached (m)
  double timeReached = 0;      ///< simulated time when the trial stopped (s)
  bool converged = true;       ///< false if the run hit non-convergence (counted as failing)
};

/// Runs the scene (equilibrium first) until its duration or until a monitor passes the failure
/// displacement, whichever comes first: a failing trial stops as soon as its verdict is certain.
TrialResult judgeStability(const model::Scene& scene, const VerdictSettings& settings = {});

}  // namespace ddaslope::calibration
