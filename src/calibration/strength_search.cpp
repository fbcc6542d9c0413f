#include "ddaslope/calibration/strength_search.hpp"

#include <algorithm>
#include <cstdio>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <system_error>
#include <thread>

#include "ddaslope/calibration/bisection.hpp"
#include "ddaslope/core/byte_record.hpp"
#include "ddaslope/core/cancellation.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/types.hpp"
#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::calibration {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Wraps a verdict function so that every forward run is counted, recorded and reported
/// (thread-safe). The function is told the value and how many times the case's duration to run.
struct CountedVerdict {
  /// `quantity`: the searched value's symbol for the progress line; `width`: the bracket the
  /// search narrows to (≤ 0: 1e-3 of its failing end), for the estimate of the runs left.
  CountedVerdict(std::function<TrialResult(double, double)> v, const SearchSettings& s, const char* quantity,
                 double width)
      : verdict(std::move(v)),
        progress(s.progress),
        quantity(quantity),
        width(width),
        perRound(std::max(1, s.threads)),
        lookAhead(s.lookAhead),
        inTurn(s.narrowInTurn) {}
  std::function<TrialResult(double, double)> verdict;
  io::ProgressSink progress;
  const char* quantity;
  double width;
  int perRound;
  bool lookAhead;  ///< SearchSettings::lookAhead
  bool inTurn;  ///< SearchSettings::narrowInTurn
  /// The duration factor of the runs being made: 1, or kReRunLength while a review re-runs trials.
  double length = 1;
  std::atomic<int> runs{0};
  std::mutex mutex;
  std::vector<TrialRecord> trials;
  /// Undecided verdicts in a row, as the bracketing loops see them (they run one trial at a time).
  int undecidedInARow = 0;
  bool operator()(double x) {
    ++runs;
    return record(x, verdict(x, length));
  }
  /// A run ahead of need (narrowAhead, AheadRunner, BranchesAhead): its outcome is kept aside,
  /// and counted and recorded only when the search takes it. A value whose outcome is aside, or
  /// whose run is under way on another thread, is not run again: that outcome is shared (a run
  /// stopped before it ends is made again by whoever still needs it). A caller waiting for
  /// another's run still stops when its own run is cancelled. `startNone`, if set, forbids
  /// starting a run (Cancelled instead); `made` counts the runs this call started.
  bool runAhead(double x, const std::atomic<bool>* startNone = nullptr, int* made = nullptr) {
    DDASLOPE_ASSERT(length == 1, "runs ahead are made at the case's duration only");
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
      if (const auto at = aside.find(x); at != aside.end()) return at->second.stable;
      if (!underWay.count(x)) break;
      ended.wait_for(lock, std::chrono::milliseconds(10));
      throwIfCancelled();
    }
    if (startNone && *startNone) throw Cancelled{};
    underWay.insert(x);
    ++madeAhead;
    if (made) ++*made;
    lock.unlock();
    // However the run ends, its value is no longer under way, and a waiter is told.
    struct Ended {
      CountedVerdict& v;
      double x;
      ~Ended() {
        const std::lock_guard<std::mutex> lock(v.mutex);
        v.underWay.erase(x);
        v.ended.notify_all();
      }
    };
    TrialResult r;
    {
      const Ended end{*this, x};
      r = verdict(x, length);
      const std::lock_guard<std::mutex> guard(mutex);
      aside[x] = r;
    }
    return r.stable;
  }
  void take(double x) {
    ++runs;
    // From aside to the record under one lock: endsRound(x) finds it in one or the other.
    const std::lock_guard<std::mutex> lock(mutex);
    const auto at = aside.find(x);
    DDASLOPE_ASSERT(at != aside.end(), "a run taken was made ahead");
    TrialResult r = std::move(at->second);
    aside.erase(at);
    ++takenAhead;
    recordLocked(x, std::move(r));
  }
  /// Whether the search runs trials ahead of need now: asked to, and not re-running trials longer.
  bool looksAhead() const { return lookAhead && length == 1; }
  /// This verdict as the look-ahead machinery calls it (bisection.hpp).
  LookAheadVerdict ahead() {
    return {[this](double x) { return runAhead(x); }, [this](double x) { take(x); },
            [this](double x) { return endsRound(x); }};
  }
  /// Whether the failure of the run at x just made ends its narrowing round: the slope passed
  /// the failure displacement after t = 0, which a longer run does not undo. A failure while
  /// settling, or on the trend of a motion, leaves the round's values beyond it to run as checks
  /// that the verdicts are monotone: a trend may be misjudged (the review re-runs it), and a
  /// failure while settling may not be monotone in the value searched (docs/calibration.md,
  /// "Where contradictions can be seen"). A run made ahead is read from aside, or from the record
  /// if already taken; `recorded`: a run just recorded (operator()), read from the record alone.
  bool endsRound(double x, bool recorded = false) {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto proven = [](const TrialResult& r) {
      return !r.stable && r.rule == VerdictRule::PassedDisplacement;
    };
    if (const auto at = aside.find(x); !recorded && at != aside.end()) return proven(at->second);
    for (auto t = trials.rbegin(); t != trials.rend(); ++t)
      if (t->value == x) return proven(t->result);
    return false;
  }
  /// Counts a narrowing's or a bracketing loop's runs started ahead of need.
  void countAhead(int made) { runsAhead += made; }
  int runsAhead = 0;  ///< runs started ahead of need (a diagnostic: a shared run may count twice)
  /// Runs made by runAhead (stopped or not) that the search did not take.
  int runsAheadUnused() const { return madeAhead - takenAhead; }
  /// Runs made ahead of need and not taken (yet), by value.
  std::map<double, TrialResult> aside;
  /// Values whose runAhead is under way; `ended` is told when one ends (or stops).
  std::set<double> underWay;
  std::condition_variable ended;
  int madeAhead = 0, takenAhead = 0;
  /// The trials by value: the record does not depend on which thread finished first.
  std::vector<TrialRecord> sortedTrials() {
    std::sort(trials.begin(), trials.end(), [](const TrialRecord& a, const TrialRecord& b) {
      return a.value < b.value || (a.value == b.value && !a.rerun && b.rerun);
    });
    return trials;
  }

 private:
  bool record(double x, TrialResult r) {
    const std::lock_guard<std::mutex> lock(mutex);
    return recordLocked(x, std::move(r));
  }
  bool recordLocked(double x, TrialResult r) {
    undecidedInARow = r.undecided ? undecidedInARow + 1 : 0;
    const bool stable = r.stable;
    trials.push_back({x, std::move(r), length > 1});
    if (progress) report(x, stable ? "stable" : trials.back().result.undecided ? "undecided" : "fails");
    return stable;
  }

  /// The tightest bracket so far (a stable and a failing trial closest together) and the runs a
  /// k-section still needs to narrow it to the width.
  void report(double last, const char* lastVerdict) {
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
      std::snprintf(text, sizeof text, "%s %.6g %s", quantity, last, lastVerdict);
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

/// The verdict of a trial `length` times the case's duration: a first run (length 1) runs a
/// trend failure on to the review's re-run length itself, so that the review need not run it
/// again from t = 0 (VerdictSettings::runOnLength); a re-run is judged at its own length.
VerdictSettings verdictOf(const SearchSettings& s, double length) {
  VerdictSettings v = s.verdict;
  v.runOnLength = length == 1 ? kReRunLength : 1;
  v.length = length;
  return v;
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

/// Narrows [stable, failing] to `width` with the search's verdict (narrowAhead): a round's values
/// at once, the round taken up to a failure that ends it (CountedVerdict::endsRound); looking
/// ahead unless the search was told not to (SearchSettings::lookAhead). In turn, the same trials
/// (CountedVerdict::inTurn), or when runs are made at another length than the case's, which are
/// not kept aside by value.
BisectionResult narrow(CountedVerdict& v, double stable, double failing, double width, int threads) {
  if (v.inTurn || v.length != 1)
    return narrowBracket(std::ref(v), stable, failing, width, threads, true,
                         [&v](double x) { return v.endsRound(x, true); });
  const BisectionResult b = narrowAhead(v.ahead(), stable, failing, width, threads, v.looksAhead());
  v.countAhead(b.runsAhead);
  return b;
}

/// bisect, narrowing as `narrow` does.
BisectionResult bisectWith(CountedVerdict& v, double lo, double hi, double width, int threads) {
  return bisect(std::ref(v), lo, hi, width, threads,
                [&v](double stable, double failing, double w, int k) { return narrow(v, stable, failing, w, k); });
}

/// A bracketing loop's trials on the search's verdict, run ahead of need (AheadRunner) unless
/// `narrow` would not look ahead; its unused runs counted when it closes.
class Bracketing {
 public:
  Bracketing(CountedVerdict& v, int threads)
      : v_(v), verdict_(v.ahead()), runner_(verdict_, v.looksAhead() ? threads : 1) {}
  ~Bracketing() {
    runner_.stop();
    v_.countAhead(runner_.runsAhead());
  }
  Bracketing(const Bracketing&) = delete;
  Bracketing& operator=(const Bracketing&) = delete;
  /// The verdict at x; the spare threads meanwhile run `hoped`, the values the loop takes next if
  /// it goes on.
  bool take(double x, std::vector<double> hoped) { return runner_.take(x, std::move(hoped)); }

 private:
  CountedVerdict& v_;
  LookAheadVerdict verdict_;
  AheadRunner runner_;
};

/// The first trials of a strength reduction on two threads or more, F = 1 and 1.5 at once, with
/// the spare thread, once 1.5 is done, running ahead the trials the search makes next:
/// - if 1.5 stands, F = 1 stands too (verdicts are monotone), and the search goes up by 1.5: the
///   spare thread runs 2.25, 3.375, … until one fails;
/// - if 1.5 fails, first the narrowing's first round of [1, 1.5] (the search's next trials if
///   F = 1 stands: a slope near its strength settles slowly at F = 1, while these, well beyond
///   it, fail fast), then the trials the search makes if F = 1 fails: the bracketing down by 1.5
///   and the narrowing's rounds, each round's values one after another. A slope whose F lies just
///   below 1 (a back-analysis of a failure is built so) has a slow trial at F = 1, a slide
///   creeping to the failure displacement, and quick trials below it.
/// Once F = 1 is decided the spare thread starts no more runs (the search's own threads go on, and
/// a third would slow them down); a run under way of the branch F = 1 chose ends, for the search
/// to take, and one of the other branch is stopped. The search takes the same trials in the same
/// order; the runs it does not take are counted unused.
class BranchesAhead {
 public:
  BranchesAhead(CountedVerdict& v, double width, int threads) : v_(v) {
    try {
      spare_ = std::thread([this, width, threads] { runBranches(width, threads); });
    } catch (const std::system_error&) {
      // No thread to spare: the first trials run as a search without runs ahead runs them.
    }
  }
  ~BranchesAhead() { stop(); }
  BranchesAhead(const BranchesAhead&) = delete;
  BranchesAhead& operator=(const BranchesAhead&) = delete;
  /// The verdicts at 1 and 1.5, taken (recorded) in that order. F = 1 runs on the calling thread.
  std::vector<bool> first() {
    bool one = false;
    try {
      one = v_.runAhead(1.0);
    } catch (...) {
      stop();
      throw;
    }
    // Set before the branch is read: a branch entered after this starts no run (runAhead's
    // startNone), one entered before is seen here.
    decided_ = true;
    const bool oneAndAHalf = v_.runAhead(1.5);
    if (branch_ == (one ? Branch::IfOneFails : Branch::IfOneStands)) stop();
    v_.take(1.0);
    v_.take(1.5);
    return {one, oneAndAHalf};
  }
  /// Stops the runs still under way (the search has taken what it needs) and counts the runs
  /// the spare thread started.
  void stop() {
    stop_ = true;
    if (spare_.joinable()) {
      spare_.join();
      v_.countAhead(made_);
    }
  }

 private:
  enum class Branch { Both, IfOneStands, IfOneFails };

  void runBranches(double width, int threads) {
    const CancellationScope scope(stop_);
    const auto run = [this](double x) { return v_.runAhead(x, &decided_, &made_); };
    try {
      const bool oneAndAHalfStands = run(1.5);
      branch_ = Branch::IfOneStands;
      if (oneAndAHalfStands) {
        // The values factorOfSafetyOf's bracketing loop takes, computed as it computes them.
        double f = 1.5;
        for (int k = 0; k < 40; ++k)
          if (!run(f = f * 1.5)) break;
        return;
      }
      for (const double x : roundValues(1.0, 1.5, threads))
        if (!run(x) && v_.endsRound(x)) break;
      branch_ = Branch::IfOneFails;
      double stable = 0, failing = 1, f = 1;
      for (int k = 0; k < 40 && stable == 0; ++k) {
        f /= 1.5;
        (run(f) ? stable : failing) = f;
      }
      if (stable > 0)
        narrowBracket(run, stable, failing, width, threads, true, [this](double x) { return v_.endsRound(x); });
    } catch (...) {
      // Stopped, or an error of a run that the search meets again if it takes that run.
    }
  }

  CountedVerdict& v_;
  std::atomic<bool> stop_{false}, decided_{false};
  std::atomic<Branch> branch_{Branch::Both};
  int made_ = 0;  ///< runs the spare thread started (read after the join)
  std::thread spare_;
};

/// Narrows a known [stable, failing] bracket to `width` and records it in r.
void narrowInto(CriticalResult& r, CountedVerdict& v, double stable, double failing, double width, int threads) {
  const BisectionResult b = narrow(v, stable, failing, width, threads);
  copyBracket(b, r);
  r.critical = b.critical;
}

/// The search's accounting: its forward runs, every trial by value, and its wall time.
template <class Result>
Result& account(Result& r, CountedVerdict& v, std::chrono::steady_clock::time_point t0) {
  r.runs = v.runs;
  r.runsAhead = v.runsAhead;
  r.runsAheadUnused = v.runsAheadUnused();
  r.trials = v.sortedTrials();
  r.wallTime = secondsSince(t0);
  return r;
}

/// A range of mixed verdicts this narrow (against the value) is an answer, given as that range.
constexpr double kMixedRangeTolerance = 0.01;

/// Why a bracketing loop stopped on undecided verdicts.
constexpr const char* kUndecidedBracket =
    "two trials in a row were undecided (small motions that neither grew nor stopped within the runs' extensions): "
    "no bracket; see the trials, and lengthen analysis.duration or look at the moving blocks with `ddaslope run`";

/// Why strength reduction found no F: at 1.5^-40 every reduced joint has 1.1e7 times its cohesion,
/// tensile strength and tan φ, so what still moves is not held by their strength.
/// `strongest`: the trial at the least factor tried. Where it failed while settling by no more
/// than the blocks' elastic settlement could be (`elasticSettlement`), the motion may be that
/// settlement (a soft rock's), which no strength changes: said with its size, and `spread`, how
/// far the settling motions of all the trials spread about it.
std::string failsAtEveryFactor(const std::string& caseLabel, const TrialResult* strongest, double spread,
                               double elasticSettlement) {
  std::string m = "fails at every reduction factor tried, down to 1.5^-40 (c, tensile strength and tan φ multiplied by "
                  "1.1e7): no strength of the reduced joints holds this scene. Something their strength does not resist "
                  "moves it: a block that topples or lifts off joints with no tensile strength to multiply, or one "
                  "moving on joints not reduced";
  if (strongest && strongest->rule == VerdictRule::MovedWhileSettling &&
      strongest->settlingDisplacement <= elasticSettlement) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "; or the blocks' own settlement: at the least factor the scene still moved %.3g m while it settled "
                  "(%s), against the failure displacement %.3g m%s. Soft blocks (a low young_modulus) settle "
                  "elastically by that much whatever the joints' strength: compare analysis.failure_displacement or "
                  "the modulus",
                  strongest->settlingDisplacement, strongest->movedMost.c_str(), strongest->failureDisplacement,
                  spread < 0.01 ? ", as much as at every other factor (within 1 %)" : "");
    m += buf;
  }
  return m + "; see the mechanism with `ddaslope run " + caseLabel + " --at-fos 0.01`";
}

/// The verdict in force at each value tried (a re-run's replaces the first run's), by value.
std::map<double, TrialResult> verdictsByValue(const std::vector<TrialRecord>& trials) {
  std::map<double, TrialResult> by;
  for (const TrialRecord& t : trials)
    if (t.rerun || !by.count(t.value)) by[t.value] = t.result;
  return by;
}

/// The review every search ends with (TrialReview). `stableBelow`: whether the stable side is
/// that of the smaller values (F, k_h) or of the larger (c, φ); `domain`: the values a trial may
/// take. `setAnswer` records a new bracket.
template <class Result>
void reviewTrials(Result& r, CountedVerdict& v, bool stableBelow, std::pair<double, double> domain, double width,
                  int threads, const std::function<void(double stable, double failing)>& setAnswer) {
  // Oriented so that stable values lie below failing ones.
  const auto o = [&](double x) { return stableBelow ? x : -x; };
  std::set<double> rerun;
  std::set<std::pair<double, double>> narrowed;
  bool probed = false, changed = false;
  // A trend failure run on in place to the re-run length (TrialResult::runOn) is its own re-run.
  const auto takeRunsOn = [&] {
    for (const TrialRecord& t : v.trials)
      if (t.result.runOn) rerun.insert(t.value);
  };
  const auto reRun = [&](const std::vector<double>& values) {
    // A trial that moved the failure displacement while it settled was decided before t = 0, by
    // the equilibrium alone, which the run's length does not enter: run longer, it fails on the
    // same path at the same step. Its verdict stands as its own re-run.
    const std::map<double, TrialResult> by = verdictsByValue(v.trials);
    std::vector<double> run;
    for (double x : values)
      if (by.at(x).rule != VerdictRule::MovedWhileSettling) run.push_back(x);
    v.length = kReRunLength;
    evaluateAll(std::ref(v), run, threads);
    v.length = 1;
    r.review.reruns += static_cast<int>(run.size());
    rerun.insert(values.begin(), values.end());
    changed = true;
  };
  for (int round = 0; round < 12; ++round) {
    takeRunsOn();
    const std::map<double, TrialResult> by = verdictsByValue(v.trials);
    bool anyStable = false;
    double hs = -INFINITY, lf = INFINITY, lfAny = INFINITY, hsValue = 0, lfValue = 0, lfAnyValue = 0;
    for (const auto& [x, t] : by) {
      if (t.stable && o(x) > hs) hs = o(x), hsValue = x, anyStable = true;
      if (!t.stable && !t.undecided && o(x) < lf) lf = o(x), lfValue = x;
      if (!t.stable && o(x) < lfAny) lfAny = o(x), lfAnyValue = x;
    }
    if (!anyStable || lfAny == INFINITY) return;  // nothing bracketed: the search's own message stands
    const double target = width > 0 ? width : 1e-3 * std::abs(lfAnyValue);
    if (hs > lfAny) {
      // A failing (or undecided) trial on the stable side of a stable one. Re-run, longer, every
      // trial between them that has not been re-run yet.
      std::vector<double> again;
      for (const auto& [x, t] : by)
        if (o(x) >= lfAny && o(x) <= hs && !rerun.count(x)) again.push_back(x);
      if (!again.empty() && round < 10) {
        reRun(again);
        continue;
      }
      // The answer lies where the verdicts are mixed: between the last stable trial below the
      // first failure and the first failing trial above the last stable one.
      double below = -INFINITY, above = INFINITY, belowValue = lfAnyValue, aboveValue = hsValue;
      for (const auto& [x, t] : by) {
        if (t.stable && o(x) < lfAny && o(x) > below) below = o(x), belowValue = x;
        if (!t.stable && o(x) > hs && o(x) < above) above = o(x), aboveValue = x;
      }
      r.review.contradiction = true;
      // Trials that disagree by less than the precision asked for, or within a mixed range of 1 %
      // of the value (DDA near a critical strength: which block gives way first), do not unsettle
      // the answer, given over the whole mixed range.
      const double mixed = std::abs(aboveValue - belowValue);
      r.found = hs - lfAny <= target * (1 + 1e-9) ||
                mixed <= kMixedRangeTolerance * std::max(std::abs(aboveValue), std::abs(belowValue));
      setAnswer(belowValue, aboveValue);
      std::ostringstream m;
      m << "verdicts contradict: stable at " << hsValue << " but " << (by.at(lfAnyValue).undecided ? "undecided" : "failing")
        << " at " << lfAnyValue << " (" << v.quantity << "), ";
      if (by.at(lfAnyValue).rule == VerdictRule::MovedWhileSettling)
        m << "where it moved the failure displacement while it settled, before t = 0, which no run length changes; ";
      else if (rerun.count(lfAnyValue))
        m << "also when run " << kReRunLength << " times longer; ";
      else
        m << "and the review's rounds of re-runs are spent; ";
      if (r.found)
        m << "they are closer than the bracket width asked for (" << target << ") or than 1 % of the value, so the "
          << "answer is given over the range that holds them, [" << std::min(belowValue, aboveValue) << ", "
          << std::max(belowValue, aboveValue) << "]";
      else
        m << "the answer lies between " << belowValue << " and " << aboveValue << " and this search cannot say where "
          << "(see the trials)";
      r.message = m.str();
      return;
    }
    // The bracket's failing end, if decided on the trend of a motion (not on its size), is run
    // again longer, with every other trial so decided on the failing side: a one-thread bisection
    // never tries a value that could contradict them.
    const TrialResult& end = by.at(lfAnyValue);
    const auto onTrend = [](const TrialResult& t) { return t.rule == VerdictRule::StillMoving || t.undecided; };
    if (!rerun.count(lfAnyValue) && onTrend(end)) {
      std::vector<double> again;
      for (const auto& [x, t] : by)
        if (o(x) >= lfAny && onTrend(t) && !rerun.count(x)) again.push_back(x);
      reRun(again);
      continue;
    }
    if (changed && std::abs(lfAnyValue - hsValue) > target * (1 + 1e-9)) {
      // Re-runs moved the bracket: narrow it again (never twice between the same ends), review again.
      if (!narrowed.insert({hsValue, lfAnyValue}).second) break;
      narrow(v, hsValue, lfAnyValue, target, threads);
      continue;
    }
    if (end.undecided && lf == INFINITY && !probed) {
      // Undecided trials and no decided failure beyond them: look further out for one, so that
      // the bracket reported is one the trials vouch for.
      probed = true;
      double far = lfAnyValue;
      for (const auto& [x, t] : by)
        if (t.undecided && o(x) > o(far)) far = x;
      const double step = std::max(std::abs(far - hsValue), target);
      for (int k = 0; k < 4; ++k) {
        const double x = far + (stableBelow ? 1 : -1) * step * std::pow(2.0, k);
        if (x < domain.first || x > domain.second) break;
        if (!v(x) && !verdictsByValue(v.trials).at(x).undecided) break;
      }
      continue;
    }
    if (changed) {
      r.found = true;
      setAnswer(hsValue, lfAnyValue);
    }
    if (end.undecided && !(lf < INFINITY && std::abs(lfValue - hsValue) <= target * (1 + 1e-9))) {
      r.review.undecided = true;
      r.found = false;
      std::ostringstream m;
      m << "undecided at " << lfAnyValue << " (" << v.quantity << "): a small motion that neither grew nor stopped "
        << "within the run's extensions; the slope stands at " << hsValue;
      if (lf < INFINITY) m << " and fails at " << lfValue << ": the answer lies between them";
      else m << ", and no trial beyond it was decided failing";
      r.message = m.str();
      r.stableEnd = hsValue;
      r.failingEnd = lf < INFINITY ? lfValue : lfAnyValue;
    }
    return;
  }
  r.found = false;
  r.message = "the review of the trials did not settle within its rounds (see the trials)";
}

}  // namespace

CriticalResult criticalCohesion(const model::Scene& scene, int joint, double frictionDeg, double width,
                                const SearchSettings& s, double initialGuess) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto held = sharedEquilibrium(scene);
  CountedVerdict stableAt{[&](double c, double length) {
    model::Scene trial = scene;
    trial.settings.duration *= length;
    trial.joints[joint].cohesion = c;
    trial.joints[joint].frictionAngle = degToRad(frictionDeg);
    return judgeStability(trial, verdictOf(s, length), held ? &*held : nullptr, endOf(s, c));
  }, s, "c (Pa)", width};
  CriticalResult r;
  double failing = 0, hi = initialGuess;
  bool holdsWithout = false;
  {
    // Bracket: double the cohesion until the scene holds.
    Bracketing b(stableAt, s.threads);
    holdsWithout = b.take(0, {hi, 2 * hi});
    if (!holdsWithout)
      while (!b.take(hi, {2 * hi, 4 * hi}) && hi < 1e12 && stableAt.undecidedInARow < 2) {
        failing = hi;
        hi *= 2;
      }
  }
  if (holdsWithout) {
    r.found = true;
    r.message = "stable without cohesion at this friction angle";
  } else {
    if (stableAt.undecidedInARow >= 2) {
      r.message = kUndecidedBracket;
    } else if (hi >= 1e12) {
      r.message = "fails even with a cohesion of 1e12 Pa: strength cannot hold this scene";
    } else {
      narrowInto(r, stableAt, hi, failing, width, s.threads);
    }
  }
  reviewTrials(r, stableAt, false, {0.0, 1e12}, width, s.threads, [&](double stable, double failing) {
    r.stableEnd = stable, r.failingEnd = failing, r.critical = 0.5 * (stable + failing);
  });
  return account(r, stableAt, t0);
}

CriticalResult criticalFriction(const model::Scene& scene, int joint, double cohesion, double width,
                                const SearchSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto held = sharedEquilibrium(scene);
  CountedVerdict stableAt{[&](double phiDeg, double length) {
    model::Scene trial = scene;
    trial.settings.duration *= length;
    trial.joints[joint].cohesion = cohesion;
    trial.joints[joint].frictionAngle = degToRad(phiDeg);
    return judgeStability(trial, verdictOf(s, length), held ? &*held : nullptr, endOf(s, phiDeg));
  }, s, "φ (°)", width};
  const BisectionResult b = bisectWith(stableAt, 0.0, 89.9, width, s.threads);
  CriticalResult r;
  copyBracket(b, r);
  r.critical = b.critical;
  if (!r.found) {
    r.message = b.stableEnd == 0 ? "stable even with φ = 0 at this cohesion"
                                 : "fails even with φ = 89.9°: strength cannot hold this scene (a block that topples or "
                                   "lifts off, or one moving on other joints)";
    if (b.stableEnd == 0) {  // holds without friction: the critical angle is 0
      r.found = true;
      r.critical = 0;
    }
  }
  reviewTrials(r, stableAt, false, {0.0, 89.9}, width, s.threads, [&](double stable, double failing) {
    r.stableEnd = stable, r.failingEnd = failing, r.critical = 0.5 * (stable + failing);
  });
  return account(r, stableAt, t0);
}

CriticalResult criticalJrc(const model::Scene& scene, int joint, double width, const SearchSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto held = sharedEquilibrium(scene);
  CountedVerdict stableAt{[&](double jrc, double length) {
    model::Scene trial = scene;
    trial.settings.duration *= length;
    trial.joints[joint].bartonBandis->jrc = jrc;
    return judgeStability(trial, verdictOf(s, length), held ? &*held : nullptr, endOf(s, jrc));
  }, s, "JRC", width};
  constexpr double kLargest = 20;
  const BisectionResult b = bisectWith(stableAt, 0.0, kLargest, width, s.threads);
  CriticalResult r;
  copyBracket(b, r);
  r.critical = b.critical;
  if (!r.found) {
    r.message = b.stableEnd == 0 ? "stable even with JRC = 0 (φr alone holds)" : "fails even with JRC = 20";
    if (b.stableEnd == 0) {
      r.found = true;
      r.critical = 0;
    }
  }
  reviewTrials(r, stableAt, false, {0.0, kLargest}, width, s.threads, [&](double stable, double failing) {
    r.stableEnd = stable, r.failingEnd = failing, r.critical = 0.5 * (stable + failing);
  });
  return account(r, stableAt, t0);
}

CriticalResult criticalSeismicCoefficient(const model::Scene& scene, int direction, double width,
                                          const SearchSettings& s, double relativeWidth) {
  const auto t0 = std::chrono::steady_clock::now();
  // The load enters each trial's own equilibrium (model/seismic.hpp): none is shared.
  CountedVerdict stableAt{[&](double k, double length) {
    model::Scene trial = scene;
    trial.settings.duration *= length;
    trial.seismic.kh = direction * k;
    trial.seismic.ground = {};  // k_y belongs to the slope, not to a record
    // Told k_h as applied; k = 0 is one trial whatever the direction (not −0 and 0).
    return judgeStability(trial, verdictOf(s, length), nullptr, endOf(s, k == 0 ? 0.0 : direction * k));
  }, s, "k_h (g)", width};
  constexpr double kFirst = 0.05, kLargest = 2.0;
  CriticalResult r;
  const auto next = [&](double k) { return std::min(2 * k, kLargest); };
  double stable = 0, k = kFirst;
  bool holdsWithout = false;
  {
    // Bracket: double k_h until the slope fails.
    Bracketing b(stableAt, s.threads);
    holdsWithout = b.take(0, {k, next(k)});
    if (holdsWithout)
      while (b.take(k, {next(k), next(next(k))})) {
        stable = k;
        if (k >= kLargest) break;
        k = next(k);
      }
  }
  if (!holdsWithout) {
    r.message = stableAt.undecidedInARow > 0 ? "undecided without seismic loading (k_h = 0): a small motion that "
                                               "neither grew nor stopped; no yield acceleration can be bracketed"
                                             : "the slope fails without seismic loading (k_h = 0): it has no yield acceleration";
  } else {
    if (stable >= kLargest) {
      r.message = std::string("stable up to k_h = 2 along ") + (direction > 0 ? "+x" : "-x") +
                  ": does the slope face the other way (--direction)?";
      r.stableEnd = stable;
    } else {
      if (width > 0) {
        narrowInto(r, stableAt, stable, k, width, s.threads);
      } else {
        // To a fraction of k_y itself: narrow, and again while the bracket is wider than that of
        // its new failing end (a small k_y is found in a bracket that began at 0.05).
        double failing = k;
        do {
          narrowInto(r, stableAt, stable, failing, relativeWidth * failing, s.threads);
          stable = r.stableEnd;
          failing = r.failingEnd;
        } while (r.found && failing - stable > relativeWidth * failing * (1 + 1e-9));
      }
    }
  }
  reviewTrials(r, stableAt, true, {0.0, 2.0}, width, s.threads, [&](double stable, double failing) {
    r.stableEnd = stable, r.failingEnd = failing, r.critical = 0.5 * (stable + failing);
  });
  return account(r, stableAt, t0);
}

CriticalResult criticalSupport(const model::Scene& scene, const std::string& id, double targetFactor, double width,
                               const SearchSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  model::Scene reduced = scene;
  for (size_t j = 0; j < scene.joints.size(); ++j) reduced.joints[j] = scene.joints[j].reducedBy(targetFactor);
  // The support's force enters the equilibrium: none is shared.
  CountedVerdict stableAt{[&](double x, double length) {
    model::Scene trial = reduced;
    trial.settings.duration *= length;
    trial.setSupportQuantity(id, x);
    return judgeStability(trial, verdictOf(s, length), nullptr, endOf(s, x));
  }, s, "support (N/m)", width};
  CriticalResult r;
  constexpr double kLargest = 1e12;
  const model::SupportQuantity quantity = scene.supportQuantity(id);
  const bool load = quantity.kind == model::SupportQuantity::Kind::Load;
  const double own = quantity.value;
  // The first value a bracketing doubles from: a load's own, or a support's (1e5 N/m without one).
  double hi = load ? own : own > 0 && std::isfinite(own) ? own : 1e5;
  double stable = 0, failing = 0;
  bool holdsWithout = false;
  {
    Bracketing b(stableAt, s.threads);
    holdsWithout = b.take(0, {hi, 2 * hi});
    if (holdsWithout && load) {
      // A load the slope stands without: how large may it grow (a surcharge, a berm)?
      while (b.take(hi, {2 * hi, 4 * hi}) && hi < kLargest && stableAt.undecidedInARow < 2) {
        stable = hi;
        hi *= 2;
      }
    } else if (!holdsWithout) {
      while (!b.take(hi, {2 * hi, 4 * hi}) && hi < kLargest && stableAt.undecidedInARow < 2) {
        failing = hi;
        hi *= 2;
      }
    }
  }
  if (holdsWithout && load) {
    r.largestThatHolds = true;
    if (stableAt.undecidedInARow >= 2) {
      r.message = kUndecidedBracket;
    } else if (hi >= kLargest) {
      r.found = true;
      r.critical = r.stableEnd = stable;
      r.message = "holds under every load tried, up to 1e12 N/m: this load does not push the slope towards failure";
    } else {
      narrowInto(r, stableAt, stable, hi, width > 0 ? width : 1e-3 * hi, s.threads);
    }
    reviewTrials(r, stableAt, true, {0.0, kLargest}, width > 0 ? width : 1e-3 * r.failingEnd, s.threads,
                 [&](double stable, double failing) {
                   r.stableEnd = stable, r.failingEnd = failing, r.critical = 0.5 * (stable + failing);
                 });
    return account(r, stableAt, t0);
  }
  if (holdsWithout) {
    r.found = true;
    r.message = "stable without it at this factor of safety";
  } else {
    if (stableAt.undecidedInARow >= 2) {
      r.message = kUndecidedBracket;
    } else if (hi >= kLargest) {
      r.message = load ? "fails without the load and under every load tried, up to 1e12 N/m: this load does not hold "
                         "the slope at this factor of safety"
                       : "fails even with 1e12 N/m: no support of this kind holds the slope at this factor of safety";
    } else {
      const double w = width > 0 ? width : 1e-3 * hi;
      narrowInto(r, stableAt, hi, failing, w, s.threads);
    }
  }
  reviewTrials(r, stableAt, false, {0.0, kLargest}, width > 0 ? width : 1e-3 * r.stableEnd, s.threads,
               [&](double stable, double failing) {
                 r.stableEnd = stable, r.failingEnd = failing, r.critical = 0.5 * (stable + failing);
               });
  return account(r, stableAt, t0);
}

std::vector<CurvePoint> criticalCurve(const model::Scene& scene, int joint, double phiMinDeg, double phiMaxDeg,
                                      int n, double width, const SearchSettings& s, TaskFarm* farm,
                                      const PointScene& sceneAt) {
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
        double crackX = std::numeric_limits<double>::quiet_NaN();
        int runs = 0;
        const CriticalResult r = criticalCohesion(sceneAt ? sceneAt(curve[i].frictionDeg, crackX, runs) : scene, joint,
                                                  curve[i].frictionDeg, width, single);
        BytePacker b;
        b.put(r.found).put(r.critical).put(r.stableEnd).put(r.failingEnd).put(r.runs + runs).put(r.wallTime).put(r.message);
        b.put(crackX);
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
        curve[i].crackX = b.get<double>();
        if (s.progress) {
          char text[96];
          std::snprintf(text, sizeof text, "c = %.6g Pa at φ = %.4g°", r.critical, curve[i].frictionDeg);
          s.progress({"points", ++finished, static_cast<int>(curve.size()), text, {}});
        }
      });
  return curve;
}

namespace {
/// A strength-reduction trial's scene: `joints` (all if empty) reduced by f, run `length` times the
/// case's duration.
model::Scene reducedScene(const model::Scene& scene, const std::vector<int>& joints, double f, double length = 1) {
  model::Scene trial = scene;
  trial.settings.duration *= length;
  if (joints.empty())
    for (model::JointProperties& j : trial.joints) j = j.reducedBy(f);
  for (int j : joints) trial.joints[static_cast<size_t>(j)] = scene.joints[static_cast<size_t>(j)].reducedBy(f);
  return trial;
}
}  // namespace

namespace {
/// The largest settlement of a free block under its own weight, ρ g h² / E (h its height): twice a
/// column's top settlement ρ g h² / 2E, an upper bound. Rigid blocks do not settle.
double elasticSettlementOf(const model::Scene& scene) {
  if (scene.settings.rigidBlocks) return 0;
  double most = 0;
  for (const model::Block& b : scene.blocks) {
    if (b.fixed) continue;
    const model::Material& m = scene.materials[static_cast<size_t>(b.material)];
    const geometry::Aabb box = geometry::boundingBox(b.vertices);
    const double h = box.hi.y() - box.lo.y();
    if (m.youngModulus > 0) most = std::max(most, m.density * scene.gravity.norm() * h * h / m.youngModulus);
  }
  return most;
}
}  // namespace

FactorOfSafetyResult factorOfSafety(const model::Scene& scene, const std::vector<int>& joints, double width,
                                    const SearchSettings& settings) {
  SearchSettings s = settings;
  s.elasticSettlement = elasticSettlementOf(scene);
  const auto held = sharedEquilibrium(scene);
  // The rest of the first trial, at F = 1 (factorOfSafetyOf runs it alone, before any other,
  // when the trials start from it), once that trial stands: where the later trials start with
  // TrialStart::Settled. Held trials run F = 1 beside 1.5 and never touch it.
  std::optional<solver::HeldEquilibrium> settled;
  std::atomic<bool> first{s.trialStart == TrialStart::Settled};
  FactorOfSafetyResult r = factorOfSafetyOf(
      [&](double f, double length) {
        const model::Scene trial = reducedScene(scene, joints, f, length);
        if (first.exchange(false)) {
          const bool keep = held && f == 1 && length == 1;
          TrialResult r = judgeStability(trial, verdictOf(s, length), held ? &*held : nullptr, endOf(s, f), keep ? &settled : nullptr);
          if (!r.stable) settled.reset();
          return r;
        }
        return judgeStability(trial, verdictOf(s, length), settled ? &*settled : held ? &*held : nullptr, endOf(s, f));
      },
      width, s);
  r.trialStart = settled ? TrialStart::Settled : TrialStart::Held;
  return r;
}

StrengthReductionCheck strengthReductionTrial(const model::Scene& scene, const std::vector<int>& joints, double f,
                                              const SearchSettings& s) {
  const auto held = sharedEquilibrium(scene);
  StrengthReductionCheck check;
  // As factorOfSafety's trials: the one at F = 1 from every contact held; the others, when asked,
  // from its rest if it stands.
  std::optional<solver::HeldEquilibrium> settled;
  if (held && s.trialStart == TrialStart::Settled && f != 1) {
    check.runs.push_back({1.0, judgeStability(reducedScene(scene, joints, 1), verdictOf(s, 1), &*held, endOf(s, 1), &settled), false});
    if (!check.runs.back().result.stable) settled.reset();
  }
  check.start = settled ? TrialStart::Settled : TrialStart::Held;
  const solver::HeldEquilibrium* start = settled ? &*settled : held ? &*held : nullptr;
  check.runs.push_back({f, judgeStability(reducedScene(scene, joints, f), verdictOf(s, 1), start, endOf(s, f)), false});
  // The review's re-run (reviewTrials): a trend failure has run on to its length already; an
  // undecided small motion runs again that long from t = 0.
  if (check.verdict().undecided)
    check.runs.push_back({f,
                          judgeStability(reducedScene(scene, joints, f, kReRunLength), verdictOf(s, kReRunLength), start,
                                         endOf(s, f)),
                          true});
  return check;
}

std::optional<solver::HeldEquilibrium> settledStart(const model::Scene& scene, const solver::HeldEquilibrium& held,
                                                    const VerdictSettings& verdict) {
  std::optional<solver::HeldEquilibrium> settled;
  if (!judgeStability(scene, verdict, &held, {}, &settled).stable) settled.reset();
  return settled;
}

const char* name(TrialStart start) { return start == TrialStart::Settled ? "settled" : "held"; }

FactorOfSafetyResult factorOfSafetyOf(const std::function<TrialResult(double, double)>& verdict, double width,
                                      const SearchSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  CountedVerdict stableAt{verdict, s, "F", width};
  FactorOfSafetyResult r;
  // Bracket from F = 1 by factors of 1.5 (stable: raise F; failing: lower it).
  double stable = 0, failing = 0, f = 1;
  bool atOne = false;
  std::optional<BranchesAhead> branches;
  if (s.threads >= 2 && s.trialStart == TrialStart::Held) {
    // F = 1 and 1.5 at once: most slopes stand at F = 1, and then the trial at 1.5, which a
    // search one trial at a time makes next, costs no wall time. (A slope failing at F = 1 spends
    // it: that search goes down.) Trials that start from F = 1's rest must wait for it.
    if (stableAt.looksAhead()) branches.emplace(stableAt, width, s.threads);
    const std::vector<bool> first =
        branches ? branches->first() : evaluateAll(std::ref(stableAt), {1.0, 1.5}, 2);
    atOne = first[0];
    (atOne ? stable : failing) = 1;
    if (atOne) f = 1.5, (first[1] ? stable : failing) = f;
    // Undecided trials in a row, as one trial at a time would have counted them.
    const auto undecidedAt = [&](double x) {
      for (const TrialRecord& t : stableAt.trials)
        if (t.value == x && !t.rerun) return t.result.undecided;
      return false;
    };
    stableAt.undecidedInARow = atOne ? static_cast<int>(undecidedAt(1.5)) : static_cast<int>(undecidedAt(1.0));
  } else {
    atOne = stableAt(f);
    (atOne ? stable : failing) = f;
  }
  {
    Bracketing b(stableAt, s.threads);
    const auto next = [&](double x) { return atOne ? x * 1.5 : x / 1.5; };
    for (int k = 0; k < 40 && (stable == 0 || failing == 0) && stableAt.undecidedInARow < 2; ++k) {
      f = next(f);
      (b.take(f, {next(f), next(next(f))}) ? stable : failing) = f;
    }
  }
  // The trial at the least factor, and how far the settling motions of the trials spread about it.
  const auto strongest = [&]() -> const TrialResult* {
    const TrialRecord* least = nullptr;
    for (const TrialRecord& t : stableAt.trials)
      if (!least || t.value < least->value) least = &t;
    return least ? &least->result : nullptr;
  };
  const auto settlingSpread = [&]() -> double {
    double lo = INFINITY, hi = 0;
    for (const TrialRecord& t : stableAt.trials) {
      if (t.result.rule != VerdictRule::MovedWhileSettling) return INFINITY;  // not every factor settled so
      lo = std::min(lo, t.result.settlingDisplacement), hi = std::max(hi, t.result.settlingDisplacement);
    }
    return hi > 0 ? (hi - lo) / hi : INFINITY;
  };
  if (stable == 0 || failing == 0) {
    r.message = stableAt.undecidedInARow >= 2 ? kUndecidedBracket
                : stable == 0                 ? failsAtEveryFactor(s.caseLabel, strongest(), settlingSpread(),
                                                                   s.elasticSettlement)
                                              : "stable at every reduction factor tried (up to 1.5^40)";
  } else {
    const BisectionResult b = narrow(stableAt, stable, failing, width, s.threads);
    copyBracket(b, r);
    r.factor = b.critical;
    r.rounds = b.rounds;
  }
  if (branches) branches->stop();  // before the review changes the runs' length
  reviewTrials(r, stableAt, true, {0.0, 1e6}, width, s.threads, [&](double stable, double failing) {
    r.stableEnd = stable, r.failingEnd = failing, r.factor = 0.5 * (stable + failing);
  });
  return account(r, stableAt, t0);
}

}  // namespace ddaslope::calibration
