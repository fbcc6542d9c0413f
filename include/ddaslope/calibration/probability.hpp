#pragma once
// Probability of failure (docs/probability.md), the pure parts: the standard normal,
// counter-based random numbers, the marginal distributions, the sampling design (Monte Carlo or
// Latin hypercube, correlated through a Gaussian copula), the Wilson score interval, the
// reliability index, and the summary of a set of finished samples.
//
// A sample's values come from (seed, sample index, N for a Latin hypercube) only, never from the
// thread or process that runs it or the order in which samples finish, so any scheduler (threads
// now, MPI ranks later) gives the same samples, and a summary of the samples sorted by index is
// the same bit for bit.
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "ddaslope/model/uncertainty.hpp"

namespace ddaslope::calibration {

/// z of a two-sided 95 % interval: Φ⁻¹(0.975).
inline constexpr double kZ95 = 1.959963984540054;

/// Φ(z), the standard normal distribution function, through erfc (full relative precision in the
/// lower tail).
double normalCdf(double z);
/// Φ⁻¹(p) for p in (0, 1) (−∞ at 0, +∞ at 1): Wichura's algorithm AS 241 (Appl. Statist. 37,
/// 1988), relative error about 1e-16.
double normalQuantile(double p);

/// SplitMix64's output function (Steele, Lea & Flood 2014): a bijective 64-bit mix.
std::uint64_t splitMix64(std::uint64_t x);
/// 64 random bits that depend on (seed, stream, index) only: a counter-based generator, so the
/// numbers of sample k are the same whatever was drawn before.
std::uint64_t counterBits(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);
/// A uniform number in (0, 1), never 0 or 1, from counterBits (53 bits, offset by half a step).
double counterUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

/// The value of the marginal at the standard normal z: F⁻¹(Φ(z)) (the Nataf map), computed
/// without the round trip through Φ where the distribution allows (normal, lognormal), and
/// through the nearer tail for a truncated normal.
double valueAt(const model::Distribution& d, double z);
/// The exact mean and standard deviation of the marginal.
double distributionMean(const model::Distribution& d);
double distributionSd(const model::Distribution& d);
/// "normal", "lognormal", "uniform", "truncated_normal".
const char* name(model::DistributionKind kind);
const char* name(model::Sampling sampling);      ///< "monte_carlo", "latin_hypercube"
const char* name(model::ProbabilityMeasure m);   ///< "verdict", "fos"
const char* name(model::ProbabilityMethod m);    ///< "sampling", "importance_sampling", "active_learning"
/// E.g. "normal (mean 20000, sd 5000)", "truncated_normal (mean 30, sd 3 before truncation to [20, 40])".
std::string describe(const model::Distribution& d);

/// The samples of a study: sample k's correlated standard normals and the input values they give.
///
/// Monte Carlo: input i of sample k draws z = Φ⁻¹(u), u = counterUniform(seed, i, k).
/// Latin hypercube: input i has a permutation π_i of 0..N−1 (Fisher–Yates driven by
/// counterBits(seed, 2^32 + i, step): it depends on the seed and N only), and sample k takes
/// u = (π_i(k) + counterUniform(seed, i, k)) / N, a point of its own stratum.
/// Correlation: x = L z with L the Cholesky factor of the inputs' correlation matrix, applied to
/// the (stratified) normals. Each sample is then an exact draw from the joint distribution, so
/// every estimate is unbiased; the first input of a correlated group keeps its strata exactly,
/// and the others are sums of stratified terms (docs/probability.md, *Sampling*).
class SampleDesign {
 public:
  /// The spec must be valid (io::readProbabilityJob checks it): a positive-definite correlation
  /// matrix, samples ≥ 1.
  explicit SampleDesign(const model::ProbabilitySpec& spec);
  int samples() const { return samples_; }
  int inputs() const { return static_cast<int>(inputs_.size()); }
  /// The correlated standard normals of sample `index` (in [0, N)).
  std::vector<double> normals(int index) const;
  /// The input values of sample `index`, in case units.
  std::vector<double> values(int index) const;
  /// The input values at the independent standard normals u: the marginals at L u.
  std::vector<double> valuesAt(const std::vector<double>& u) const;

  /// Importance sampling: every sample's independent normals are shifted by `centre` (the design
  /// point, reliability.hpp), and the sample is weighted by importanceWeight.
  void centreOn(std::vector<double> centre) { centre_ = std::move(centre); }
  const std::vector<double>& centre() const { return centre_; }
  /// The weight of sample `index` in Pf's estimate: 1 without a centre.
  double weight(int index) const;
  /// L, row-major.
  const std::vector<double>& cholesky() const { return cholesky_; }
  /// Sample `index`'s independent standard normals, before the centre and the correlation.
  std::vector<double> independent(int index) const;

 private:
  std::vector<double> correlated(const std::vector<double>& u) const;
  std::vector<double> centre_;                   ///< empty: no importance sampling
  std::vector<model::UncertainInput> inputs_;
  int samples_ = 0;
  model::Sampling sampling_ = model::Sampling::LatinHypercube;
  std::uint64_t seed_ = 1;
  std::vector<double> cholesky_;                 ///< lower factor, row-major, inputs × inputs
  std::vector<std::vector<int>> permutations_;   ///< Latin hypercube: π_i
};

enum class SampleOutcome { Stable, Fails, NotConverged };
/// "stable", "fails", "not_converged".
const char* name(SampleOutcome outcome);

/// One finished sample.
struct SampleResult {
  int index = 0;
  std::vector<double> inputs;  ///< the values run, in case units
  SampleOutcome outcome = SampleOutcome::Stable;
  /// What decided it: the verdict rule's name (verdict.hpp), for the factor-of-safety measure
  /// that of the run at F = 1, or "no_bracket" when the search found no F.
  std::string rule;
  double factor = std::numeric_limits<double>::quiet_NaN();  ///< F (factor-of-safety measure)
  double maxDisplacement = 0;  ///< m, the largest monitor displacement after t = 0 (at F = 1)
  double runTime = 0;          ///< s of wall time; never part of a summary
  double weight = 1;           ///< importance sampling: SampleDesign::weight of its index
  int runs = 1;                ///< forward runs spent (a search's trials)
};

struct Interval {
  double low = 0, high = 1;
};

/// The Wilson score interval of a binomial proportion, `failures` of `n` (Wilson 1927;
/// Newcombe 1998, method 3). n = 0: [0, 1].
Interval wilsonInterval(int failures, int n, double z = kZ95);

/// β = Φ⁻¹(1 − Pf) = −Φ⁻¹(Pf): +∞ at Pf = 0, −∞ at Pf = 1.
double reliabilityIndex(double pf);

/// What a set of finished samples says, computed from them in index order only.
struct ProbabilitySummary {
  int planned = 0;       ///< N
  int finished = 0;      ///< samples with a result
  int converged = 0;     ///< stable + failing
  int notConverged = 0;
  int failures = 0;
  /// Sampling: failures / converged. Importance sampling (weighted): Σ w over the failing
  /// samples / converged, w the samples' weights.
  double pf = 0;
  /// Sampling: Wilson, 95 %, on the converged samples. Importance sampling: pf ± 1.96 standard
  /// errors (the normal approximation; its upper end NaN when no sample fails).
  Interval pfInterval;
  bool weighted = false;
  double pfStandardError = 0;  ///< importance sampling
  /// The estimate's standard error over Pf: √((1 − Pf)/(Pf n)) for sampling; NaN when no sample fails.
  double coefficientOfVariation = std::numeric_limits<double>::quiet_NaN();
  /// The non-converged samples counted as stable, and as failing, over all finished samples; and
  /// the Wilson interval from the lower end of the first to the upper end of the second.
  double pfNotConvergedStable = 0, pfNotConvergedFailing = 0;
  Interval pfBounds;
  double beta = 0;       ///< reliabilityIndex(pf)
  Interval betaInterval; ///< β at the ends of pfInterval
  /// Factor-of-safety measure: F over the converged samples.
  bool hasFactor = false;
  double factorMean = 0, factorSd = 0, factorMeanError = 0, factorMin = 0, factorMax = 0, factorMedian = 0;
  double betaMoments = 0;  ///< (mean F − 1) / sd F
  std::vector<std::pair<std::string, int>> rules;  ///< samples per deciding rule, by name
  /// Pf and its Wilson interval over the first m converged samples in index order, m = 1..converged.
  std::vector<double> runningPf, runningLow, runningHigh;
};

/// The summary of `samples` (sorted by index, as resumed or finished) of a study of `planned`
/// samples; `factor`: the factor-of-safety measure; `weights`: importance sampling's weight of
/// each sample (in the order of `samples`), none for plain sampling.
ProbabilitySummary summarise(const std::vector<SampleResult>& samples, int planned, bool factor,
                             const std::vector<double>* weights = nullptr);

}  // namespace ddaslope::calibration
