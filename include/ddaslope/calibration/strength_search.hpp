#pragma once
// The searches over joint strength: critical cohesion or friction angle of one joint by
// bisection, and the strength-reduction factor of safety (benchmarks.md §G).
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "ddaslope/calibration/verdict.hpp"
#include "ddaslope/core/task_farm.hpp"
#include "ddaslope/io/progress.hpp"
#include "ddaslope/model/scene.hpp"

namespace ddaslope::calibration {

/// One forward run of a search: the value tried (a strength factor F, a cohesion in Pa or a
/// friction angle in degrees) and its verdict, with the rule that decided it.
struct TrialRecord {
  double value = 0;
  TrialResult result;
  /// A re-run, kReRunLength times longer, of a trial whose verdict contradicted another's (the
  /// search's review): its verdict replaces the first one's.
  bool rerun = false;
};

/// How much longer (× the case's duration) a search re-runs trials whose verdicts contradict.
constexpr double kReRunLength = 4;

/// What a search's review of its own trials found (every search ends with one). The verdict must
/// be monotone in the value searched: a failing trial on the stable side of a stable one is a
/// contradiction. Contradicting trials are re-run kReRunLength times longer (except those that
/// failed while they settled, before t = 0, which a longer run repeats) and the bracket is
/// narrowed again; if they still contradict, or if an undecided trial leaves the bracket between
/// decided trials wider than asked for, the search has no answer (`found` false) and says so,
/// with the bracket it can vouch for.
struct TrialReview {
  bool contradiction = false;  ///< trials still contradict after their re-runs
  bool undecided = false;      ///< the answer's bracket is bounded by undecided trials
  int reruns = 0;              ///< trials re-run longer
};

enum class TrialStart { Settled, Held };
const char* name(TrialStart start);  ///< "settled", "held"

struct SearchSettings {
  VerdictSettings verdict;
  int threads = 2;  ///< independent forward runs evaluated at once
  /// Told after every forward run: the runs so far, the bracket once there is one, and an
  /// estimate of the runs left (io/progress.hpp). Empty: silent.
  io::ProgressSink progress;
  /// Sees every trial's final state with the value it tried (k_h signed by its direction for the
  /// seismic coefficient), from the trial's own thread (a search's --vtk). Not passed on to the
  /// searches of criticalCurve.
  std::function<void(double value, const solver::Simulation&, const TrialResult&)> finalStates;
  /// While a round's last trial runs, the threads its other trials freed run the trials the next
  /// round may need (calibration/bisection.hpp, narrowAhead): the same trials and answer, sooner.
  /// Off when every trial's final state is written, since a run the search does not use must
  /// leave no file.
  bool lookAhead = true;
  /// A narrowing runs each round's values one after another instead of at once (the same trials,
  /// slower): set where every trial's final state is written to a file (a search's --vtk), since
  /// a value run beside the one that ends its round would leave the file of a trial the search
  /// does not take.
  bool narrowInTurn = false;
  /// Strength reduction (factorOfSafety): where each trial's equilibrium starts. Settled: from the
  /// rest the trial at the case's own strengths (F = 1) found, when that trial stands, as the
  /// strength reduction of FLAC and UDEC starts from the model in equilibrium; a trial then only
  /// settles what its weaker joints let go. Held: every trial settles from every contact held
  /// (stage 1) with its own strengths, as all trials do when F = 1 fails (docs/calibration.md,
  /// "Where a trial starts").
  TrialStart trialStart = TrialStart::Held;
  /// How messages' hints name the case (`ddaslope run CASE --at-fos ...`): the CLI gives its path.
  std::string caseLabel = "CASE";
  /// The free blocks' own elastic settlement under their weight, at most (ρ g h² / E, m; 0:
  /// unknown): a search that fails at every factor by a settling motion within it may be seeing
  /// that settlement (factorOfSafety sets it from the scene).
  double elasticSettlement = 0;
};

struct CriticalResult {
  bool found = false;
  std::string message;      ///< why not found, or a remark (e.g. stable without cohesion)
  double critical = 0;      ///< Pa for cohesion, degrees for friction
  /// The answer is the largest value at which the scene holds (a load that destabilises), not
  /// the smallest (a strength, a support).
  bool largestThatHolds = false;
  double stableEnd = 0;     ///< bracket end that holds
  double failingEnd = 0;    ///< bracket end that fails
  int runs = 0;
  /// Runs made ahead of need (SearchSettings::lookAhead); and the runs made that the search did
  /// not use, stopped or finished: made ahead, or a narrowing round's values beyond a failure
  /// that ended the round. Threads' time spent, not counted in `runs` nor recorded as trials.
  /// Both depend on the threads' timing; nothing else in the result does.
  int runsAhead = 0;
  int runsAheadUnused = 0;
  double wallTime = 0;      ///< s
  TrialReview review;
  std::vector<TrialRecord> trials;  ///< every forward run, by value
};

/// The cohesion (Pa) of `joint` at which the scene becomes stable, with φ of that joint set to
/// `frictionDeg`. Bracketing from 0 upward by doubling from `initialGuess`, then bisection to
/// `width` Pa. 0 with a remark when the scene holds without cohesion.
CriticalResult criticalCohesion(const model::Scene& scene, int joint, double frictionDeg, double width,
                                const SearchSettings& s = {}, double initialGuess = 1e5);
/// The friction angle (degrees) of `joint` at which the scene becomes stable, with its cohesion
/// set to `cohesion`; bisection on [0, 89.9] to `width` degrees.
CriticalResult criticalFriction(const model::Scene& scene, int joint, double cohesion, double width,
                                const SearchSettings& s = {});

/// The JRC of Barton–Bandis joint `joint` at which the scene becomes stable, its φr and JCS as
/// the case has them; bisection on [0, 20] to `width`.
CriticalResult criticalJrc(const model::Scene& scene, int joint, double width, const SearchSettings& s = {});

/// The yield (critical) horizontal seismic coefficient k_y of Newmark's method: the smallest k_h
/// (a fraction of g, acting along `direction`, +1 for +x or −1 for −x, with the case's k_v) at
/// which the slope fails. Brackets upward from 0 by doubling from 0.05 (to at most 2), then
/// bisects to `width` (≤ 0: to `relativeWidth` of the bracket's failing end). Not found if the
/// slope fails without it or holds at 2. A ground-motion record in the scene is left out of the
/// trials.
CriticalResult criticalSeismicCoefficient(const model::Scene& scene, int direction, double width,
                                          const SearchSettings& s = {}, double relativeWidth = 1e-3);

/// The size of the support or load `id` (model::Scene::supportQuantity: an anchor's force, a
/// bolt's capacity, a load's resultant, N/m) at which the scene holds with every joint's strength
/// reduced by `targetFactor` (c/F, atan(tan φ/F)); support capacities are not reduced. Brackets
/// upward from 0 by doubling from the case's own value (or 1e5 N/m), then bisects to `width`
/// (≤ 0: 1e-3 of the bracket's stable end). 0 with a remark when the scene holds without it;
/// for a load that holds without it, the largest load that holds (largestThatHolds), bracketed
/// upward by doubling from the case's own value.
CriticalResult criticalSupport(const model::Scene& scene, const std::string& id, double targetFactor, double width,
                               const SearchSettings& s = {});

struct CurvePoint {
  double frictionDeg = 0;
  CriticalResult cohesion;  ///< critical cohesion at this friction angle
  double crackX = std::numeric_limits<double>::quiet_NaN();  ///< where a searched crack was put (PointScene)
};

/// The scene of one curve point, when it depends on the point (a tension crack at its least safe
/// position for that friction angle): sets `crackX` and adds its own forward runs to `runs`.
using PointScene = std::function<model::Scene(double frictionDeg, double& crackX, int& runs)>;

/// The curve of critical (c, φ) pairs of `joint`: the critical cohesion at n friction angles
/// evenly spaced over [phiMin, phiMax] (n ≥ 2). Points are independent searches (one thread
/// each), run on `farm` (null: `threads` at a time in this process). Under MPI only the root's
/// curve is filled in (the search's record of trials stays empty: the points' results are
/// what crosses between ranks).
std::vector<CurvePoint> criticalCurve(const model::Scene& scene, int joint, double phiMinDeg, double phiMaxDeg,
                                      int n, double width, const SearchSettings& s = {}, TaskFarm* farm = nullptr,
                                      const PointScene& sceneAt = {});

struct FactorOfSafetyResult {
  bool found = false;
  std::string message;
  double factor = 0;      ///< midpoint of the final bracket
  double stableEnd = 0;   ///< largest F tried that holds
  double failingEnd = 0;  ///< smallest F tried that fails
  /// Where the trials after the first started: Settled only if asked for and F = 1 stands.
  TrialStart trialStart = TrialStart::Held;
  int runs = 0;
  int rounds = 0;
  /// Runs made ahead of need (SearchSettings::lookAhead); and the runs made that the search did
  /// not use, stopped or finished: made ahead, or a narrowing round's values beyond a failure
  /// that ended the round. Threads' time spent, not counted in `runs` nor recorded as trials.
  /// Both depend on the threads' timing; nothing else in the result does.
  int runsAhead = 0;
  int runsAheadUnused = 0;
  double wallTime = 0;
  TrialReview review;
  std::vector<TrialRecord> trials;  ///< every forward run, by value
};

/// Strength reduction: the F at which c/F and atan(tan φ / F) on `joints` (all if empty) turn
/// the scene from stable to failing. Brackets from F = 1 (×1.5 or ÷1.5 per step), then narrows
/// to `width`; each round tries `threads` interior factors at once (k-section), so one round
/// shrinks the bracket by threads + 1.
FactorOfSafetyResult factorOfSafety(const model::Scene& scene, const std::vector<int>& joints, double width,
                                    const SearchSettings& s = {});
/// What strengthReductionTrial ran: every forward run (the trial at F = 1 a settled start needs,
/// the trial at F, its re-run), the verdict in force last, and the start the trial at F took.
struct StrengthReductionCheck {
  std::vector<TrialRecord> runs;
  TrialStart start = TrialStart::Held;
  const TrialResult& verdict() const { return runs.back().result; }
};

/// One trial of factorOfSafety at F, judged as the search judges the failing end of its bracket:
/// whether the scene stands with c/F, σt/F and atan(tan φ/F) on `joints` (all if empty). It starts
/// where the search's trials start (s.trialStart: from the rest at F = 1 when it stands, which
/// takes a run at F = 1), runs a failure decided on its trend on to the review's length, and runs
/// an undecided trial again that much longer, as the review does (`fos --check`: a required F
/// checked without a search).
StrengthReductionCheck strengthReductionTrial(const model::Scene& scene, const std::vector<int>& joints, double f,
                                              const SearchSettings& s = {});
/// The start factorOfSafety's trials take with TrialStart::Settled: the rest of the scene at its
/// own strengths, from `held` (its stage 1), if a trial there stands; none otherwise. `run
/// --at-fos` starts from it as the search's trials do.
std::optional<solver::HeldEquilibrium> settledStart(const model::Scene& scene, const solver::HeldEquilibrium& held,
                                                    const VerdictSettings& verdict);
/// The same search on any verdict of (F, duration factor): factorOfSafety's, or a test's.
FactorOfSafetyResult factorOfSafetyOf(const std::function<TrialResult(double, double)>& verdict, double width,
                                      const SearchSettings& s = {});

}  // namespace ddaslope::calibration
