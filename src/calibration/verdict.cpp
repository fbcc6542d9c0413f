#include "ddaslope/calibration/verdict.hpp"

#include "ddaslope/core/errors.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::calibration {

TrialResult judgeStability(const model::Scene& scene, const VerdictSettings& settings) {
  DDASLOPE_ASSERT(!scene.monitors.empty(), "a stability verdict needs at least one monitor");
  solver::Simulation sim(scene);
  const double threshold =
      settings.failureDisplacement > 0 ? settings.failureDisplacement : 1e-3 * sim.modelHalfSize();
  TrialResult r;
  const auto update = [&] {
    for (const model::Monitor& m : sim.scene().monitors)
      r.maxDisplacement = std::max(r.maxDisplacement, (m.point.current - m.point.initial).norm());
    r.timeReached = sim.time();
    return r.maxDisplacement > threshold;
  };
  try {
    sim.bringToEquilibrium();
    if (update()) {
      r.stable = false;
      return r;
    }
    while (!sim.finished()) {
      sim.advance();
      if (update()) {
        r.stable = false;
        return r;
      }
    }
  } catch (const NonConvergenceError&) {
    r.stable = false;
    r.converged = false;
  }
  return r;
}

}  // namespace ddaslope::calibration
