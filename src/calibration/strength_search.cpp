#include "ddaslope/calibration/strength_search.hpp"

#include <algorithm>
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

/// Wraps a verdict function so that every forward run is counted and recorded (thread-safe).
struct CountedVerdict {
  explicit CountedVerdict(std::function<TrialResult(double)> v) : verdict(std::move(v)) {}
  std::function<TrialResult(double)> verdict;
  std::atomic<int> runs{0};
  std::mutex mutex;
  std::vector<TrialRecord> trials;
  bool operator()(double x) {
    ++runs;
    TrialResult r = verdict(x);
    const std::lock_guard<std::mutex> lock(mutex);
    trials.push_back({x, r});
    return r.stable;
  }
  /// The trials by value: the record does not depend on which thread finished first.
  std::vector<TrialRecord> sortedTrials() {
    std::sort(trials.begin(), trials.end(), [](const TrialRecord& a, const TrialRecord& b) { return a.value < b.value; });
    return trials;
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
  }};
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
  }};
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
  }};
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
  }};
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
