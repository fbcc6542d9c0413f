#include "ddaslope/calibration/strength_search.hpp"

#include <algorithm>
#include <cstdio>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>
#include <thread>

#include "ddaslope/calibration/bisection.hpp"
#include "ddaslope/core/byte_record.hpp"
#include "ddaslope/core/types.hpp"

namespace ddaslope::calibration {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Wraps a verdict function so that every forward run is counted, recorded and reported
/// (thread-safe).
struct CountedVerdict {
  /// `quantity`: the searched value's symbol for the progress line; `width`: the bracket the
  /// search narrows to (≤ 0: 1e-3 of its failing end), for the estimate of the runs left.
  CountedVerdict(std::function<TrialResult(double)> v, const SearchSettings& s, const char* quantity, double width)
      : verdict(std::move(v)), progress(s.progress), quantity(quantity), width(width), perRound(std::max(1, s.threads)) {}
  std::function<TrialResult(double)> verdict;
  io::ProgressSink progress;
  const char* quantity;
  double width;
  int perRound;
  std::atomic<int> runs{0};
  std::mutex mutex;
  std::vector<TrialRecord> trials;
  bool operator()(double x) {
    ++runs;
    TrialResult r = verdict(x);
    const std::lock_guard<std::mutex> lock(mutex);
    trials.push_back({x, r});
    if (progress) report(x, r.stable);
    return r.stable;
  }
  /// The trials by value: the record does not depend on which thread finished first.
  std::vector<TrialRecord> sortedTrials() {
    std::sort(trials.begin(), trials.end(), [](const TrialRecord& a, const TrialRecord& b) { return a.value < b.value; });
    return trials;
  }

 private:
  /// The tightest bracket so far (a stable and a failing trial closest together) and the runs a
  /// k-section still needs to narrow it to the width.
  void report(double last, bool lastStable) {
    io::ProgressEvent e;
    e.done = static_cast<int>(trials.size());
    const TrialRecord* s = nullptr;
    const TrialRecord* f = nullptr;
    for (const TrialRecord& a : trials)
      for (const TrialRecord& b : trials)
        if (a.result.stable && !b.result.stable &&
            (!s || std::abs(a.value - b.value) < std::abs(s->value - f->value)))
          s = &a, f = &b;
    char text[160];
    if (s) {
      const double gap = std::abs(s->value - f->value);
      const double target = width > 0 ? width : 1e-3 * std::abs(f->value);
      const int rounds = gap > target ? static_cast<int>(std::ceil(std::log(gap / target) / std::log(perRound + 1.0))) : 0;
      e.stage = "narrow";
      e.planned = e.done + rounds * perRound;
      std::snprintf(text, sizeof text, "%s stable at %.6g, fails at %.6g", quantity, s->value, f->value);
      e.values = {{"stable_end", s->value}, {"failing_end", f->value}};
    } else {
      e.stage = "bracket";
      std::snprintf(text, sizeof text, "%s %.6g %s", quantity, last, lastStable ? "stable" : "fails");
      e.values = {{"last_trial", last}};
    }
    e.detail = text;
    progress(e);
  }
};

/// Stage 1 of the equilibrium, computed once for a search whose trials differ only in joint
/// strengths (it holds every contact, so strengths do not enter it).
std::optional<solver::HeldEquilibrium> sharedEquilibrium(const model::Scene& scene) {
  if (!scene.settings.initialEquilibrium) return std::nullopt;
  solver::Simulation sim(scene);
  return sim.holdEquilibrium();
}

/// The search's observer of final states, told the value tried; none if the search has none.
TrialEndObserver endOf(const SearchSettings& s, double value) {
  if (!s.finalStates) return {};
  return [&s, value](const solver::Simulation& sim, const TrialResult& r) { s.finalStates(value, sim, r); };
}

template <class Result>
void copyBracket(const BisectionResult& b, Result& r) {
  r.found = b.bracketed;
  r.message = b.message;
  r.stableEnd = b.stableEnd;
  r.failingEnd = b.failingEnd;
}

/// Narrows a known [stable, failing] bracket to `width` and records it in r.
void narrowInto(CriticalResult& r, const std::function<bool(double)>& f, double stable, double failing, double width,
                int threads) {
  const BisectionResult b = narrowBracket(f, stable, failing, width, threads);
  copyBracket(b, r);
  r.critical = b.critical;
}

/// The search's accounting: its forward runs, every trial by value, and its wall time.
template <class Result>
Result& account(Result& r, CountedVerdict& v, std::chrono::steady_clock::time_point t0) {
  r.runs = v.runs;
  r.trials = v.sortedTrials();
  r.wallTime = secondsSince(t0);
  return r;
}

}  // namespace

CriticalResult criticalCohesion(const model::Scene& scene, int joint, double frictionDeg, double width,
                                const SearchSettings& s, double initialGuess) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto held = sharedEquilibrium(scene);
  CountedVerdict stableAt{[&](double c) {
    model::Scene trial = scene;
    trial.joints[joint].cohesion = c;
    trial.joints[joint].frictionAngle = degToRad(frictionDeg);
    return judgeStability(trial, s.verdict, held ? &*held : nullptr, endOf(s, c));
  }, s, "c (Pa)", width};
  const std::function<bool(double)> f = std::ref(stableAt);
  CriticalResult r;
  if (stableAt(0)) {
    r.found = true;
    r.message = "stable without cohesion at this friction angle";
  } else {
    // Bracket: double the cohesion until the scene holds.
    double failing = 0, hi = initialGuess;
    while (!stableAt(hi) && hi < 1e12) {
      failing = hi;
      hi *= 2;
    }
    if (hi >= 1e12) {
      r.message = "fails even with a cohesion of 1e12 Pa: strength cannot hold this scene";
    } else {
      narrowInto(r, f, hi, failing, width, s.threads);
    }
  }
  return account(r, stableAt, t0);
}

CriticalResult criticalFriction(const model::Scene& scene, int joint, double cohesion, double width,
                                const SearchSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto held = sharedEquilibrium(scene);
  CountedVerdict stableAt{[&](double phiDeg) {
    model::Scene trial = scene;
    trial.joints[joint].cohesion = cohesion;
    trial.joints[joint].frictionAngle = degToRad(phiDeg);
    return judgeStability(trial, s.verdict, held ? &*held : nullptr, endOf(s, phiDeg));
  }, s, "φ (°)", width};
  const BisectionResult b = bisect(std::ref(stableAt), 0.0, 89.9, width, s.threads);
  CriticalResult r;
  copyBracket(b, r);
  r.critical = b.critical;
  if (!r.found) {
    r.message = b.stableEnd == 0 ? "stable even with φ = 0 at this cohesion" : "fails even with φ = 89.9°";
    if (b.stableEnd == 0) {  // holds without friction: the critical angle is 0
      r.found = true;
      r.critical = 0;
    }
  }
  return account(r, stableAt, t0);
}

CriticalResult criticalSeismicCoefficient(const model::Scene& scene, int direction, double width,
                                          const SearchSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  // The load enters each trial's own equilibrium (model/seismic.hpp): none is shared.
  CountedVerdict stableAt{[&](double k) {
    model::Scene trial = scene;
    trial.seismic.kh = direction * k;
    trial.seismic.ground = {};  // k_y belongs to the slope, not to a record
    // Told k_h as applied; k = 0 is one trial whatever the direction (not −0 and 0).
    return judgeStability(trial, s.verdict, nullptr, endOf(s, k == 0 ? 0.0 : direction * k));
  }, s, "k_h (g)", width};
  const std::function<bool(double)> f = std::ref(stableAt);
  constexpr double kFirst = 0.05, kLargest = 2.0;
  CriticalResult r;
  if (!stableAt(0)) {
    r.message = "the slope fails without seismic loading (k_h = 0): it has no yield acceleration";
  } else {
    double stable = 0, k = kFirst;
    while (stableAt(k)) {
      stable = k;
      if (k >= kLargest) break;
      k = std::min(2 * k, kLargest);
    }
    if (stable >= kLargest) {
      r.message = std::string("stable up to k_h = 2 along ") + (direction > 0 ? "+x" : "-x") +
                  ": does the slope face the other way (--direction)?";
      r.stableEnd = stable;
    } else {
      if (width > 0) {
        narrowInto(r, f, stable, k, width, s.threads);
      } else {
        // To 1e-3 of k_y itself: narrow, and again while the bracket is wider than that of its
        // new failing end (a small k_y is found in a bracket that began at 0.05).
        double failing = k;
        do {
          narrowInto(r, f, stable, failing, 1e-3 * failing, s.threads);
          stable = r.stableEnd;
          failing = r.failingEnd;
        } while (r.found && failing - stable > 1e-3 * failing * (1 + 1e-9));
      }
    }
  }
  return account(r, stableAt, t0);
}

std::vector<CurvePoint> criticalCurve(const model::Scene& scene, int joint, double phiMinDeg, double phiMaxDeg,
                                      int n, double width, const SearchSettings& s, TaskFarm* farm) {
  std::vector<CurvePoint> curve(std::max(2, n));
  std::vector<int> points(curve.size());
  for (size_t i = 0; i < curve.size(); ++i) {
    curve[i].frictionDeg = phiMinDeg + (phiMaxDeg - phiMinDeg) * i / (curve.size() - 1);
    points[i] = static_cast<int>(i);
  }
  SearchSettings single = s;
  single.threads = 1;  // parallel over points instead: a point's search is the same on any farm
  single.progress = nullptr;  // the curve reports points
  int finished = 0;
  single.finalStates = {};
  std::unique_ptr<TaskFarm> own;
  if (!farm) own = makeThreadFarm(s.threads), farm = own.get();
  farm->run(
      points,
      [&](int i) {
        const CriticalResult r = criticalCohesion(scene, joint, curve[i].frictionDeg, width, single);
        BytePacker b;
        b.put(r.found).put(r.critical).put(r.stableEnd).put(r.failingEnd).put(r.runs).put(r.wallTime).put(r.message);
        return b.bytes();
      },
      [&](int i, const TaskResult& bytes) {
        ByteUnpacker b(bytes);
        CriticalResult& r = curve[i].cohesion;
        r.found = b.get<bool>();
        r.critical = b.get<double>();
        r.stableEnd = b.get<double>();
        r.failingEnd = b.get<double>();
        r.runs = b.get<int>();
        r.wallTime = b.get<double>();
        r.message = b.getString();
        if (s.progress) {
          char text[96];
          std::snprintf(text, sizeof text, "c = %.6g Pa at φ = %.4g°", r.critical, curve[i].frictionDeg);
          s.progress({"points", ++finished, static_cast<int>(curve.size()), text, {}});
        }
      });
  return curve;
}

FactorOfSafetyResult factorOfSafety(const model::Scene& scene, const std::vector<int>& joints, double width,
                                    const SearchSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<int> reduced = joints;
  if (reduced.empty())
    for (size_t j = 0; j < scene.joints.size(); ++j) reduced.push_back(static_cast<int>(j));
  const auto held = sharedEquilibrium(scene);
  CountedVerdict stableAt{[&](double f) {
    model::Scene trial = scene;
    for (int j : reduced) trial.joints[j] = scene.joints[j].reducedBy(f);
    return judgeStability(trial, s.verdict, held ? &*held : nullptr, endOf(s, f));
  }, s, "F", width};
  FactorOfSafetyResult r;
  // Bracket from F = 1 by factors of 1.5 (stable: raise F; failing: lower it).
  double stable = 0, failing = 0, f = 1;
  const bool atOne = stableAt(f);
  (atOne ? stable : failing) = f;
  for (int k = 0; k < 40 && (stable == 0 || failing == 0); ++k) {
    f = atOne ? f * 1.5 : f / 1.5;
    (stableAt(f) ? stable : failing) = f;
  }
  if (stable == 0 || failing == 0) {
    r.message = stable == 0 ? "fails at every reduction factor tried (down to 1.5^-40)"
                            : "stable at every reduction factor tried (up to 1.5^40)";
  } else {
    const BisectionResult b = narrowBracket(std::ref(stableAt), stable, failing, width, s.threads);
    copyBracket(b, r);
    r.factor = b.critical;
    r.rounds = b.rounds;
  }
  return account(r, stableAt, t0);
}

}  // namespace ddaslope::calibration
