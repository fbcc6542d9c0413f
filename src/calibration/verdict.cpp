#include "ddaslope/calibration/verdict.hpp"

#include "ddaslope/core/errors.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::calibration {

TrialResult judgeStability(const model::Scene& scene, const VerdictSettings& settings,
                           const solver::HeldEquilibrium* shared) {
  DDASLOPE_ASSERT(!scene.monitors.empty(), "a stability verdict needs at least one monitor");
  solver::Simulation sim(scene);
  const double threshold =
      settings.failureDisplacement > 0 ? settings.failureDisplacement : 1e-3 * sim.modelHalfSize();
  const double resting = settings.restingSpeed > 0 ? settings.restingSpeed : 1e-4 * threshold;
  TrialResult r;
  const auto largestSpeed = [&] {
    double v = 0;
    for (size_t m = 0; m < sim.scene().monitors.size(); ++m)
      v = std::max(v, sim.monitorVelocity(static_cast<int>(m)).norm());
    return v;
  };
  const auto passedThreshold = [&] {
    for (const model::Monitor& m : sim.scene().monitors)
      r.maxDisplacement = std::max(r.maxDisplacement, (m.point.current - m.point.initial).norm());
    r.timeReached = sim.time();
    return r.maxDisplacement > threshold;
  };
  try {
    sim.bringToEquilibrium(shared);
    double midSpeed = -1;
    const double half = 0.5 * scene.settings.duration;
    while (!passedThreshold()) {
      if (sim.finished()) {
        r.finalSpeed = largestSpeed();
        if (r.finalSpeed > resting && r.finalSpeed >= 0.9 * midSpeed) {
          r.stable = false;
          r.reason = "still moving and not slowing down at the end of the run";
        }
        return r;
      }
      sim.advance();
      if (midSpeed < 0 && sim.time() >= half) midSpeed = largestSpeed();
    }
    r.stable = false;
    r.reason = "a monitor passed the failure displacement";
  } catch (const NonConvergenceError&) {
    r.stable = false;
    r.converged = false;
    r.reason = "the run did not converge";
  }
  return r;
}

}  // namespace ddaslope::calibration
