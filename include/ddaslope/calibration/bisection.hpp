#pragma once
// Narrowing a bracket between a stable and a failing trial (bisection, or k-section when
// several forward runs can be evaluated at once).
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ddaslope::calibration {

struct BisectionResult {
  bool bracketed = false;  ///< false: both ends gave the same verdict (see `message`)
  double critical = 0;     ///< midpoint of the final bracket
  double stableEnd = 0;    ///< the bracket end that is stable
  double failingEnd = 0;   ///< the bracket end that fails
  int runs = 0;            ///< forward runs taken (the values whose verdicts the narrowing used)
  int rounds = 0;          ///< narrowing rounds
  int runsAhead = 0;       ///< runs started ahead of need (narrowAhead), used or not
  int runsAheadUsed = 0;   ///< of those, the runs the narrowing took
  std::string message;
};

/// Evaluates `stableAt` for every value, `threads` at a time; results in input order. An exception
/// of one evaluation is rethrown here, after the others running have finished.
std::vector<bool> evaluateAll(const std::function<bool(double)>& stableAt, const std::vector<double>& values,
                              int threads);

/// A round's k equally spaced interior values of [stable, failing], in increasing distance from
/// the stable end: the values narrowBracket and narrowAhead evaluate in a round.
std::vector<double> roundValues(double stable, double failing, int k);

/// Whether the failure just found at a value ends its round (see narrowBracket); none: no failure
/// does.
using EndsRound = std::function<bool(double)>;

/// Narrows [stable, failing] (verdicts already known) to `width`: each round evaluates
/// `threads` equally spaced interior points at once, shrinking the bracket by threads + 1.
/// The verdict is assumed monotone between the ends. `inTurn`: the same rounds, their points
/// evaluated one after another on the calling thread, from the stable end, and a round ends at a
/// failing point for which `endsRound` says so (at once, every point of a round runs, and
/// `endsRound` is not asked). The bracket after a round does not depend on the points beyond its
/// first failing one (with monotone verdicts they fail too); they are checks of monotonicity,
/// worth their runs where a failure may be misjudged. `runs` counts the points evaluated.
BisectionResult narrowBracket(const std::function<bool(double)>& stableAt, double stable, double failing,
                              double width, int threads = 1, bool inTurn = false, const EndsRound& endsRound = {});

/// A verdict whose runs may be made ahead of need. `run(x)` makes the forward run at x, on any
/// thread, keeps its outcome and returns whether it is stable; it may unwind with Cancelled
/// (core/cancellation.hpp) when the run is no longer wanted. `take(x)` hands the outcome of a
/// finished run(x) to the search (to record it); it is called once for every value the narrowing
/// uses, round by round, in the order of the round's values. Outcomes never taken are the
/// owner's to forget.
struct LookAheadVerdict {
  std::function<bool(double)> run;
  std::function<void(double)> take;
  /// Asked after run(x) returned a failure (on the thread that ran it): whether it ends its
  /// round (narrowBracket). None: no failure does.
  EndsRound endsRound;
};

/// narrowBracket's rounds, values, verdicts and result in turn (a round's values from its stable
/// end, up to a failure that ends the round: `verdict.endsRound`), with a round's values run at
/// once on `threads` threads: a round is taken as soon as its values up to such a failure have
/// finished, and the runs of the values beyond it are stopped (a failing trial near the answer
/// often creeps for a long time, and one beyond it, failing too, is not needed). With
/// `runsAhead`, the threads a round leaves idle (its other trials finished, one still running)
/// make the trials the next round may need: those of every outcome of the trials still running,
/// the outcome where they fail first.
/// A run ahead is taken only if its round comes, so the narrowing uses, and hands to `take`,
/// exactly the trials narrowBracket in turn would, whatever finishes first; a run whose round
/// cannot come any more is cancelled.
BisectionResult narrowAhead(const LookAheadVerdict& verdict, double stable, double failing, double width,
                            int threads, bool runsAhead = true);

/// Trials taken one at a time, as a bracketing loop takes them (c × 2 until the slope holds), with
/// the spare threads running ahead the values the loop hopes to take next. `take(x, hoped)` gives
/// the verdict at x, handed to the verdict's `take`: from a run made ahead, or made now on the
/// calling thread. The spare threads then run the `hoped` values not yet run, in order; a run
/// of a value neither taken nor hoped any more is stopped. The loop takes the same trials, in the
/// same order, as without the runner. Runs still going when the runner is destroyed are stopped.
class AheadRunner {
 public:
  /// `threads`: the calling thread and threads − 1 spare ones (1: no run ahead).
  AheadRunner(const LookAheadVerdict& verdict, int threads);
  ~AheadRunner();
  AheadRunner(const AheadRunner&) = delete;
  AheadRunner& operator=(const AheadRunner&) = delete;
  bool take(double x, std::vector<double> hoped);
  /// Stops the runs still going and the spare threads (the destructor does it too).
  void stop();
  int runsAhead() const;      ///< runs the spare threads started
  int runsAheadUsed() const;  ///< of those, the runs taken

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Evaluates both ends, then narrows. Exactly one end must be stable.
BisectionResult bisect(const std::function<bool(double)>& stableAt, double lo, double hi, double width,
                       int threads = 1);

/// A narrowing with narrowBracket's arguments after the verdict (narrowAhead bound to one).
using Narrowing = std::function<BisectionResult(double stable, double failing, double width, int threads)>;
/// bisect, narrowing with `narrow`.
BisectionResult bisect(const std::function<bool(double)>& stableAt, double lo, double hi, double width, int threads,
                       const Narrowing& narrow);

}  // namespace ddaslope::calibration
