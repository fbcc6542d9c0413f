#include "ddaslope/calibration/verdict.hpp"

#include "ddaslope/core/errors.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::calibration {

TrialResult judgeStability(const model::Scene& scene, const VerdictSettings& settings,
                           const solver::HeldEquilibrium* shared) {
  DDASLOPE_ASSERT(!scene.monitors.empty(), "a stability verdict needs at least one monitor");
  solver::Simulation sim(scene);
  // The call's settings first, then the case's (analysis.failure_displacement, resting_speed).
  const double threshold = settings.failureDisplacement > 0      ? settings.failureDisplacement
                           : scene.settings.failureDisplacement > 0 ? scene.settings.failureDisplacement
                                                                    : 1e-3 * sim.modelHalfSize();
  const double resting = settings.restingSpeed > 0      ? settings.restingSpeed
                         : scene.settings.restingSpeed > 0 ? scene.settings.restingSpeed
                                                           : 1e-4 * threshold;
  TrialResult r;
  std::vector<Vec2> start;  // monitor positions at t = 0, after the equilibrium
  const auto largestSpeed = [&] {
    double v = 0;
    for (size_t m = 0; m < sim.scene().monitors.size(); ++m)
      v = std::max(v, sim.monitorVelocity(static_cast<int>(m)).norm());
    return v;
  };
  const auto passedThreshold = [&] {
    const auto& mons = sim.scene().monitors;
    for (size_t k = 0; k < mons.size(); ++k)
      r.maxDisplacement = std::max(r.maxDisplacement, (mons[k].point.current - start[k]).norm());
    r.timeReached = sim.time();
    return r.maxDisplacement > threshold;
  };
  try {
    sim.bringToEquilibrium(shared);
    for (const model::Monitor& m : sim.scene().monitors) start.push_back(m.point.current);
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
