// Narrowing a bracket with a round's trials at once and runs ahead of need
// (calibration/bisection.hpp, narrowAhead): threads a round leaves idle run the trials the next
// round may need, a round ends at a failure that ends it, and the narrowing takes exactly the
// trials, and gives exactly the bracket, of the k-section in turn (narrowBracket, one value after
// another, each round up to such a failure). The reference is that k-section itself, on verdicts
// whose answers are known by construction.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <chrono>
#include <map>
#include <mutex>
#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <thread>

#include "ddaslope/calibration/bisection.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/core/cancellation.hpp"
#include "ddaslope/core/errors.hpp"

using namespace ddaslope;
using calibration::BisectionResult;

namespace {

/// A verdict for a narrowing: stable below a threshold, except inside optional "islands" of
/// failure below it and of stability above it (verdicts that are not monotone, as DDA's near a
/// critical strength may be); each run sleeps a time of its own, so threads finish out of order.
struct Landscape {
  double threshold = 0.5;
  std::vector<std::pair<double, double>> islands;
  std::map<double, int> sleepMicros;
  int defaultSleep = 200;
  bool stableAt(double x) const {
    bool stable = x < threshold;
    for (const auto& [a, b] : islands)
      if (x >= a && x <= b) stable = !stable;
    return stable;
  }
  /// Whether a failure at x ends its round: about half of them, by a hash of the value's bits.
  bool endsRoundAt(double x) const {
    if (endsNoRound || everyFailureEndsRound) return everyFailureEndsRound;
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    bits *= 0x9e3779b97f4a7c15ULL;
    return (bits >> 61) & 1u;
  }
  bool endsNoRound = false, everyFailureEndsRound = false;
  int sleepAt(double x) const {
    // Deterministic per value: a hash of its bits.
    const auto at = sleepMicros.find(x);
    if (at != sleepMicros.end()) return at->second;
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    bits ^= bits >> 29;
    bits *= 0xbf58476d1ce4e5b9ULL;
    bits ^= bits >> 32;
    return defaultSleep * static_cast<int>(bits % 8);
  }
};

/// A run: sleeps in slices of 100 µs, each a cancellation point, as a simulation's steps are.
bool run(const Landscape& l, double x) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::microseconds(l.sleepAt(x));
  while (std::chrono::steady_clock::now() < end) {
    throwIfCancelled();
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  return l.stableAt(x);
}

/// A look-ahead verdict that records its runs: each runs `verdict` (sleeping as `run` does),
/// counts the ones stopped, and checks that a value is taken only after its run finished.
struct RecordingVerdict {
  explicit RecordingVerdict(const Landscape& l, std::function<bool(double)> verdict) {
    v.run = [this, &l, verdict = std::move(verdict)](double x) {
      try {
        run(l, x);
      } catch (const Cancelled&) {
        const std::lock_guard<std::mutex> lock(m);
        ++cancelled;
        throw;
      }
      const std::lock_guard<std::mutex> lock(m);
      finished.insert(x);
      return verdict(x);
    };
    v.endsRound = [&l](double x) { return l.endsRoundAt(x); };
    v.take = [this](double x) {
      const std::lock_guard<std::mutex> lock(m);
      EXPECT_TRUE(finished.count(x)) << "took " << x << " before its run finished";
      taken.push_back(x);
    };
  }
  RecordingVerdict(const RecordingVerdict&) = delete;
  RecordingVerdict& operator=(const RecordingVerdict&) = delete;
  calibration::LookAheadVerdict v;
  std::mutex m;
  std::set<double> finished;
  std::vector<double> taken;  ///< values in the order handed to `take`
  int cancelled = 0;
};

struct Narrowed {
  BisectionResult result;
  std::vector<double> taken;  ///< values in the order handed to `take`
  int cancelled = 0;
};

Narrowed lookingAhead(const Landscape& l, double stable, double failing, double width, int threads) {
  RecordingVerdict r(l, [&l](double x) { return l.stableAt(x); });
  Narrowed n;
  n.result = calibration::narrowAhead(r.v, stable, failing, width, threads);
  n.taken = r.taken;
  n.cancelled = r.cancelled;
  return n;
}

/// The k-section's rounds in turn: the values of each, in order, up to a failure that ends it.
std::vector<double> kSectionValues(const Landscape& l, double stable, double failing, double width, int threads,
                                   BisectionResult& r) {
  std::vector<double> values;
  r = calibration::narrowBracket(
      [&](double x) {
        values.push_back(x);
        return l.stableAt(x);
      },
      stable, failing, width, threads, true, [&l](double x) { return l.endsRoundAt(x); });
  return values;
}

}  // namespace

// On 300 landscapes (monotone and not, thresholds and islands drawn at random, run times of 0 to
// 1.4 ms, about half the failures ending their rounds, none in one landscape of five), with 2, 3
// and 4 threads: the trials taken, round by round in order, are the k-section's in turn, and so
// are the bracket, its ends, the runs and the rounds, to the last bit.
TEST(LookAhead, TakesTheKSectionsTrialsAndGivesItsBracket) {
  std::mt19937 rng(20261206);
  std::uniform_real_distribution<double> u(0, 1);
  int aheadUsed = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Landscape l;
    l.threshold = 0.05 + 0.9 * u(rng);
    if (trial % 3 != 0) {
      const double a = u(rng), b = a + 0.05 * u(rng);
      l.islands.push_back({a, b});
    }
    const int threads = 2 + trial % 3;
    l.endsNoRound = trial % 5 == 0;
    const double width = 1e-3 * (1 + 9 * u(rng));
    BisectionResult reference;
    const std::vector<double> values = kSectionValues(l, 0, 1, width, threads, reference);
    const Narrowed n = lookingAhead(l, 0, 1, width, threads);
    ASSERT_EQ(n.taken, values) << "trial " << trial;
    EXPECT_EQ(n.result.stableEnd, reference.stableEnd) << trial;
    EXPECT_EQ(n.result.failingEnd, reference.failingEnd) << trial;
    EXPECT_EQ(n.result.critical, reference.critical) << trial;
    EXPECT_EQ(n.result.runs, reference.runs) << trial;
    EXPECT_EQ(n.result.rounds, reference.rounds) << trial;
    EXPECT_TRUE(n.result.bracketed);
    // The bracket against the landscape itself: its ends' verdicts (0 and 1 are given) and width.
    EXPECT_TRUE(n.result.stableEnd == 0 || l.stableAt(n.result.stableEnd)) << trial;
    EXPECT_TRUE(n.result.failingEnd == 1 || !l.stableAt(n.result.failingEnd)) << trial;
    EXPECT_LE(n.result.failingEnd - n.result.stableEnd, width) << trial;
    EXPECT_LE(n.result.runsAheadUsed, n.result.runsAhead);
    aheadUsed += n.result.runsAheadUsed;
  }
  EXPECT_GT(aheadUsed, 0) << "no run ahead was ever used";
}

/// Waits (30 s at most: a test that would hang fails instead) until `flag` is set.
void waitFor(const std::atomic<bool>& flag) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!flag && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(std::chrono::microseconds(200));
}

/// Runs until cancelled (30 s at most), a cancellation point every 100 µs; counts the stop.
void runUntilCancelled(std::atomic<int>& cancelled) {
  try {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < end) {
      throwIfCancelled();
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  } catch (const Cancelled&) {
    ++cancelled;
    throw;
  }
}

// Round 1 of [0, 1] with two threads tries 1/3 and 2/3 (stable below 0.9). The trial at 1/3 ends
// at once; the thread it frees starts the next round assuming 2/3 fails, with 5/9, a run that
// would last 30 s; only then does 2/3 end, stable. That round cannot come: the run at 5/9 is
// stopped and never taken, and the narrowing goes on in [2/3, 1] as the k-section does.
TEST(LookAhead, ARunWhoseRoundCannotComeIsCancelledAndNotTaken) {
  const double fourNinths = 1.0 / 3 + (2.0 / 3 - 1.0 / 3) * 1 / 3;  // as the narrowing computes them
  const double fiveNinths = 1.0 / 3 + (2.0 / 3 - 1.0 / 3) * 2 / 3;
  std::atomic<bool> aheadBegun{false};
  std::atomic<int> cancelled{0};
  std::mutex m;
  std::vector<double> taken;
  calibration::LookAheadVerdict v;
  v.run = [&](double x) {
    if (x == fiveNinths || x == fourNinths) {
      aheadBegun = true;
      runUntilCancelled(cancelled);
    }
    if (x == 2.0 / 3) waitFor(aheadBegun);
    return x < 0.9;
  };
  v.take = [&](double x) {
    const std::lock_guard<std::mutex> lock(m);
    taken.push_back(x);
  };
  const BisectionResult r = calibration::narrowAhead(v, 0, 1, 0.01, 2);
  Landscape l;
  l.threshold = 0.9;
  BisectionResult reference;
  EXPECT_EQ(taken, kSectionValues(l, 0, 1, 0.01, 2, reference));
  EXPECT_EQ(r.stableEnd, reference.stableEnd);
  EXPECT_EQ(r.failingEnd, reference.failingEnd);
  EXPECT_EQ(cancelled.load(), 1) << "the run at 5/9 was not stopped";
  EXPECT_EQ(std::count(taken.begin(), taken.end(), fiveNinths), 0);
  EXPECT_EQ(std::count(taken.begin(), taken.end(), fourNinths), 0);
  EXPECT_GE(r.runsAhead, 1);
}

// Round 1 of [0, 1] with two threads tries 1/3 and 2/3 (stable below 0.2). 1/3 fails at once, a
// failure that ends its round: the bracket is [0, 1/3] whatever 2/3 says, so the run at 2/3, which
// would last 30 s, is stopped and not taken, and the narrowing goes on without it, as the
// k-section in turn does. Its runs count the values taken.
TEST(LookAhead, AFailureThatEndsItsRoundStopsTheRunsBeyondIt) {
  std::atomic<int> cancelled{0};
  std::mutex m;
  std::vector<double> taken;
  calibration::LookAheadVerdict v;
  v.run = [&](double x) {
    if (x == 2.0 / 3) runUntilCancelled(cancelled);
    return x < 0.2;
  };
  v.endsRound = [](double) { return true; };
  v.take = [&](double x) {
    const std::lock_guard<std::mutex> lock(m);
    taken.push_back(x);
  };
  for (const bool ahead : {true, false}) {
    SCOPED_TRACE(ahead);
    cancelled = 0;
    taken.clear();
    const auto t0 = std::chrono::steady_clock::now();
    const BisectionResult r = calibration::narrowAhead(v, 0, 1, 0.01, 2, ahead);
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(20)) << "waited for the run at 2/3";
    Landscape l;
    l.threshold = 0.2;
    l.everyFailureEndsRound = true;
    BisectionResult reference;
    EXPECT_EQ(taken, kSectionValues(l, 0, 1, 0.01, 2, reference));
    EXPECT_EQ(cancelled.load(), 1) << "the run at 2/3 was not stopped";
    EXPECT_EQ(std::count(taken.begin(), taken.end(), 2.0 / 3), 0);
    EXPECT_EQ(r.stableEnd, reference.stableEnd);
    EXPECT_EQ(r.failingEnd, reference.failingEnd);
    EXPECT_EQ(r.runs, static_cast<int>(taken.size()));
    EXPECT_EQ(r.rounds, reference.rounds);
    if (!ahead) {
      EXPECT_EQ(r.runsAhead, 0);
    }
  }
}

// An error in a run the narrowing takes reaches the caller; one in a run ahead that it never
// takes does not (that round never came, so neither did its error).
TEST(LookAhead, OnlyTheErrorsOfRunsTakenReachTheCaller) {
  const double twoNinths = 0 + (1.0 / 3 - 0) * 2 / 3;
  const double eightNinths = 2.0 / 3 + (1 - 2.0 / 3) * 2 / 3;
  std::atomic<bool> reached{false};
  calibration::LookAheadVerdict v;
  v.take = [](double) {};
  // Round 1 of [0, 1]: 1/3 fails at once, so the next bracket is [0, 1/3] whatever 2/3 says; the
  // freed thread runs 2/9 there ahead, which meets an error, and 2/3 ends after that began.
  v.run = [&](double x) {
    if (x == twoNinths) {
      reached = true;
      throw InputError("case.json", "joints.a.cohesion", "expected ≥ 0, found -1");
    }
    if (x == 2.0 / 3) waitFor(reached);
    return x < 0.1;
  };
  EXPECT_THROW(calibration::narrowAhead(v, 0, 1, 0.01, 2), InputError);
  // The same error at 8/9, where only a run ahead assuming 2/3 stable goes (after 5/9 and 4/9,
  // which assume it fails): 2/3 then fails, and 8/9 is never taken.
  reached = false;
  v.run = [&](double x) {
    if (x == eightNinths) {
      reached = true;
      throw InputError("case.json", "joints.a.cohesion", "expected ≥ 0, found -1");
    }
    if (x == 2.0 / 3) waitFor(reached);
    return x < 0.5;
  };
  const BisectionResult r = calibration::narrowAhead(v, 0, 1, 0.01, 2);
  EXPECT_TRUE(reached) << "the run ahead at 8/9 was not made";
  EXPECT_TRUE(r.bracketed);
  EXPECT_GE(r.runsAhead, 3);
  EXPECT_LE(r.stableEnd, 0.5);
  EXPECT_GT(r.failingEnd, 0.5);
}

// A search with look-ahead and without: the same factor of safety, bracket, runs and trials, on
// a verdict of known answer whose trials near it are slow (as DDA's failing trials are).
TEST(LookAhead, AStrengthReductionSearchIsTheSameWithAndWithout) {
  int ahead = 0;
  for (const double critical : {1.1224, 0.8, 2.7}) {
    const auto verdict = [critical](double f, double) {
      calibration::TrialResult r;
      r.stable = f < critical;
      r.rule = r.stable ? calibration::VerdictRule::AtRest : calibration::VerdictRule::PassedDisplacement;
      const double near = std::abs(f - critical);
      std::this_thread::sleep_for(std::chrono::microseconds(static_cast<int>(200 + 100 / (near + 0.01))));
      return r;
    };
    calibration::SearchSettings with, without;
    with.threads = without.threads = 2;
    without.lookAhead = false;
    const auto a = calibration::factorOfSafetyOf(verdict, 0.005, with);
    const auto b = calibration::factorOfSafetyOf(verdict, 0.005, without);
    ASSERT_TRUE(a.found && b.found) << a.message << b.message;
    EXPECT_EQ(a.factor, b.factor) << critical;
    EXPECT_EQ(a.stableEnd, b.stableEnd);
    EXPECT_EQ(a.failingEnd, b.failingEnd);
    EXPECT_EQ(a.runs, b.runs);
    EXPECT_EQ(a.rounds, b.rounds);
    EXPECT_EQ(a.review.reruns, b.review.reruns);
    EXPECT_EQ(b.runsAhead, 0);
    ASSERT_EQ(a.trials.size(), b.trials.size());
    for (size_t i = 0; i < a.trials.size(); ++i) {
      EXPECT_EQ(a.trials[i].value, b.trials[i].value);
      EXPECT_EQ(a.trials[i].result.stable, b.trials[i].result.stable);
    }
    EXPECT_NEAR(a.factor, critical, 0.005);
    ahead += a.runsAhead;
  }
  // Rounds whose trials take unequal times leave a thread idle, which runs ahead.
  EXPECT_GT(ahead, 0) << "no trial was run ahead";
}

namespace {

/// A bracketing loop as the searches write theirs: double x from `first` until the verdict
/// turns stable (or 40 doublings), taking each trial through `take`.
std::vector<double> doublingLoop(const std::function<bool(double, std::vector<double>)>& take, double first) {
  std::vector<double> taken;
  double x = first;
  for (int k = 0; k < 40; ++k) {
    taken.push_back(x);
    if (take(x, {2 * x, 4 * x})) break;
    x *= 2;
  }
  return taken;
}

}  // namespace

// The same loop with the runner and without, on 200 landscapes (monotone and not) with 1, 2 and 3
// threads: the same trials taken in the same order, each after its run finished.
TEST(LookAhead, ABracketingLoopTakesTheSameTrialsWithTheRunner) {
  std::mt19937 rng(6122026);
  std::uniform_real_distribution<double> u(0, 1);
  int used = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Landscape l;
    // "Stable" here means the loop may stop: stable at or above the threshold.
    l.threshold = std::pow(2.0, 1 + 12 * u(rng));
    if (trial % 2) l.islands.push_back({l.threshold * 0.25, l.threshold * 0.3});
    const auto holds = [&](double x) { return !l.stableAt(x); };
    const std::vector<double> reference = doublingLoop([&](double x, std::vector<double>) { return holds(x); }, 1);
    const int threads = 1 + trial % 3;
    RecordingVerdict r(l, holds);
    calibration::AheadRunner runner(r.v, threads);
    const std::vector<double> looped = doublingLoop([&](double x, std::vector<double> hoped) {
      return runner.take(x, std::move(hoped));
    }, 1);
    runner.stop();
    EXPECT_EQ(looped, reference) << trial;
    EXPECT_EQ(r.taken, reference) << trial;
    if (threads == 1) {
      EXPECT_EQ(runner.runsAhead(), 0);
    }
    used += runner.runsAheadUsed();
  }
  EXPECT_GT(used, 0) << "no run ahead was ever used";
}

// A loop that stops while a run ahead is going: stopping the runner stops that run (it would
// otherwise hold the caller 30 s), and an error met by a run never taken stays there.
TEST(LookAhead, ARunnerStopsItsRunsAheadAndKeepsTheirErrors) {
  std::atomic<int> cancelled{0};
  std::atomic<bool> begun{false}, erred{false};
  calibration::LookAheadVerdict v;
  v.run = [&](double x) {
    if (x == 3) {
      erred = true;
      throw InputError("case.json", "joints.a.cohesion", "expected ≥ 0, found -1");
    }
    if (x == 2) {
      begun = true;
      runUntilCancelled(cancelled);
    }
    return true;
  };
  v.take = [](double) {};
  {
    calibration::AheadRunner runner(v, 3);
    // While 1 runs here, the spare threads start 2 (long) and 3 (an error).
    EXPECT_TRUE(runner.take(1, {2, 3}));
    waitFor(begun);
    waitFor(erred);
    runner.stop();
    EXPECT_EQ(cancelled.load(), 1) << "the run at 2 was not stopped";
    EXPECT_EQ(runner.runsAheadUsed(), 0);
  }
  // Taken, the error reaches the caller.
  calibration::AheadRunner runner(v, 2);
  EXPECT_THROW(runner.take(3, {}), InputError);
}

namespace {

/// A strength reduction on two threads whose verdict is stable below `critical`, and whose trial
/// at F = 1 ends only once the trial at `awaited` has run (30 s at most: without a spare thread
/// running it meanwhile, F = 1 ends on that timeout). The same search without runs ahead is the
/// reference.
struct WhileOneRuns {
  bool awaitedBeforeOne = false;  ///< the trial at `awaited` had run when F = 1 ended
  int leftUnderWay = 0;           ///< runs still going when the search returned
  calibration::FactorOfSafetyResult with, without;
};

WhileOneRuns searchWaitingAtOne(double critical, double awaited) {
  std::atomic<bool> awaitedRan{false}, awaitedBeforeOne{false};
  std::atomic<int> underWay{0};
  const auto verdict = [&](double f, double) {
    ++underWay;
    calibration::TrialResult r;
    r.stable = f < critical;
    r.rule = r.stable ? calibration::VerdictRule::AtRest : calibration::VerdictRule::PassedDisplacement;
    if (f == 1.0) {
      waitFor(awaitedRan);
      awaitedBeforeOne = awaitedRan.load();
    }
    std::this_thread::sleep_for(std::chrono::microseconds(300));
    if (f == awaited) awaitedRan = true;
    --underWay;
    return r;
  };
  calibration::SearchSettings with, without;
  with.threads = without.threads = 2;
  without.lookAhead = false;
  WhileOneRuns w;
  w.with = calibration::factorOfSafetyOf(verdict, 0.005, with);
  w.leftUnderWay = underWay.load();
  w.awaitedBeforeOne = awaitedBeforeOne.load();
  awaitedRan = true;  // the search without runs ahead must not wait
  w.without = calibration::factorOfSafetyOf(verdict, 0.005, without);
  return w;
}

/// The same F, runs and trials, in the same order, with runs ahead as without.
void expectTheSameSearch(const calibration::FactorOfSafetyResult& a, const calibration::FactorOfSafetyResult& b) {
  ASSERT_TRUE(a.found && b.found) << a.message << b.message;
  EXPECT_EQ(a.factor, b.factor);
  EXPECT_EQ(a.runs, b.runs);
  ASSERT_EQ(a.trials.size(), b.trials.size());
  for (size_t i = 0; i < a.trials.size(); ++i) EXPECT_EQ(a.trials[i].value, b.trials[i].value);
}

}  // namespace

// A slope whose F lies just below 1 (a back-analysis of a failure): its trial at F = 1 creeps to
// the failure displacement and is the slowest of the search, while the trials below it are quick.
// While it runs, the spare thread runs the trials the search makes next if it fails, from 1/1.5
// on; here F = 1 ends only once the trial at 2/3 has run. The search takes the same trials, and
// gives the same F, as without runs ahead, none is left under way, and where F = 1 stands
// (F* = 1.3) the run at 2/3, never taken, is counted unused.
TEST(LookAhead, TheFailingBranchRunsWhileTheTrialAtOneCreeps) {
  for (const double critical : {0.985, 1.3}) {
    SCOPED_TRACE(critical);
    const WhileOneRuns w = searchWaitingAtOne(critical, 1.0 / 1.5);
    EXPECT_EQ(w.leftUnderWay, 0) << "a run of the branch outlived the search";
    EXPECT_TRUE(w.awaitedBeforeOne) << "the trial at 2/3 did not run while F = 1 ran";
    if (critical > 1) {
      EXPECT_GE(w.with.runsAheadUnused, 1);
    }
    expectTheSameSearch(w.with, w.without);
    EXPECT_NEAR(w.with.factor, critical, 0.005);
  }
}

// The first narrowing round of a strength reduction that stands at F = 1 and fails at 1.5 tries
// 7/6 and 4/3. A failure proven by the failure displacement at 7/6 ends the round: the run at 4/3,
// which would last 30 s, is stopped, and no trial at 4/3 is recorded. A failure while settling at
// 7/6 (an island of a verdict that is not monotone, F* = 1.4 beyond it) leaves 4/3 to run: it
// stands, and the search reports the contradiction, as Goodman & Bray's slope needs
// (docs/calibration.md, "Where contradictions can be seen").
TEST(LookAhead, OnlyAFailureProvenByTheDisplacementEndsItsRound) {
  const double sevenSixths = 1 + (1.5 - 1) * 1 / 3, fourThirds = 1 + (1.5 - 1) * 2 / 3;  // as the search computes them
  for (const bool lookAhead : {true, false}) {
    SCOPED_TRACE(lookAhead);
    calibration::SearchSettings s;
    s.threads = 2;
    s.lookAhead = lookAhead;
    std::atomic<int> cancelled{0};
    const auto proven = [&](double f, double) {
      calibration::TrialResult r;
      r.stable = f < 1.1;
      r.rule = r.stable ? calibration::VerdictRule::AtRest : calibration::VerdictRule::PassedDisplacement;
      if (f == fourThirds) runUntilCancelled(cancelled);
      return r;
    };
    const auto t0 = std::chrono::steady_clock::now();
    const auto a = calibration::factorOfSafetyOf(proven, 0.005, s);
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(20)) << "waited for the run at 4/3";
    ASSERT_TRUE(a.found) << a.message;
    EXPECT_NEAR(a.factor, 1.1, 0.005);
    for (const auto& t : a.trials) EXPECT_NE(t.value, fourThirds) << "the value beyond the proven failure was taken";
    EXPECT_LE(cancelled.load(), 1);

    const auto settling = [&](double f, double) {
      calibration::TrialResult r;
      r.stable = f < 1.4 && f != sevenSixths;
      r.rule = r.stable ? calibration::VerdictRule::AtRest
               : f == sevenSixths ? calibration::VerdictRule::MovedWhileSettling
                                  : calibration::VerdictRule::PassedDisplacement;
      if (f == fourThirds) std::this_thread::sleep_for(std::chrono::milliseconds(50));
      return r;
    };
    const auto b = calibration::factorOfSafetyOf(settling, 0.005, s);
    bool fourThirdsStands = false;
    for (const auto& t : b.trials) fourThirdsStands |= t.value == fourThirds && t.result.stable;
    EXPECT_TRUE(fourThirdsStands) << "the value beyond the settling failure did not run";
    EXPECT_TRUE(b.review.contradiction) << b.message;
    EXPECT_NE(b.message.find("while it settled"), std::string::npos) << b.message;
  }
}

// A slope that stands at F = 1 but settles slowly there, while the trials well beyond its F fail
// (or, F* = 4, stand) fast. Once 1.5 is done the spare thread runs what the search takes next if
// F = 1 stands: the first round of [1, 1.5] when 1.5 fails, the bracketing's 2.25 when it stands;
// here F = 1 ends only once that run has finished. The search takes the same trials, and gives
// the same F, as without runs ahead, and no run outlives it.
TEST(LookAhead, TheSearchesNextTrialsRunWhileTheTrialAtOneSettles) {
  for (const double critical : {1.2, 4.0}) {
    SCOPED_TRACE(critical);
    const double awaited = critical < 1.5 ? calibration::roundValues(1.0, 1.5, 2).back() : 1.5 * 1.5;
    const WhileOneRuns w = searchWaitingAtOne(critical, awaited);
    EXPECT_EQ(w.leftUnderWay, 0) << "a run of the spare thread outlived the search";
    EXPECT_TRUE(w.awaitedBeforeOne) << "the trial at " << awaited << " did not run while F = 1 ran";
    expectTheSameSearch(w.with, w.without);
    EXPECT_NEAR(w.with.factor, critical, 0.005 * critical);
  }
}
