#pragma once
// Probabilities of failure by active learning (AK-MCS: Echard, Gayton & Lemaire 2011, Structural
// Safety 33, 145–154), docs/probability.md, *Active learning*.
//
// A population of the study's inputs (its plain-sampling design, Monte Carlo or Latin
// hypercube) is classified, stable or failing, by a kriging surrogate of the factor of safety
// (kriging.hpp) instead of a forward run each. The surrogate learns from strength-reduction
// searches at the population points whose sign it is least sure of. The learning function
// U = |mean|/sd is the distance of the predicted margin F − 1 from 0 in standard deviations (the
// surrogate's, combined with the searches' own resolution). Learning stops when few points have
// U < 2, or when the surrogate knows every such point's F as well as a search could: each of them
// is then judged by one forward run, cheaper than the searches that would make the surrogate sure
// (a point a hair from the limit state needs many). The classification is then confirmed by
// forward runs: the least sure of the other points are judged too, and a verdict that contradicts
// a sure surrogate makes that point a search, and the learning goes on. Pf is the failing share of
// the population, with its sampling interval; points left below U = 2 (a budget ran out) bound it.
//
// Every population point lies in all failure regions the inputs reach, so a slope that fails at
// both low and high values of an input is classified right (importance sampling around one
// design point misses the other region's share).
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "ddaslope/calibration/kriging.hpp"
#include "ddaslope/calibration/probability.hpp"
#include "ddaslope/calibration/reliability.hpp"

namespace ddaslope::calibration {

/// What a strength-reduction search says at one point.
struct PerformanceValue {
  bool converged = false;
  double margin = 0;   ///< F − 1
  bool fails = false;  ///< the verdict at F = 1 (agrees with margin < 0)
  int runs = 0;        ///< forward runs spent
};

struct ActiveLearningProblem {
  /// The population in the independent standard normals, d × N: column k is population point k.
  Eigen::MatrixXd population;
  /// The search at population point k. Called from several threads at once.
  std::function<PerformanceValue(int k)> evaluate;
  /// One forward run's verdict at population point k (the confirmation). Called from several
  /// threads at once.
  std::function<PointVerdict(int k)> judge;
  /// Optional: the searches (verdicts) of several points at once, returned in the points' order.
  /// When set they replace evaluate (judge) on `threads` threads: for a caller that replays runs
  /// made before, records each as it finishes, or spreads them over processes. They may throw to
  /// end the learning (what they ran is theirs to keep).
  std::function<std::vector<PerformanceValue>(const std::vector<int>& points)> evaluateAll;
  std::function<std::vector<PointVerdict>(const std::vector<int>& points)> judgeAll;
};

/// The searches before the first fit, for d inputs: max(12, 2(d + 2)) (Echard et al. take 12;
/// the trend and the length scales need a few points per input).
int initialSearches(int dimensions);

struct ActiveLearningSettings {
  /// Points searched first: population points 0 … initial − 1 (0: initialSearches(d)).
  int initial = 0;
  /// Points learnt per round: the least sure point, then the least sure one at least
  /// `separation` from it. Fixed, so that the answer does not depend on the thread count.
  int batch = 2;
  double separation = 0.25;
  /// Learning stops when every unrun point has U ≥ stopU.
  double stopU = 2;
  /// Searches at most; past it the classification's unsure points bound Pf.
  int maxSearches = 200;
  /// The standard deviation of a search's margin (its F is known to ± width/2). It is added to
  /// the surrogate's own in U, and where the surrogate's sd is below it, another search cannot
  /// make the surrogate surer.
  double resolution = 0.005 / 4;
  /// Learning stops when at most this many unrun points have U < stopU, or when none of them has
  /// a predicted sd above the resolution. Each unsure point is then judged by one forward run
  /// instead of a search, and so are `confirmations` of the least sure of the others.
  int confirmations = 20;
  /// Verdicts at most over the whole learning; past it the unsure points left bound Pf.
  int maxVerdicts = 2000;
  /// Searches or verdicts at once.
  int threads = 1;
  /// Called before each round with the searches and verdicts so far and the unsure points.
  std::function<void(int searches, int verdicts, int unsure)> progress;
};

enum class LearnedRole { Initial, Learning, Confirmation };
/// "initial", "learning", "confirmation".
const char* name(LearnedRole role);

/// One point run, in the order they were run.
struct LearnedPoint {
  int index = 0;  ///< population point
  LearnedRole role = LearnedRole::Initial;
  PerformanceValue value;                        ///< a search (initial, learning)
  PointVerdict verdict = PointVerdict::Stable;   ///< a confirmation's verdict
  /// The surrogate's margin and its sd where the point was chosen (NaN for the initial points).
  double predictedMean = std::numeric_limits<double>::quiet_NaN();
  double predictedSd = std::numeric_limits<double>::quiet_NaN();
  bool agrees = true;  ///< a confirmation: its verdict has the surrogate's sign
  bool sure = false;   ///< a confirmation: the surrogate had U ≥ stopU there (a disagreement is a contradiction)
};

struct ActiveLearningResult {
  std::vector<LearnedPoint> points;
  int population = 0;
  int failing = 0;       ///< population points classified failing (a run point by its run)
  int notConverged = 0;  ///< run points whose search or verdict did not converge: counted apart
  /// Unrun points classified with U < stopU (a budget ran out), by predicted sign.
  int unsureFailing = 0, unsureStable = 0;
  double minU = 0;       ///< the least U of the unrun points at the end
  bool learnt = false;   ///< every unrun point reached U ≥ stopU and the last confirmation agreed
  std::string stoppedBy;  ///< when not learnt: "searches" or "verdicts", the budget that ran out
  int rounds = 0;        ///< surrogate fits
  int searches = 0, searchRuns = 0, verdicts = 0;
  /// Confirmations of points the surrogate was sure of (U ≥ stopU) that contradicted it.
  int disagreements = 0;
  /// Unsure points (U < stopU) decided by their own forward run at the end of the learning.
  int decidedByVerdict = 0;
  std::vector<char> fails;  ///< each population point's final class
  Kriging surrogate;        ///< the last fit (none when rounds = 0)
  std::string message;      ///< why the learning could not start (too few points converged)
};

/// What the classified population says.
struct LearnedProbability {
  int converged = 0;  ///< population points less those run that did not converge
  /// failing / converged, with the Wilson interval of a Monte Carlo estimate from `converged`
  /// samples (the population's sampling error; the classification is taken as exact).
  double pf = 0;
  Interval interval;
  double coefficientOfVariation = std::numeric_limits<double>::quiet_NaN();  ///< √((1 − Pf)/(Pf n))
  double beta = 0;
  Interval betaInterval;
  /// Wilson's lower end with the unsure points and the not-converged ones called stable, to its
  /// upper end with both called failing (as wide as the interval when learning finished).
  Interval bounds;
};
LearnedProbability probabilityOf(const ActiveLearningResult& r);

/// The surrogate's design point: the point of least |u| where the surrogate's margin is 0,
/// found from the failing population point of least |u| (constrained COBYLA, no forward run).
/// It gives FORM's sensitivities α (and γ) for the study without the rays of findDesignPoint;
/// found = false when no population point fails. runs = 0: it costs none.
DesignPoint surrogateDesignPoint(const ActiveLearningProblem& problem, const ActiveLearningResult& r);

/// Classifies the population (see the file comment).
ActiveLearningResult learnFailureDomain(const ActiveLearningProblem& problem, const ActiveLearningSettings& settings);

}  // namespace ddaslope::calibration
