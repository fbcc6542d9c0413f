#include "ddaslope/calibration/verdict.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::calibration {
namespace {

/// A net motion more than this many times the scatter about a smooth path is motion, not noise:
/// a vibration of amplitude A scatters by A/√2 and moves a monitor at most 2A ≈ 2.8 × that.
constexpr double kNoiseFactor = 5;
/// Net motion over the last window against the window before: a slide accelerating from rest
/// gives 7/5, a transient dying out less than 1.
constexpr double kStillMovingRatio = 0.9;
constexpr double kMarginalRatioLow = 0.75, kMarginalRatioHigh = 1.25;

/// Monitor positions at every accepted step, for window judgements.
struct MonitorPath {
  std::vector<double> time;
  std::vector<std::vector<Vec2>> position;  ///< [sample][monitor]

  void record(const solver::Simulation& sim) {
    time.push_back(sim.time());
    std::vector<Vec2> p;
    for (const model::Monitor& m : sim.scene().monitors) p.push_back(m.point.current);
    position.push_back(std::move(p));
  }
  /// Position of monitor m at time t (linear between samples, held beyond the ends).
  Vec2 at(size_t m, double t) const {
    const auto it = std::lower_bound(time.begin(), time.end(), t);
    if (it == time.begin()) return position.front()[m];
    if (it == time.end()) return position.back()[m];
    const size_t k = static_cast<size_t>(it - time.begin());
    const double w = (t - time[k - 1]) / std::max(time[k] - time[k - 1], 1e-300);
    return (1 - w) * position[k - 1][m] + w * position[k][m];
  }
  /// RMS distance of monitor m's samples in [t0, t1] from their least-squares quadratic in time.
  double scatter(size_t m, double t0, double t1) const {
    std::vector<size_t> in;
    for (size_t k = 0; k < time.size(); ++k)
      if (time[k] >= t0 && time[k] <= t1) in.push_back(k);
    if (in.size() < 4) return 0;
    Eigen::MatrixXd a(in.size(), 3);
    Eigen::MatrixXd y(in.size(), 2);
    const double mid = 0.5 * (t0 + t1), half = std::max(0.5 * (t1 - t0), 1e-300);
    for (size_t r = 0; r < in.size(); ++r) {
      const double tau = (time[in[r]] - mid) / half;  // in [−1, 1]: a well-conditioned fit
      a.row(r) << 1, tau, tau * tau;
      y.row(r) = (position[in[r]][m] - position[in.front()][m]).transpose();
    }
    const Eigen::MatrixXd coef = a.colPivHouseholderQr().solve(y);
    return std::sqrt((a * coef - y).squaredNorm() / static_cast<double>(in.size()));
  }
};

struct WindowJudgement {
  WindowVerdict verdict = WindowVerdict::AtRest;
  bool marginal = false;
  WindowMotion motion;
};

/// Judges every monitor on quarters of [0, end]; the deciding monitor is a moving one if any
/// (the largest net motion), else the one nearest its floor.
WindowJudgement judgeAllWindows(const MonitorPath& path, size_t monitors, double end, double restingSpeed) {
  const double w = 0.25 * end;
  WindowJudgement worst;
  double worstScore = -1;
  for (size_t m = 0; m < monitors; ++m) {
    WindowMotion mo;
    const Vec2 a = path.at(m, end - 2 * w), b = path.at(m, end - w), c = path.at(m, end);
    mo.last = (c - b).norm();
    mo.previous = (b - a).norm();
    mo.floor = std::max(restingSpeed * w, kNoiseFactor * path.scatter(m, end - 2 * w, end));
    bool marginal = false;
    const WindowVerdict v = judgeWindows(mo, &marginal);
    // Moving monitors first (by net motion), then the others by how near their floor they come.
    const double score = v == WindowVerdict::StillMoving ? 2 + mo.last : mo.last / std::max(mo.floor, 1e-300) / 1e3;
    if (score > worstScore) worstScore = score, worst.verdict = v, worst.motion = mo;
    worst.marginal |= marginal;
  }
  return worst;
}

}  // namespace

const char* describe(VerdictRule rule) {
  switch (rule) {
    case VerdictRule::AtRest: return "at rest: net motion over the last window below the noise floor";
    case VerdictRule::SlowingDown: return "slowing down: net motion over the last window under 90 % of the window before";
    case VerdictRule::PassedDisplacement: return "a monitor passed the failure displacement";
    case VerdictRule::StillMoving: return "still moving and not slowing down at the end of the run";
    case VerdictRule::MovedWhileSettling:
      return "a monitor passed the failure displacement while the scene came to rest before t = 0";
    case VerdictRule::NotConverged: return "the run did not converge";
  }
  return "";
}

const char* name(VerdictRule rule) {
  switch (rule) {
    case VerdictRule::AtRest: return "at_rest";
    case VerdictRule::SlowingDown: return "slowing_down";
    case VerdictRule::PassedDisplacement: return "failure_displacement";
    case VerdictRule::StillMoving: return "still_moving";
    case VerdictRule::MovedWhileSettling: return "moved_while_settling";
    case VerdictRule::NotConverged: return "not_converged";
  }
  return "";
}

WindowVerdict judgeWindows(const WindowMotion& m, bool* marginal) {
  bool doubt = false;
  WindowVerdict v;
  if (!(m.last > m.floor)) {
    v = WindowVerdict::AtRest;
    doubt = m.last > 0.5 * m.floor;
  } else {
    const double ratio = m.previous > 0 ? m.last / m.previous : INFINITY;
    v = ratio >= kStillMovingRatio ? WindowVerdict::StillMoving : WindowVerdict::SlowingDown;
    doubt = m.last < 2 * m.floor || (ratio >= kMarginalRatioLow && ratio <= kMarginalRatioHigh);
  }
  if (marginal) *marginal = doubt;
  return v;
}

TrialResult judgeStability(const model::Scene& scene, const VerdictSettings& settings,
                           const solver::HeldEquilibrium* shared, const TrialEndObserver& atEnd) {
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
  r.failureDisplacement = threshold;
  const size_t monitors = scene.monitors.size();
  std::vector<Vec2> start;  // monitor positions at t = 0, after the equilibrium
  MonitorPath path;
  const auto passedThreshold = [&] {
    const auto& mons = sim.scene().monitors;
    for (size_t k = 0; k < monitors; ++k)
      r.maxDisplacement = std::max(r.maxDisplacement, (mons[k].point.current - start[k]).norm());
    r.timeReached = sim.time();
    return r.maxDisplacement > threshold;
  };
  const auto finish = [&](VerdictRule rule) {
    r.rule = rule;
    r.stable = rule == VerdictRule::AtRest || rule == VerdictRule::SlowingDown;
    r.reason = describe(rule);
    r.steps = static_cast<int>(path.time.size()) - 1;
    for (size_t m = 0; m < monitors; ++m)
      r.finalSpeed = std::max(r.finalSpeed, sim.monitorVelocity(static_cast<int>(m)).norm());
    if (atEnd) atEnd(sim, r);
    return r;
  };
  try {
    sim.bringToEquilibrium(shared);
    // Rule 0 counts the motion once contacts may slip (stages 2 and 3), not the elastic settlement
    // with every contact held (stage 1), which a soft rock makes large on a slope that stands.
    const std::vector<Vec2>& held = sim.monitorsAfterHeldEquilibrium();
    for (size_t k = 0; k < monitors; ++k) {
      start.push_back(sim.scene().monitors[k].point.current);
      const Vec2 from = k < held.size() ? held[k] : scene.monitors[k].point.current;
      r.settlingDisplacement = std::max(r.settlingDisplacement, (start[k] - from).norm());
    }
    if (r.settlingDisplacement > threshold) return finish(VerdictRule::MovedWhileSettling);
    path.record(sim);
    for (;;) {
      while (!sim.finished()) {
        sim.advance();
        path.record(sim);
        if (passedThreshold()) return finish(VerdictRule::PassedDisplacement);
      }
      const WindowJudgement j = judgeAllWindows(path, monitors, sim.time(), resting);
      r.lastWindowMotion = j.motion.last;
      r.previousWindowMotion = j.motion.previous;
      r.noiseFloor = j.motion.floor;
      if (j.marginal && !r.extended) {
        // Marginal: run as long again rather than guess, then judge on quarters of the whole.
        r.extended = true;
        sim.extendDuration(scene.settings.duration);
        continue;
      }
      r.marginal = j.marginal;
      return finish(j.verdict == WindowVerdict::StillMoving ? VerdictRule::StillMoving
                    : j.verdict == WindowVerdict::SlowingDown ? VerdictRule::SlowingDown
                                                              : VerdictRule::AtRest);
    }
  } catch (const NonConvergenceError&) {
    r.converged = false;
    return finish(VerdictRule::NotConverged);
  }
}

}  // namespace ddaslope::calibration
