#include "ddaslope/calibration/probability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/calibration/reliability.hpp"

namespace ddaslope::calibration {
namespace {

using model::Distribution;
using model::DistributionKind;

constexpr double kInf = std::numeric_limits<double>::infinity();

double normalPdf(double z) { return std::isfinite(z) ? std::exp(-0.5 * z * z) / std::sqrt(2 * M_PI) : 0.0; }

/// Polynomial a[0] + a[1] r + … + a[7] r^7 (Horner).
double poly7(const double (&a)[8], double r) {
  double v = a[7];
  for (int k = 6; k >= 0; --k) v = v * r + a[k];
  return v;
}

/// A stream of counterBits per purpose: input i's normals use stream i, its Latin-hypercube
/// permutation stream 2^32 + i.
constexpr std::uint64_t kPermutationStream = std::uint64_t{1} << 32;

__extension__ typedef unsigned __int128 Wide;  // GCC and Clang: 64 × 64 → 128-bit products

/// z of a point of [0, 1] given as k/N + v/N with v in (0, 1), through the nearer tail so that
/// the upper strata keep their precision: 1 − u is formed exactly as ((N − 1 − k) + (1 − v))/N.
double stratumNormal(int stratum, int n, double v) {
  const double lower = (stratum + v) / n;
  if (lower < 0.5) return normalQuantile(lower);
  return -normalQuantile(((n - 1 - stratum) + (1 - v)) / n);
}

/// A standard truncated normal on [a, b] at the standard normal z: Φ⁻¹ of Φ(a) + Φ(z)(Φ(b) − Φ(a)),
/// or of the same in upper-tail probabilities when the interval lies above the mean, where Φ
/// would round to 1.
double truncatedStandard(double a, double b, double z) {
  double x = 0;
  if (a > 0) {
    const double qa = normalCdf(-a), qb = normalCdf(-b);
    x = -normalQuantile(qb + normalCdf(-z) * (qa - qb));
  } else {
    const double pa = normalCdf(a), pb = normalCdf(b);
    x = normalQuantile(pa + normalCdf(z) * (pb - pa));
  }
  return std::clamp(x, a, b);
}

/// The lognormal's (μ, σ) of ln X from the mean and sd of X.
std::pair<double, double> logParameters(const Distribution& d) {
  const double s2 = std::log1p((d.sd / d.mean) * (d.sd / d.mean));
  return {std::log(d.mean) - 0.5 * s2, std::sqrt(s2)};
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

double normalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

double normalQuantile(double p) {
  // AS 241 (PPND16), coefficients as published (Wichura 1988, Appl. Statist. 37, 477-484).
  static constexpr double a[8] = {3.387132872796366608,  133.14166789178437745, 1971.5909503065514427,
                                  13731.693765509461125, 45921.953931549871457, 67265.770927008700853,
                                  33430.575583588128105, 2509.0809287301226727};
  static constexpr double b[8] = {1.0,                   42.313330701600911252, 687.1870074920579083,
                                  5394.1960214247511077, 21213.794301586595867, 39307.89580009271061,
                                  28729.085735721942674, 5226.495278852854561};
  static constexpr double c[8] = {1.42343711074968357734,   4.6303378461565452959,   5.7694972214606914055,
                                  3.64784832476320460504,   1.27045825245236838258,  0.24178072517745061177,
                                  0.0227238449892691845833, 7.7454501427834140764e-4};
  static constexpr double d[8] = {1.0,                      2.05319162663775882187,  1.6763848301838038494,
                                  0.68976733498510000455,   0.14810397642748007459,  0.0151986665636164571966,
                                  5.475938084995344946e-4,  1.05075007164441684324e-9};
  static constexpr double e[8] = {6.6579046435011037772,    5.4637849111641143699,   1.7848265399172913358,
                                  0.29656057182850489123,   0.026532189526576123093, 0.0012426609473880784386,
                                  2.71155556874348757815e-5, 2.01033439929228813265e-7};
  static constexpr double f[8] = {1.0,                      0.59983220655588793769,  0.13692988092273580531,
                                  0.0148753612908506148525, 7.868691311456132591e-4, 1.8463183175100546818e-5,
                                  1.4215117583164458887e-7, 2.04426310338993978564e-15};
  if (!(p > 0)) return p == 0 ? -kInf : std::numeric_limits<double>::quiet_NaN();
  if (!(p < 1)) return p == 1 ? kInf : std::numeric_limits<double>::quiet_NaN();
  const double q = p - 0.5;
  if (std::abs(q) <= 0.425) {
    const double r = 0.180625 - q * q;
    return q * poly7(a, r) / poly7(b, r);
  }
  double r = std::sqrt(-std::log(q < 0 ? p : 1 - p));
  const double v = r <= 5 ? poly7(c, r - 1.6) / poly7(d, r - 1.6) : poly7(e, r - 5) / poly7(f, r - 5);
  return q < 0 ? -v : v;
}

std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t counterBits(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return splitMix64(splitMix64(splitMix64(seed) ^ stream) ^ index);
}

double counterUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return (static_cast<double>(counterBits(seed, stream, index) >> 11) + 0.5) * 0x1.0p-53;
}

double valueAt(const Distribution& d, double z) {
  switch (d.kind) {
    case DistributionKind::Normal:
      return d.mean + d.sd * z;
    case DistributionKind::Lognormal: {
      const auto [mu, sigma] = logParameters(d);
      return std::exp(mu + sigma * z);
    }
    case DistributionKind::Uniform:
      // Through the nearer tail, so that the two ends are reached with equal precision.
      return z < 0 ? d.min + (d.max - d.min) * normalCdf(z) : d.max - (d.max - d.min) * normalCdf(-z);
    case DistributionKind::TruncatedNormal: {
      const double x = truncatedStandard((d.min - d.mean) / d.sd, (d.max - d.mean) / d.sd, z);
      return std::clamp(d.mean + d.sd * x, d.min, d.max);
    }
  }
  DDASLOPE_ASSERT(false, "unknown distribution kind");
}

namespace {

/// The mean and standard deviation of a marginal. A truncated normal's: Johnson, Kotz &
/// Balakrishnan (1994), eq. 13.134, with the mass through the nearer tail.
std::pair<double, double> moments(const Distribution& d) {
  switch (d.kind) {
    case DistributionKind::Normal:
    case DistributionKind::Lognormal:
      return {d.mean, d.sd};
    case DistributionKind::Uniform:
      return {0.5 * (d.min + d.max), (d.max - d.min) / std::sqrt(12.0)};
    case DistributionKind::TruncatedNormal: {
      const double a = (d.min - d.mean) / d.sd, b = (d.max - d.mean) / d.sd;
      const double mass = a > 0 ? normalCdf(-a) - normalCdf(-b) : normalCdf(b) - normalCdf(a);
      const double apa = std::isfinite(a) ? a * normalPdf(a) : 0, bpb = std::isfinite(b) ? b * normalPdf(b) : 0;
      const double shift = (normalPdf(a) - normalPdf(b)) / mass;
      return {d.mean + d.sd * shift, d.sd * std::sqrt(1 + (apa - bpb) / mass - shift * shift)};
    }
  }
  DDASLOPE_ASSERT(false, "unknown distribution kind");
}

}  // namespace

double distributionMean(const Distribution& d) { return moments(d).first; }

double distributionSd(const Distribution& d) { return moments(d).second; }

const char* name(DistributionKind kind) {
  switch (kind) {
    case DistributionKind::Normal: return "normal";
    case DistributionKind::Lognormal: return "lognormal";
    case DistributionKind::Uniform: return "uniform";
    case DistributionKind::TruncatedNormal: return "truncated_normal";
  }
  return "?";
}

const char* name(model::Sampling s) { return s == model::Sampling::MonteCarlo ? "monte_carlo" : "latin_hypercube"; }

const char* name(model::ProbabilityMeasure m) { return m == model::ProbabilityMeasure::Verdict ? "verdict" : "fos"; }
const char* name(model::ProbabilityMethod m) {
  switch (m) {
    case model::ProbabilityMethod::Sampling: return "sampling";
    case model::ProbabilityMethod::ImportanceSampling: return "importance_sampling";
    case model::ProbabilityMethod::ActiveLearning: return "active_learning";
  }
  return "?";
}

std::string describe(const Distribution& d) {
  const std::string kind = name(d.kind);
  switch (d.kind) {
    case DistributionKind::Normal:
    case DistributionKind::Lognormal:
      return kind + " (mean " + number(d.mean) + ", sd " + number(d.sd) + ")";
    case DistributionKind::Uniform:
      return kind + " [" + number(d.min) + ", " + number(d.max) + "]";
    case DistributionKind::TruncatedNormal:
      return kind + " (mean " + number(d.mean) + ", sd " + number(d.sd) + " before truncation to [" + number(d.min) +
             ", " + number(d.max) + "])";
  }
  return kind;
}

SampleDesign::SampleDesign(const model::ProbabilitySpec& spec)
    : inputs_(spec.inputs), samples_(spec.samples), sampling_(spec.sampling), seed_(spec.seed) {
  DDASLOPE_ASSERT(samples_ >= 1, "a study needs at least one sample");
  const int n = inputs();
  Eigen::MatrixXd r = Eigen::MatrixXd::Identity(n, n);
  for (const auto& c : spec.correlations) r(c.a, c.b) = r(c.b, c.a) = c.rho;
  const Eigen::LLT<Eigen::MatrixXd> llt(r);
  DDASLOPE_ASSERT(llt.info() == Eigen::Success, "the correlation matrix is not positive definite");
  const Eigen::MatrixXd l = llt.matrixL();
  cholesky_.resize(static_cast<size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) cholesky_[static_cast<size_t>(i) * n + j] = l(i, j);
  if (sampling_ != model::Sampling::LatinHypercube) return;
  permutations_.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    std::vector<int>& p = permutations_[static_cast<size_t>(i)];
    p.resize(static_cast<size_t>(samples_));
    std::iota(p.begin(), p.end(), 0);
    // Fisher–Yates; j uniform in [0, m] by Lemire's multiply-shift (bias below m/2^64).
    for (int m = samples_ - 1; m > 0; --m) {
      const Wide wide =
          static_cast<Wide>(counterBits(seed_, kPermutationStream + i, static_cast<std::uint64_t>(m))) *
          static_cast<std::uint64_t>(m + 1);
      std::swap(p[static_cast<size_t>(m)], p[static_cast<size_t>(wide >> 64)]);
    }
  }
}

std::vector<double> SampleDesign::independent(int index) const {
  DDASLOPE_ASSERT(index >= 0 && index < samples_, "sample index out of range");
  const int n = inputs();
  std::vector<double> z(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double v = counterUniform(seed_, static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(index));
    z[static_cast<size_t>(i)] = sampling_ == model::Sampling::LatinHypercube
                                    ? stratumNormal(permutations_[static_cast<size_t>(i)][static_cast<size_t>(index)], samples_, v)
                                    : stratumNormal(0, 1, v);
  }
  return z;
}

std::vector<double> SampleDesign::correlated(const std::vector<double>& u) const {
  const int n = inputs();
  std::vector<double> x(static_cast<size_t>(n), 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) x[static_cast<size_t>(i)] += cholesky_[static_cast<size_t>(i) * n + j] * u[static_cast<size_t>(j)];
  return x;
}

std::vector<double> SampleDesign::normals(int index) const {
  std::vector<double> u = independent(index);
  for (size_t i = 0; i < centre_.size(); ++i) u[i] += centre_[i];
  return correlated(u);
}

std::vector<double> SampleDesign::values(int index) const {
  std::vector<double> x = normals(index);
  for (size_t i = 0; i < x.size(); ++i) x[i] = valueAt(inputs_[i].distribution, x[i]);
  return x;
}

std::vector<double> SampleDesign::valuesAt(const std::vector<double>& u) const {
  std::vector<double> x = correlated(u);
  for (size_t i = 0; i < x.size(); ++i) x[i] = valueAt(inputs_[i].distribution, x[i]);
  return x;
}

double SampleDesign::weight(int index) const {
  return centre_.empty() ? 1.0 : importanceWeight(independent(index), centre_);
}

const char* name(SampleOutcome outcome) {
  switch (outcome) {
    case SampleOutcome::Stable: return "stable";
    case SampleOutcome::Fails: return "fails";
    case SampleOutcome::NotConverged: return "not_converged";
  }
  return "?";
}

Interval wilsonInterval(int failures, int n, double z) {
  if (n <= 0) return {0, 1};
  const double p = static_cast<double>(failures) / n, z2 = z * z;
  const double centre = (p + z2 / (2.0 * n)) / (1 + z2 / n);
  const double half = z / (1 + z2 / n) * std::sqrt(p * (1 - p) / n + z2 / (4.0 * n * n));
  // At 0 or n failures the interval ends exactly at 0 or 1 (round-off would leave ±1e-17).
  return {failures == 0 ? 0.0 : std::max(0.0, centre - half), failures == n ? 1.0 : std::min(1.0, centre + half)};
}

double reliabilityIndex(double pf) { return -normalQuantile(pf); }

namespace {

/// The mean of terms and its 95 % interval by the normal approximation (importance sampling).
struct MeanEstimate {
  double mean = 0, standardError = 0;
  Interval interval;
};

MeanEstimate meanOf(const std::vector<double>& terms) {
  MeanEstimate e;
  const double n = static_cast<double>(terms.size());
  if (terms.empty()) return {std::numeric_limits<double>::quiet_NaN(), 0, {0, 1}};
  double sum = 0;
  for (double t : terms) sum += t;
  e.mean = sum / n;
  double ss = 0;
  for (double t : terms) ss += (t - e.mean) * (t - e.mean);
  e.standardError = terms.size() > 1 ? std::sqrt(ss / (n - 1) / n) : 0;
  // No failing sample: the sample variance is 0 and says nothing about Pf's upper end.
  const bool none = sum == 0;
  e.interval = {std::max(0.0, e.mean - kZ95 * e.standardError),
                none ? std::numeric_limits<double>::quiet_NaN() : e.mean + kZ95 * e.standardError};
  return e;
}

}  // namespace

ProbabilitySummary summarise(const std::vector<SampleResult>& samples, int planned, bool factor,
                             const std::vector<double>* weights) {
  ProbabilitySummary s;
  s.planned = planned;
  s.finished = static_cast<int>(samples.size());
  s.hasFactor = factor;
  s.weighted = weights != nullptr;
  std::map<std::string, int> rules;
  std::vector<double> f;
  // Importance sampling: each sample's term I·w of Pf's estimate; and those with the
  // non-converged samples counted as stable and as failing, over every finished sample.
  std::vector<double> terms, asStable, asFailing;
  double runningMean = 0, runningSquares = 0;
  for (size_t k = 0; k < samples.size(); ++k) {
    const SampleResult& r = samples[k];
    const double w = weights ? (*weights)[k] : 1.0;
    ++rules[r.rule];
    asStable.push_back(r.outcome == SampleOutcome::Fails ? w : 0.0);
    asFailing.push_back(r.outcome != SampleOutcome::Stable ? w : 0.0);
    if (r.outcome == SampleOutcome::NotConverged) {
      ++s.notConverged;
      continue;
    }
    ++s.converged;
    s.failures += r.outcome == SampleOutcome::Fails;
    terms.push_back(r.outcome == SampleOutcome::Fails ? w : 0.0);
    if (s.weighted) {
      // The estimate after each converged sample, in index order (Welford's running variance).
      const double n = static_cast<double>(terms.size()), delta = terms.back() - runningMean;
      runningMean += delta / n;
      runningSquares += delta * (terms.back() - runningMean);
      const double se = n > 1 ? std::sqrt(runningSquares / (n - 1) / n) : 0;
      s.runningPf.push_back(runningMean);
      s.runningLow.push_back(std::max(0.0, runningMean - kZ95 * se));
      s.runningHigh.push_back(runningMean + kZ95 * se);
    } else {
      const Interval wi = wilsonInterval(s.failures, s.converged);
      s.runningPf.push_back(static_cast<double>(s.failures) / s.converged);
      s.runningLow.push_back(wi.low);
      s.runningHigh.push_back(wi.high);
    }
    if (factor && std::isfinite(r.factor)) f.push_back(r.factor);
  }
  s.rules.assign(rules.begin(), rules.end());
  if (s.weighted) {
    const MeanEstimate e = meanOf(terms);
    s.pf = e.mean;
    s.pfStandardError = e.standardError;
    s.pfInterval = e.interval;
    s.coefficientOfVariation = e.mean > 0 ? e.standardError / e.mean : std::numeric_limits<double>::quiet_NaN();
    if (s.finished > 0) {
      const MeanEstimate a = meanOf(asStable), b = meanOf(asFailing);
      s.pfNotConvergedStable = a.mean;
      s.pfNotConvergedFailing = b.mean;
      s.pfBounds = {a.interval.low, b.interval.high};
    }
  } else {
    s.pf = s.converged > 0 ? static_cast<double>(s.failures) / s.converged : std::numeric_limits<double>::quiet_NaN();
    s.pfInterval = wilsonInterval(s.failures, s.converged);
    if (s.converged > 0 && s.failures > 0)
      s.coefficientOfVariation = std::sqrt((1 - s.pf) / (s.pf * s.converged));
    if (s.finished > 0) {
      s.pfNotConvergedStable = static_cast<double>(s.failures) / s.finished;
      s.pfNotConvergedFailing = static_cast<double>(s.failures + s.notConverged) / s.finished;
      s.pfBounds = {wilsonInterval(s.failures, s.finished).low,
                    wilsonInterval(s.failures + s.notConverged, s.finished).high};
    }
  }
  s.beta = reliabilityIndex(s.pf);
  s.betaInterval = {reliabilityIndex(s.pfInterval.high), reliabilityIndex(s.pfInterval.low)};
  if (!f.empty()) {
    // Sums in index order: the same digits whatever finished first.
    double sum = 0;
    for (double v : f) sum += v;
    s.factorMean = sum / f.size();
    double ss = 0;
    for (double v : f) ss += (v - s.factorMean) * (v - s.factorMean);
    s.factorSd = f.size() > 1 ? std::sqrt(ss / (f.size() - 1)) : 0;
    s.factorMeanError = s.factorSd / std::sqrt(static_cast<double>(f.size()));
    std::vector<double> sorted = f;
    std::sort(sorted.begin(), sorted.end());
    s.factorMin = sorted.front();
    s.factorMax = sorted.back();
    const size_t m = sorted.size();
    s.factorMedian = m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);
    s.betaMoments = s.factorSd > 0 ? (s.factorMean - 1) / s.factorSd : std::numeric_limits<double>::quiet_NaN();
  }
  return s;
}

}  // namespace ddaslope::calibration
