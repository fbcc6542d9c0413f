#include "ddaslope/calibration/bisection.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <system_error>
#include <thread>
#include <tuple>

#include "ddaslope/core/cancellation.hpp"
#include "ddaslope/core/task_farm.hpp"

namespace ddaslope::calibration {

std::vector<bool> evaluateAll(const std::function<bool(double)>& stableAt, const std::vector<double>& values,
                              int threads) {
  std::vector<char> out(values.size());
  runOnThreads(static_cast<int>(values.size()), threads,
               [&](int i) { out[static_cast<size_t>(i)] = stableAt(values[static_cast<size_t>(i)]); });
  return {out.begin(), out.end()};
}

std::vector<double> roundValues(double stable, double failing, int k) {
  std::vector<double> values;
  for (int i = 1; i <= k; ++i) values.push_back(stable + (failing - stable) * i / (k + 1));
  return values;
}

namespace {

/// The bracket after a round: between the last stable value and the first failing one (`ok`: the
/// verdicts of the round's first values, up to its first failing one at least).
std::pair<double, double> afterRound(const std::vector<double>& values, const std::vector<bool>& ok, double stable,
                                     double failing) {
  for (size_t i = 0; i < ok.size(); ++i) {
    if (!ok[i]) return {stable, values[i]};
    stable = values[i];
  }
  return {stable, failing};
}

BisectionResult bracketed(BisectionResult r, double stable, double failing) {
  r.bracketed = true;
  r.stableEnd = stable;
  r.failingEnd = failing;
  r.critical = 0.5 * (stable + failing);
  return r;
}

}  // namespace

BisectionResult narrowBracket(const std::function<bool(double)>& stableAt, double stable, double failing,
                              double width, int threads, bool inTurn, const EndsRound& endsRound) {
  BisectionResult r;
  const int k = std::max(1, threads);
  while (std::abs(failing - stable) > width) {
    const std::vector<double> values = roundValues(stable, failing, k);
    std::vector<bool> ok;
    if (inTurn) {
      for (const double x : values)
        if (ok.push_back(stableAt(x)); !ok.back() && endsRound && endsRound(x)) break;
    } else {
      ok = evaluateAll(stableAt, values, k);
    }
    r.runs += static_cast<int>(ok.size());
    ++r.rounds;
    std::tie(stable, failing) = afterRound(values, ok, stable, failing);
  }
  return bracketed(r, stable, failing);
}

namespace {

/// A run of a look-ahead verdict, by value: its cancellation flag and, once done, its outcome.
struct AheadRun {
  std::atomic<bool> cancel{false};
  bool ahead = false;  ///< started ahead of need
  bool done = false;
  bool stable = false;
  bool endsRound = false;  ///< a failure that ends its round (LookAheadVerdict::endsRound)
  std::exception_ptr error;
};
using AheadRuns = std::map<double, std::shared_ptr<AheadRun>>;

/// Makes `run` of x with `lock` released, then records its outcome under it: a stopped run leaves
/// `runs` (it may be started again), a finished one keeps its verdict or its error.
void execute(const LookAheadVerdict& v, double x, const std::shared_ptr<AheadRun>& run, AheadRuns& runs,
             std::unique_lock<std::mutex>& lock) {
  lock.unlock();
  bool stable = false, cancelled = false, endsRound = false;
  std::exception_ptr error;
  try {
    const CancellationScope scope(run->cancel);
    stable = v.run(x);
    endsRound = !stable && v.endsRound && v.endsRound(x);
  } catch (const Cancelled&) {
    cancelled = true;
  } catch (...) {
    error = std::current_exception();
  }
  lock.lock();
  if (cancelled) {
    const auto at = runs.find(x);
    if (at != runs.end() && at->second == run) runs.erase(at);
  } else {
    run->done = true;
    run->stable = stable;
    run->endsRound = endsRound;
    run->error = error;
  }
}

/// The state narrowAhead's threads share, under its mutex.
class AheadRounds {
 public:
  AheadRounds(const LookAheadVerdict& v, double stable, double failing, double width, int k, bool runsAhead)
      : v_(v), stable_(stable), failing_(failing), width_(width), k_(k), runsAhead_(runsAhead) {
    nextRound();
  }

  /// One thread's share: runs the values the rounds need, or may need, until the narrowing ends.
  void work() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      if (finished_) return;
      double x = 0;
      bool ahead = false;
      if (!pick(x, ahead)) {
        idle_.wait(lock);
        continue;
      }
      auto run = std::make_shared<AheadRun>();
      run->ahead = ahead;
      runs_[x] = run;
      if (ahead) ++result_.runsAhead;
      execute(v_, x, run, runs_, lock);
      try {
        settle();
      } catch (...) {
        // Taking a trial failed (its record or progress report): end here, as an error of a run.
        if (!error_) error_ = std::current_exception();
        finished_ = true;
        for (auto& [value, other] : runs_) other->cancel = true;
      }
      idle_.notify_all();
    }
  }

  BisectionResult result() {
    if (error_) std::rethrow_exception(error_);
    return bracketed(result_, stable_, failing_);
  }

 private:
  void nextRound() {
    round_.clear();
    if (std::abs(failing_ - stable_) > width_) round_ = roundValues(stable_, failing_, k_);
    finished_ = round_.empty();
  }

  bool done(double x) const {
    const auto at = runs_.find(x);
    return at != runs_.end() && at->second->done;
  }

  /// The next round's values for every outcome of the round's unfinished trials, the outcomes
  /// in which more of them fail first (a trial that outlasts the others of its round is most
  /// often a failing one creeping near the answer), each round's values from its failing end.
  std::vector<double> mayNeed() const {
    std::vector<size_t> open;
    for (size_t i = 0; i < round_.size(); ++i)
      if (!done(round_[i])) open.push_back(i);
    std::vector<double> values;
    if (open.size() > 6) return values;
    std::vector<unsigned> outcomes;
    for (unsigned m = 0; m < (1u << open.size()); ++m) outcomes.push_back(m);
    std::stable_sort(outcomes.begin(), outcomes.end(),
                     [](unsigned a, unsigned b) { return std::popcount(a) < std::popcount(b); });
    for (const unsigned m : outcomes) {
      std::vector<bool> ok(round_.size());
      for (size_t i = 0, j = 0; i < round_.size(); ++i)
        ok[i] = j < open.size() && open[j] == i ? (m >> j++) & 1u : runs_.at(round_[i])->stable;
      const auto [s, f] = afterRound(round_, ok, stable_, failing_);
      if (std::abs(f - s) <= width_) continue;
      const std::vector<double> next = roundValues(s, f, k_);
      for (auto x = next.rbegin(); x != next.rend(); ++x)
        if (std::find(values.begin(), values.end(), *x) == values.end()) values.push_back(*x);
    }
    return values;
  }

  /// A value to run: the round's first not started, else one the next round may need; a
  /// round's values from its failing end, whose trials (failing slowly near the answer) take
  /// longest.
  bool pick(double& x, bool& ahead) const {
    for (auto value = round_.rbegin(); value != round_.rend(); ++value)
      if (!runs_.count(*value)) {
        x = *value, ahead = false;
        return true;
      }
    if (!runsAhead_) return false;
    for (const double value : mayNeed())
      if (!runs_.count(value)) {
        x = value, ahead = true;
        return true;
      }
    return false;
  }

  /// Takes every round whose trials have all finished, then cancels the runs no round can need.
  void settle() {
    while (!finished_ && takeRound()) nextRound();
    std::vector<double> keep = round_;
    if (!finished_) {
      const std::vector<double> next = mayNeed();
      keep.insert(keep.end(), next.begin(), next.end());
    }
    for (auto& [x, run] : runs_)
      if (!run->done && std::find(keep.begin(), keep.end(), x) == keep.end()) run->cancel = true;
  }

  /// Takes the round once its trials have finished, from its stable end up to a failure that
  /// ends it (narrowBracket in turn): hands them to the verdict, in order, and narrows the
  /// bracket. The values beyond are not needed, and their runs are stopped. An error of a trial
  /// taken ends the narrowing.
  bool takeRound() {
    std::vector<bool> ok;
    for (const double x : round_) {
      if (!done(x)) return false;
      const AheadRun& run = *runs_.at(x);
      if (run.error) {
        error_ = run.error;
        finished_ = true;
        return false;
      }
      if (ok.push_back(run.stable); run.endsRound) break;
    }
    for (size_t i = 0; i < round_.size(); ++i) {
      const double x = round_[i];
      if (i < ok.size()) {
        v_.take(x);
        if (runs_.at(x)->ahead) ++result_.runsAheadUsed;
      }
      // A value beyond the failure that ended the round: forgotten if it finished, stopped by
      // settle() if not.
      if (i < ok.size() || done(x)) runs_.erase(x);
    }
    result_.runs += static_cast<int>(ok.size());
    ++result_.rounds;
    std::tie(stable_, failing_) = afterRound(round_, ok, stable_, failing_);
    return true;
  }

  const LookAheadVerdict& v_;
  double stable_, failing_, width_;
  int k_;
  bool runsAhead_;  ///< idle threads run the values the next round may need
  std::mutex mutex_;
  std::condition_variable idle_;
  std::vector<double> round_;
  AheadRuns runs_;
  bool finished_ = false;
  std::exception_ptr error_;
  BisectionResult result_;
};

}  // namespace

BisectionResult narrowAhead(const LookAheadVerdict& verdict, double stable, double failing, double width,
                            int threads, bool runsAhead) {
  const int k = std::max(1, threads);
  if (k == 1)
    return narrowBracket(
        [&](double x) {
          const bool ok = verdict.run(x);
          verdict.take(x);
          return ok;
        },
        stable, failing, width, 1);
  AheadRounds rounds(verdict, stable, failing, width, k, runsAhead);
  std::vector<std::thread> pool;
  try {
    for (int t = 1; t < k; ++t) pool.emplace_back([&] { rounds.work(); });
  } catch (const std::system_error&) {
    // No thread to start: the ones started share the rounds (a round's trials then run in turn).
  }
  rounds.work();
  for (std::thread& t : pool) t.join();
  return rounds.result();
}

struct AheadRunner::State {
  explicit State(const LookAheadVerdict& v) : v(v) {}

  /// Makes the run of x (the caller holds `lock`, released meanwhile) and wakes the waiters.
  void execute(double x, const std::shared_ptr<AheadRun>& run, std::unique_lock<std::mutex>& lock) {
    calibration::execute(v, x, run, runs, lock);
    changed.notify_all();
  }

  bool wanted(double x) const {
    return x == taking || std::find(hoped.begin(), hoped.end(), x) != hoped.end();
  }

  /// A spare thread: runs hoped values until the runner closes.
  void help() {
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
      if (closing) return;
      const auto next =
          std::find_if(hoped.begin(), hoped.end(), [&](double x) { return !runs.count(x) && !taken.count(x); });
      if (next == hoped.end()) {
        changed.wait(lock);
        continue;
      }
      const double x = *next;
      auto run = std::make_shared<AheadRun>();
      run->ahead = true;
      runs[x] = run;
      ++ahead;
      execute(x, run, lock);
    }
  }

  const LookAheadVerdict& v;
  std::mutex mutex;
  std::condition_variable changed;
  AheadRuns runs;
  std::vector<double> hoped;
  std::set<double> taken;  ///< values taken: never run again
  double taking = std::numeric_limits<double>::quiet_NaN();
  bool closing = false;
  int ahead = 0, aheadUsed = 0;
  std::vector<std::thread> helpers;
};

AheadRunner::AheadRunner(const LookAheadVerdict& verdict, int threads) : state_(std::make_unique<State>(verdict)) {
  try {
    for (int t = 1; t < threads; ++t) state_->helpers.emplace_back([s = state_.get()] { s->help(); });
  } catch (const std::system_error&) {
    // No thread to start: the spare threads started run ahead (none: every trial runs when taken).
  }
}

AheadRunner::~AheadRunner() { stop(); }

void AheadRunner::stop() {
  {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    state_->closing = true;
    for (auto& [x, run] : state_->runs) run->cancel = true;
  }
  state_->changed.notify_all();
  for (std::thread& t : state_->helpers) t.join();
  state_->helpers.clear();
}

bool AheadRunner::take(double x, std::vector<double> hoped) {
  State& s = *state_;
  std::unique_lock<std::mutex> lock(s.mutex);
  s.taking = x;
  s.hoped = std::move(hoped);
  for (auto& [value, run] : s.runs)
    if (!run->done && !s.wanted(value)) run->cancel = true;
  s.changed.notify_all();
  std::shared_ptr<AheadRun> run;
  for (;;) {
    const auto at = s.runs.find(x);
    if (at == s.runs.end()) {
      // Not run ahead (or stopped before it was wanted again): run it here.
      run = std::make_shared<AheadRun>();
      s.runs[x] = run;
      s.execute(x, run, lock);
      break;
    }
    run = at->second;
    if (run->done) break;
    s.changed.wait(lock);
  }
  s.runs.erase(x);
  s.taken.insert(x);
  s.taking = std::numeric_limits<double>::quiet_NaN();
  if (run->error) std::rethrow_exception(run->error);
  if (run->ahead) ++s.aheadUsed;
  lock.unlock();
  s.v.take(x);
  return run->stable;
}

int AheadRunner::runsAhead() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->ahead;
}

int AheadRunner::runsAheadUsed() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->aheadUsed;
}

BisectionResult bisect(const std::function<bool(double)>& stableAt, double lo, double hi, double width,
                       int threads) {
  return bisect(stableAt, lo, hi, width, threads, [&](double stable, double failing, double w, int k) {
    return narrowBracket(stableAt, stable, failing, w, k);
  });
}

BisectionResult bisect(const std::function<bool(double)>& stableAt, double lo, double hi, double width, int threads,
                       const Narrowing& narrow) {
  const std::vector<bool> ends = evaluateAll(stableAt, {lo, hi}, threads);
  if (ends[0] == ends[1]) {
    BisectionResult r;
    r.runs = 2;
    std::ostringstream m;
    m << "not bracketed: both ends (" << lo << ", " << hi << ") are " << (ends[0] ? "stable" : "failing");
    r.message = m.str();
    r.critical = ends[0] ? lo : hi;
    r.stableEnd = r.failingEnd = r.critical;
    return r;
  }
  BisectionResult r = narrow(ends[0] ? lo : hi, ends[0] ? hi : lo, width, threads);
  r.runs += 2;
  return r;
}

}  // namespace ddaslope::calibration
