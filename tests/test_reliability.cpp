// Small probabilities of failure (issue #42): FORM's design point found from binary verdicts along
// rays, and importance sampling around it, on limit states whose design point and Pf are known in
// closed form. The DDA cases (the planar failure) are in test_probability.cpp.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <numeric>

#include "ddaslope/calibration/probability.hpp"
#include "ddaslope/calibration/reliability.hpp"

using namespace ddaslope;
using calibration::PointVerdict;

namespace {

/// A limit state judged by `fails(u)`, every point accepted; counts its runs.
struct Synthetic {
  std::function<bool(const std::vector<double>&)> fails;
  std::atomic<int> runs{0};
  calibration::LimitState limit(int n) {
    calibration::LimitState l;
    l.dimensions = n;
    l.accepts = [](const std::vector<double>&) { return true; };
    l.judge = [this](const std::vector<double>& u) {
      ++runs;
      return fails(u) ? PointVerdict::Fails : PointVerdict::Stable;
    };
    return l;
  }
};

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  return std::inner_product(a.begin(), a.end(), b.begin(), 0.0);
}

std::vector<double> unit(std::vector<double> v) {
  const double n = std::sqrt(dot(v, v));
  for (double& x : v) x /= n;
  return v;
}

/// The importance-sampling estimate of P(fails) with `samples` Latin-hypercube samples of n
/// independent standard normals centred on the design point.
calibration::ProbabilitySummary importanceSample(const std::function<bool(const std::vector<double>&)>& fails, int n,
                                                 const std::vector<double>& centre, int samples, int seed = 1) {
  model::ProbabilitySpec spec;
  for (int i = 0; i < n; ++i) {
    model::UncertainInput in;
    in.path = std::string("u").append(std::to_string(i));
    in.distribution.mean = 0, in.distribution.sd = 1;
    spec.inputs.push_back(in);
  }
  spec.samples = samples;
  spec.seed = static_cast<std::uint64_t>(seed);
  calibration::SampleDesign design(spec);
  design.centreOn(centre);
  std::vector<calibration::SampleResult> results;
  std::vector<double> weights;
  for (int k = 0; k < samples; ++k) {
    calibration::SampleResult r;
    r.index = k;
    r.inputs = design.values(k);
    r.outcome = fails(r.inputs) ? calibration::SampleOutcome::Fails : calibration::SampleOutcome::Stable;
    results.push_back(r);
    weights.push_back(design.weight(k));
  }
  return calibration::summarise(results, samples, false, &weights);
}

}  // namespace

// A linear limit state a·u ≥ β (a a unit vector): the design point is β a exactly, and
// Pf = Φ(−β). The search resolves each ray's radius to 0.01 and settles the direction to
// 0.02 rad, so β within 0.01 and α within 0.02. In two and four dimensions.
TEST(Reliability, DesignPointOfALinearLimitState) {
  for (const std::vector<double>& a : {unit({0.6, -0.8}), unit({0.5, -0.5, 0.5, 0.5})}) {
    const double beta = 3.5;
    Synthetic s;
    s.fails = [&](const std::vector<double>& u) { return dot(a, u) >= beta; };
    const calibration::DesignPoint d = calibration::findDesignPoint(s.limit(static_cast<int>(a.size())), {});
    ASSERT_TRUE(d.found) << d.message;
    EXPECT_NEAR(d.beta, beta, 0.01);
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(d.alpha[i], a[i], 0.02) << i;
    EXPECT_TRUE(d.converged);
    EXPECT_TRUE(d.otherRegions.empty());
    EXPECT_EQ(d.runs, s.runs.load()) << "every run counted";
    std::printf("n = %zu: β %.4f (exact %.1f), %d runs on %d rays, %d secant steps\n", a.size(), d.beta, beta, d.runs,
                d.rays, d.steps);
  }
}

// A curved limit state u1 ≥ 3 + 0.1 u2² (a paraboloid bending away from the origin): the design
// point is (3, 0), and Pf = ∫ φ(u2) Φ(−(3 + 0.1 u2²)) du2 = 1.04360e-3 (Simpson below; scipy's
// quad alike to 1e-15; FORM's Φ(−3) = 1.350e-3 overestimates it by 29 %). Importance sampling with 2000 samples recovers the
// exact value within 4 of its own standard errors, and its 95 % interval covers it.
TEST(Reliability, ImportanceSamplingCorrectsFormOnACurvedLimitState) {
  const auto fails = [](const std::vector<double>& u) { return u[0] >= 3 + 0.1 * u[1] * u[1]; };
  double exact = 0;
  const int m = 4000;
  const double h = 20.0 / m;
  for (int k = 0; k <= m; ++k) {
    const double x = -10 + k * h;
    exact += (k == 0 || k == m ? 1 : k % 2 ? 4 : 2) * std::exp(-0.5 * x * x) / std::sqrt(2 * M_PI) *
             calibration::normalCdf(-(3 + 0.1 * x * x));
  }
  exact *= h / 3;
  EXPECT_NEAR(exact, 1.0435987587942798e-3, 1e-12);
  Synthetic s;
  s.fails = fails;
  const calibration::DesignPoint d = calibration::findDesignPoint(s.limit(2), {});
  ASSERT_TRUE(d.found);
  EXPECT_NEAR(d.beta, 3, 0.01);
  EXPECT_NEAR(d.u[1], 0, 0.1);
  const calibration::ProbabilitySummary is = importanceSample(fails, 2, d.u, 2000);
  EXPECT_NEAR(is.pf, exact, 4 * is.pfStandardError);
  EXPECT_LE(is.pfInterval.low, exact);
  EXPECT_GE(is.pfInterval.high, exact);
  EXPECT_LT(is.coefficientOfVariation, 0.1);
  std::printf("Pf %.4e ± %.2e (CoV %.3f), exact %.4e, FORM %.4e; design point %d runs\n", is.pf, is.pfStandardError,
              is.coefficientOfVariation, exact, calibration::normalCdf(-d.beta), d.runs);
}

// The estimator is unbiased whatever its centre: centred off the design point (here on the
// origin, which is plain Monte Carlo with weights 1, and half-way), the same exact Pf = Φ(−3.5)
// lies within 4 standard errors; the origin's estimate is the plain fraction of failures.
TEST(Reliability, WeightsKeepTheEstimateUnbiasedAnywhere) {
  const std::vector<double> a = unit({1, 1});
  const auto fails = [&](const std::vector<double>& u) { return dot(a, u) >= 2.5; };
  const double exact = calibration::normalCdf(-2.5);
  for (double shift : {0.0, 1.25, 2.5}) {
    const calibration::ProbabilitySummary is = importanceSample(fails, 2, {shift * a[0], shift * a[1]}, 20000, 3);
    EXPECT_NEAR(is.pf, exact, 4 * is.pfStandardError) << shift;
    if (shift == 0) {
      EXPECT_DOUBLE_EQ(is.pf, static_cast<double>(is.failures) / is.converged);
    }
  }
}

// With correlated inputs x = L u, a limit state linear in x, c·x ≥ b, has its design point along
// Lᵀc in u, and the importance vector γ = L⁻ᵀα / |L⁻ᵀα| is c/|c|: the sensitivities are those of
// the inputs themselves, not of the independent normals (Der Kiureghian 2005).
TEST(Reliability, ImportanceVectorOfCorrelatedInputs) {
  const double rho = -0.5;
  const std::vector<double> lower = {1, 0, rho, std::sqrt(1 - rho * rho)};  // L, row-major
  const std::vector<double> c = {0.3, 1.0};
  const std::vector<double> ltc = {lower[0] * c[0] + lower[2] * c[1], lower[3] * c[1]};
  const std::vector<double> gamma = calibration::importanceVector(unit(ltc), lower);
  const std::vector<double> expected = unit(c);
  EXPECT_NEAR(gamma[0], expected[0], 1e-12);
  EXPECT_NEAR(gamma[1], expected[1], 1e-12);
}

// No design point: a slope that fails at the medians (failure is not rare: sampling answers), and
// one that never fails within the search's radius along any axis or diagonal, are reported, not
// guessed.
TEST(Reliability, NoDesignPointIsReported) {
  Synthetic always, never;
  always.fails = [](const std::vector<double>&) { return true; };
  never.fails = [](const std::vector<double>&) { return false; };
  const calibration::DesignPoint a = calibration::findDesignPoint(always.limit(2), {});
  EXPECT_FALSE(a.found);
  EXPECT_NE(a.message.find("does not stand at the inputs' medians"), std::string::npos) << a.message;
  EXPECT_EQ(a.runs, 1);
  const calibration::DesignPoint n = calibration::findDesignPoint(never.limit(3), {});
  EXPECT_FALSE(n.found);
  EXPECT_NE(n.message.find("no run failed"), std::string::npos) << n.message;
  EXPECT_EQ(n.runs, 1 + 6 + 8) << "the origin, 6 axis ends and 8 diagonal ends";
}

// Failure on both sides (|u1| ≥ 3: two design points at ±3 e1): the search finds one and reports
// the other region, since importance sampling around one would miss half of Pf.
TEST(Reliability, ASecondFailureRegionIsReported) {
  Synthetic s;
  s.fails = [](const std::vector<double>& u) { return std::abs(u[0]) >= 3; };
  const calibration::DesignPoint d = calibration::findDesignPoint(s.limit(2), {});
  ASSERT_TRUE(d.found);
  EXPECT_NEAR(d.beta, 3, 0.01);
  EXPECT_EQ(d.otherRegions.size(), 1u);
}

// A ray ends where the case stops accepting the inputs (a cohesion below 0): beyond it nothing is
// judged, and a limit state lying past it is not found there.
TEST(Reliability, RaysEndWhereTheCaseRefusesTheInputs) {
  Synthetic s;
  s.fails = [](const std::vector<double>& u) { return u[0] <= -2; };
  calibration::LimitState l = s.limit(1);
  int judgedBeyond = 0;
  l.accepts = [](const std::vector<double>& u) { return u[0] > -4; };
  const auto judge = l.judge;
  l.judge = [&](const std::vector<double>& u) {
    judgedBeyond += u[0] <= -4;
    return judge(u);
  };
  const calibration::DesignPoint d = calibration::findDesignPoint(l, {});
  ASSERT_TRUE(d.found);
  EXPECT_NEAR(d.beta, 2, 0.01);
  EXPECT_EQ(judgedBeyond, 0);
  s.fails = [](const std::vector<double>& u) { return u[0] <= -5; };
  EXPECT_FALSE(calibration::findDesignPoint(l, {}).found);
}
