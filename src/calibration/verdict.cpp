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
/// A still-moving verdict on less motion than this fraction of the failure displacement is not
/// failure unless the motion grows over extensions of the run.
constexpr double kDecisiveMotion = 0.1;
/// Extensions of the run (each by its duration) a small motion gets to show whether it grows.
constexpr int kMaxExtensions = 3;
/// Growth of the net speed over the last window from one judgement to the next that counts as
/// growing (a slide accelerating from rest: 2, then 1.5, then 4/3 as the run doubles, triples…).
constexpr double kGrowth = 1.1;

/// Paths of the points a verdict watches, in three coordinates: a monitor's (x, y, 0) at every
/// step, and a free block's centroid with its rotation times its reach, (x, y, R·θ), sampled every
/// `interval` of simulated time (thousands of blocks over thousands of steps would otherwise keep
/// gigabytes; 64 samples a run resolve the windows' quadratic fits).
struct PointPaths {
  explicit PointPaths(double interval) : interval(interval) {}
  double interval;
  size_t points = 0;
  std::vector<double> time;
  std::vector<Vec3> position;  ///< [sample · points + point]

  bool due(double t) const { return time.empty() || t >= time.back() + interval * (1 - 1e-9); }
  void record(double t, const std::vector<Vec3>& p) {
    points = p.size();
    time.push_back(t);
    position.insert(position.end(), p.begin(), p.end());
  }
  const Vec3& sample(size_t k, size_t m) const { return position[k * points + m]; }
  /// Position of point m at time t (linear between samples, held beyond the ends).
  Vec3 at(size_t m, double t) const {
    const auto it = std::lower_bound(time.begin(), time.end(), t);
    if (it == time.begin()) return sample(0, m);
    if (it == time.end()) return sample(time.size() - 1, m);
    const size_t k = static_cast<size_t>(it - time.begin());
    const double w = (t - time[k - 1]) / std::max(time[k] - time[k - 1], 1e-300);
    return (1 - w) * sample(k - 1, m) + w * sample(k, m);
  }
  /// RMS distance of point m's samples in [t0, t1] from their least-squares quadratic in time.
  double scatter(size_t m, double t0, double t1) const {
    std::vector<size_t> in;
    for (size_t k = 0; k < time.size(); ++k)
      if (time[k] >= t0 && time[k] <= t1) in.push_back(k);
    if (in.size() < 4) return 0;
    Eigen::MatrixXd a(in.size(), 3);
    Eigen::MatrixXd y(in.size(), 3);
    const double mid = 0.5 * (t0 + t1), half = std::max(0.5 * (t1 - t0), 1e-300);
    for (size_t r = 0; r < in.size(); ++r) {
      const double tau = (time[in[r]] - mid) / half;  // in [−1, 1]: a well-conditioned fit
      a.row(r) << 1, tau, tau * tau;
      y.row(r) = (sample(in[r], m) - sample(in.front(), m)).transpose();
    }
    const Eigen::MatrixXd coef = a.colPivHouseholderQr().solve(y);
    return std::sqrt((a * coef - y).squaredNorm() / static_cast<double>(in.size()));
  }
};

/// Every free block of the scene, as the verdict watches it.
struct BlockWatch {
  std::vector<int> blocks;      ///< free blocks
  std::vector<double> reach;    ///< largest distance of a vertex from the centroid at t = 0 (m)
  std::vector<std::vector<Vec2>> start;  ///< vertices at t = 0

  explicit BlockWatch(const model::Scene& s) {
    for (size_t b = 0; b < s.blocks.size(); ++b)
      if (!s.blocks[b].fixed) blocks.push_back(static_cast<int>(b));
  }
  void markStart(const model::Scene& s) {
    reach.clear();
    start.clear();
    for (int b : blocks) {
      const model::Block& blk = s.blocks[static_cast<size_t>(b)];
      double r = 0;
      for (const Vec2& v : blk.vertices) r = std::max(r, (v - blk.moments.centroid).norm());
      reach.push_back(r);
      start.push_back(blk.vertices);
    }
  }
  std::vector<Vec3> positions(const model::Scene& s) const {
    std::vector<Vec3> p;
    p.reserve(blocks.size());
    for (size_t k = 0; k < blocks.size(); ++k) {
      const model::Block& blk = s.blocks[static_cast<size_t>(blocks[k])];
      p.emplace_back(blk.moments.centroid.x(), blk.moments.centroid.y(), reach[k] * blk.rotation);
    }
    return p;
  }
  /// The largest displacement of a vertex of each watched block from `from` (its vertices in
  /// the order of `which`), into `out`.
  static void moves(const model::Scene& s, const std::vector<int>& which, const std::vector<std::vector<Vec2>>& from,
                    std::vector<double>& out) {
    out.assign(which.size(), 0.0);
    for (size_t k = 0; k < which.size(); ++k) {
      const std::vector<Vec2>& now = s.blocks[static_cast<size_t>(which[k])].vertices;
      const std::vector<Vec2>& was = from[k];
      for (size_t v = 0; v < now.size() && v < was.size(); ++v) out[k] = std::max(out[k], (now[v] - was[v]).norm());
    }
  }
};

/// What the window rules find over every point (monitors first, then blocks), for one judgement.
struct WindowJudgement {
  WindowVerdict verdict = WindowVerdict::AtRest;  ///< StillMoving: a point failing by rule (b)
  bool marginal = false;   ///< some point's verdict is marginal
  bool smallMotion = false;  ///< some point still moves, on too little motion to call it failure
  WindowMotion motion;     ///< of the deciding point
  std::string point;       ///< the deciding point
  double travelled = 0;    ///< the deciding point's largest displacement since t = 0 (m)
};

/// Each point's net motion over the last window per second at every judgement so far, and its
/// largest displacement since t = 0 (m): what rule (b) asks of a small motion.
struct PointRecord {
  std::vector<std::vector<double>> speeds;
  std::vector<double> largest;
};

/// Judges every point of `paths` (point m is record index offset + m) on quarters of [0, end]. A
/// point still moving fails rule (b) if it has moved at least kDecisiveMotion of the failure
/// displacement since t = 0 or its speed over the last window grew at each of its last two
/// judgements; else it is a small motion. The deciding point: a failing one if any (the largest
/// net motion), else a small motion (the largest), else the one nearest its floor.
void judgeAllWindows(const PointPaths& paths, const std::vector<std::string>& names, size_t offset, double end,
                     double restingSpeed, double failure, PointRecord& record, WindowJudgement& worst,
                     double& worstScore) {
  const double w = 0.25 * end;
  for (size_t m = 0; m < paths.points; ++m) {
    WindowMotion mo;
    const Vec3 a = paths.at(m, end - 2 * w), b = paths.at(m, end - w), c = paths.at(m, end);
    mo.last = (c - b).norm();
    mo.previous = (b - a).norm();
    mo.floor = std::max(restingSpeed * w, kNoiseFactor * paths.scatter(m, end - 2 * w, end));
    bool marginal = false;
    const WindowVerdict v = judgeWindows(mo, &marginal);
    std::vector<double>& speeds = record.speeds[offset + m];
    speeds.push_back(mo.last / w);
    const size_t n = speeds.size();
    const bool growing = n >= 3 && speeds[n - 1] >= kGrowth * speeds[n - 2] && speeds[n - 2] >= kGrowth * speeds[n - 3];
    const bool small = v == WindowVerdict::StillMoving && record.largest[offset + m] < kDecisiveMotion * failure && !growing;
    // Failing points first (by net motion), then small motions, then the others by how near their
    // floor they come.
    const double score = v == WindowVerdict::StillMoving ? (small ? 2 : 4) + mo.last
                                                         : mo.last / std::max(mo.floor, 1e-300) / 1e3;
    if (score > worstScore) {
      worstScore = score, worst.verdict = small ? WindowVerdict::AtRest : v, worst.motion = mo, worst.point = names[m];
      worst.travelled = record.largest[offset + m];
    }
    worst.marginal |= marginal;
    worst.smallMotion |= small;
  }
}

/// Early rest's condition (3) on one set of paths at time t of a run of `duration`, windows w:
/// every point's net motion over the last window, grown to the end of the run by the larger of its
/// last growth and a doubling every window, stays under half the end's floor `endFloor`; or it is
/// noise (within kNoiseFactor times its scatter about a smooth path over the two windows, that
/// scatter itself under 1e-3 of `endFloor`).
bool restsToTheEnd(const PointPaths& paths, double t, double w, double duration, double endFloor) {
  const double windowsLeft = (duration - t) / w;
  for (size_t m = 0; m < paths.points; ++m) {
    const Vec3 a = paths.at(m, t - 2 * w), b = paths.at(m, t - w), c = paths.at(m, t);
    const double last = (c - b).norm(), previous = (b - a).norm();
    const double growth = std::max(2.0, previous > 0 ? last / previous : INFINITY);
    if (last * std::pow(growth, windowsLeft) <= 0.5 * endFloor) continue;
    // Else noise: round-off, far below what the end's floor could notice (a vibration loud enough
    // to hide a creep is not let through). The fit costs more than the rest: asked last.
    const double noise = kNoiseFactor * paths.scatter(m, t - 2 * w, t);
    if (!(last <= noise && previous <= noise && noise <= 1e-3 * endFloor)) return false;
  }
  return true;
}

}  // namespace

const char* describe(VerdictRule rule) {
  switch (rule) {
    case VerdictRule::AtRest: return "at rest: net motion over the last window below the noise floor";
    case VerdictRule::SlowingDown: return "slowing down: net motion over the last window under 90 % of the window before";
    case VerdictRule::PassedDisplacement: return "a monitor or a block passed the failure displacement";
    case VerdictRule::StillMoving:
      return "still moving and not slowing down at the end of the run (by at least 10 % of the failure displacement, "
             "or growing over extensions of the run)";
    case VerdictRule::MovedWhileSettling:
      return "a monitor or a block passed the failure displacement while the scene came to rest before t = 0";
    case VerdictRule::NotConverged: return "the run did not converge";
    case VerdictRule::Undecided:
      return "undecided: a small motion (under 10 % of the failure displacement) still moving after 3 extensions of "
             "the run, neither growing nor stopping";
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
    case VerdictRule::Undecided: return "undecided";
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

double trialStepGrowth(const model::AnalysisSettings& settings) {
  return settings.timeStepGrowth > 0 ? settings.timeStepGrowth : kTrialStepGrowth;
}

TrialResult judgeStability(const model::Scene& scene, const VerdictSettings& settings,
                           const solver::HeldEquilibrium* shared, const TrialEndObserver& atEnd,
                           std::optional<solver::HeldEquilibrium>* settled) {
  solver::Simulation sim([&] {
    model::Scene trial = scene;
    trial.settings.timeStepGrowth = trialStepGrowth(scene.settings);
    return trial;
  }());
  // A trend failure run on past the case's duration takes the steps of its re-run from t = 0.
  sim.landStepsOn(scene.settings.duration / settings.length);
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
  std::vector<std::string> monitorNames, blockNames;
  for (const model::Monitor& m : scene.monitors) monitorNames.push_back("monitor " + m.id);
  BlockWatch watch(scene);
  for (int b : watch.blocks) blockNames.push_back("block " + scene.blocks[static_cast<size_t>(b)].id);
  std::vector<Vec2> start;  // monitor positions at t = 0, after the equilibrium
  PointPaths monitorPath(0), blockPath(scene.settings.duration / 64);
  // Early rest (verdict.hpp): the contact and support state changes so far at each block sample.
  // Under a record or a level history it is judged on the time since the loads stopped changing,
  // if they stop by the middle of the run: the end-of-run windows then lie after it too.
  const double quietFrom = scene.lastLoadChange();
  const bool earlyRest = scene.settings.earlyRest && quietFrom <= 0.5 * scene.settings.duration;
  std::vector<long> changesAt;
  const auto changes = [&] {
    const solver::RunStatistics& st = sim.statistics();
    return st.stickSlipChanges + st.openCloseChanges + st.supportStateChanges + st.frozenSteps + st.cycles + st.cuts;
  };
  const auto record = [&] {
    std::vector<Vec3> p;
    for (const model::Monitor& m : sim.scene().monitors) p.emplace_back(m.point.current.x(), m.point.current.y(), 0);
    monitorPath.record(sim.time(), p);
    if (blockPath.due(sim.time())) {
      blockPath.record(sim.time(), watch.positions(sim.scene()));
      changesAt.push_back(changes());
    }
  };
  const auto atRestForGood = [&] {
    // The time since the loads stopped changing (t itself in a time-invariant scene) stands for
    // the time so far: the scene has evolved by itself since then.
    const double t = sim.time(), duration = sim.scene().settings.duration, w = 0.25 * (t - quietFrom);
    if (t - quietFrom < (duration - quietFrom) / 8) return false;
    if (std::count_if(blockPath.time.begin(), blockPath.time.end(), [&](double s) { return s >= quietFrom; }) < 9)
      return false;
    // (2) No change since the last two windows began (the sample at or before t − 2w).
    const size_t k0 = static_cast<size_t>(std::upper_bound(blockPath.time.begin(), blockPath.time.end(), t - 2 * w) -
                                          blockPath.time.begin());
    if (k0 == 0 || changesAt.back() != changesAt[k0 - 1]) return false;
    // (3) Every point rests to the end of the run.
    const double endFloor = resting * 0.25 * duration;
    return restsToTheEnd(monitorPath, t, w, duration, endFloor) && restsToTheEnd(blockPath, t, w, duration, endFloor);
  };
  // The largest motion since t = 0 of any monitor or any point of a free block: monitors report
  // where the user looks, but a slope fails wherever it moves. Each point's own largest motion
  // is kept for rule (b).
  PointRecord points;
  points.speeds.resize(monitors + watch.blocks.size());
  points.largest.assign(monitors + watch.blocks.size(), 0.0);
  std::vector<double> blockMoves;
  const auto passedThreshold = [&] {
    // A point that passes the threshold within this step passed it at a time interpolated along
    // the step (a grown step may be several Δt long); the first such point decides.
    const double since = r.timeReached, now = sim.time();
    double crossed = now;
    const auto track = [&](size_t k, double d, const std::string& name) {
      const double before = points.largest[k];
      if (d > threshold && before <= threshold && since < now)
        crossed = std::min(crossed, since + (threshold - before) / (d - before) * (now - since));
      points.largest[k] = std::max(before, d);
      if (d > r.maxDisplacement) r.maxDisplacement = d, r.movedMost = name;
    };
    const auto& mons = sim.scene().monitors;
    for (size_t k = 0; k < monitors; ++k) track(k, (mons[k].point.current - start[k]).norm(), monitorNames[k]);
    BlockWatch::moves(sim.scene(), watch.blocks, watch.start, blockMoves);
    for (size_t k = 0; k < blockMoves.size(); ++k) track(monitors + k, blockMoves[k], blockNames[k]);
    const bool passed = r.maxDisplacement > threshold;
    r.timeReached = passed ? crossed : now;
    return passed;
  };
  const auto finish = [&](VerdictRule rule) {
    r.rule = rule;
    r.stable = rule == VerdictRule::AtRest || rule == VerdictRule::SlowingDown;
    r.undecided = rule == VerdictRule::Undecided;
    r.reason = describe(rule);
    r.equilibriumSteps = sim.statistics().equilibriumSteps + sim.statistics().settlingSteps;
    r.steps = std::max(0, static_cast<int>(monitorPath.time.size()) - 1);  // none recorded: no step after t = 0
    if (rule != VerdictRule::AtRest && rule != VerdictRule::SlowingDown && rule != VerdictRule::StillMoving &&
        rule != VerdictRule::Undecided) {
      // Decided on a displacement (or no run): no window judged it, whatever an extension had.
      r.decidedBy = r.movedMost;
      r.lastWindowMotion = r.previousWindowMotion = r.noiseFloor = 0;
    }
    for (size_t m = 0; m < monitors; ++m)
      r.finalSpeed = std::max(r.finalSpeed, sim.monitorVelocity(static_cast<int>(m)).norm());
    // And every free block's fastest point: |v| at its centroid + |ω| times its reach.
    for (int b : watch.blocks) {
      const model::Block& blk = sim.scene().blocks[static_cast<size_t>(b)];
      double reach = 0;
      for (const Vec2& v : blk.vertices) reach = std::max(reach, (v - blk.moments.centroid).norm());
      r.finalSpeed = std::max(r.finalSpeed, std::hypot(blk.velocity[0], blk.velocity[1]) + std::abs(blk.velocity[2]) * reach);
    }
    if (atEnd) atEnd(sim, r);
    return r;
  };
  bool ranOn = false;  // a failing slide run on to the failure displacement
  // The run's unit: its duration, or the run-on length once a trend failure is run on (an
  // extension adds one unit, judged on quarters of the whole, as a re-run that long would be).
  double unit = scene.settings.duration;
  int extensions = 0;  // extensions of the current unit
  try {
    // Rule (0) is decided the moment a point passes the threshold while the scene settles.
    sim.stopSettlingPast(threshold);
    sim.bringToEquilibrium(shared);
    if (settled && shared && sim.statistics().startedAtRest) *settled = sim.settledState(*shared);
    r.settling = sim.statistics().settling;
    if (r.settling == "stalled") r.startAcceleration = sim.statistics().equilibriumResidual;
    // Rule 0 counts the motion once contacts may slip (stages 2 and 3), not the elastic settlement
    // with every contact held (stage 1), which a soft rock makes large on a slope that stands.
    const std::vector<Vec2>& held = sim.monitorsAfterHeldEquilibrium();
    for (size_t k = 0; k < monitors; ++k) {
      start.push_back(sim.scene().monitors[k].point.current);
      const Vec2 from = k < held.size() ? held[k] : scene.monitors[k].point.current;
      const double d = (start[k] - from).norm();
      if (d > r.settlingDisplacement) r.settlingDisplacement = d, r.movedMost = monitorNames[k];
    }
    {
      std::vector<std::vector<Vec2>> heldVertices;
      const auto& heldBlocks = sim.blocksAfterHeldEquilibrium();
      for (int b : watch.blocks)
        heldVertices.push_back(heldBlocks.empty() ? scene.blocks[static_cast<size_t>(b)].vertices
                                                  : heldBlocks[static_cast<size_t>(b)].vertices);
      std::vector<double> settled;
      BlockWatch::moves(sim.scene(), watch.blocks, heldVertices, settled);
      for (size_t k = 0; k < settled.size(); ++k)
        if (settled[k] > r.settlingDisplacement) r.settlingDisplacement = settled[k], r.movedMost = blockNames[k];
    }
    if (r.settlingDisplacement > threshold) return finish(VerdictRule::MovedWhileSettling);
    r.movedMost.clear();
    watch.markStart(sim.scene());
    record();
    for (;;) {
      while (!sim.finished()) {
        sim.advance();
        const bool sampled = blockPath.due(sim.time());
        record();
        if (passedThreshold()) return finish(VerdictRule::PassedDisplacement);
        if (earlyRest && sampled && atRestForGood()) {
          r.earlyRest = true;
          r.decidedBy = "every point (early rest)";
          return finish(VerdictRule::AtRest);
        }
      }
      WindowJudgement j;
      double worstScore = -1;
      judgeAllWindows(monitorPath, monitorNames, 0, sim.time(), resting, threshold, points, j, worstScore);
      judgeAllWindows(blockPath, blockNames, monitors, sim.time(), resting, threshold, points, j, worstScore);
      r.lastWindowMotion = j.motion.last;
      r.previousWindowMotion = j.motion.previous;
      r.noiseFloor = j.motion.floor;
      r.decidedBy = j.point;
      const bool failing = j.verdict == WindowVerdict::StillMoving;
      // A marginal verdict is not guessed, and a small motion is failure only if it grows: run as
      // long again, then judge on quarters of the whole.
      if ((j.marginal && extensions == 0) || (!failing && j.smallMotion && extensions < kMaxExtensions)) {
        ++extensions, ++r.extensions;
        r.extended = true;
        sim.extendDuration(unit);
        continue;
      }
      if (!failing && j.smallMotion) return finish(VerdictRule::Undecided);
      // A trend failure is run on in place to settings.runOnLength times the duration and judged
      // afresh there, as a search review's re-run that long from t = 0 would be judged
      // (VerdictSettings::runOnLength), without running the first stretch twice.
      const double runOnTo = settings.runOnLength * scene.settings.duration;
      if (failing && !r.runOn && settings.runOnLength > 1) {
        r.runOn = true;
        unit = runOnTo;
        extensions = 0;
        for (std::vector<double>& sp : points.speeds) sp.clear();
        if (sim.time() < runOnTo * (1 - 1e-9)) {
          ++r.extensions;
          r.extended = true;
          sim.extendDuration(runOnTo - sim.time());
        }
        // Judged afresh at that length (here at once if its extensions already reached it).
        continue;
      }
      // A slide that its last window's pace, not slowing, carries past the failure displacement
      // within one more window is run on (as long again, stopping there: rule (a), certain)
      // rather than called failing on its trend, which a search confirms by a run four times as
      // long. If it stops short, the longer run's windows judge it.
      if (failing && !ranOn && j.travelled + j.motion.last >= threshold && j.motion.last >= j.motion.previous) {
        ranOn = true;
        ++r.extensions;
        r.extended = true;
        sim.extendDuration(unit);
        continue;
      }
      r.marginal = j.marginal;
      return finish(failing ? VerdictRule::StillMoving
                    : j.verdict == WindowVerdict::SlowingDown ? VerdictRule::SlowingDown
                                                              : VerdictRule::AtRest);
    }
  } catch (const NonConvergenceError&) {
    r.converged = false;
    return finish(VerdictRule::NotConverged);
  }
}

}  // namespace ddaslope::calibration
