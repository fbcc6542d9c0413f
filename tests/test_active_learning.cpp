// Active learning (AK-MCS) and its kriging surrogate, on limit states whose classification of
// every population point is known exactly: the surrogate must reproduce it with a few dozen
// evaluations, in every failure region.
#include <gtest/gtest.h>

#include <cmath>

#include "ddaslope/calibration/active_learning.hpp"
#include "ddaslope/calibration/kriging.hpp"
#include "ddaslope/calibration/probability.hpp"

using namespace ddaslope;
using calibration::ActiveLearningProblem;
using calibration::ActiveLearningResult;
using calibration::ActiveLearningSettings;
using calibration::PerformanceValue;
using calibration::PointVerdict;

namespace {

/// n standard normal points in d dimensions from the study's counter generator (seed 7).
Eigen::MatrixXd normals(int d, int n, std::uint64_t seed = 7) {
  Eigen::MatrixXd u(d, n);
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < d; ++i)
      u(i, k) = calibration::normalQuantile(calibration::counterUniform(seed, static_cast<std::uint64_t>(i),
                                                                        static_cast<std::uint64_t>(k)));
  return u;
}

struct Learnt {
  ActiveLearningResult result;
  int exactFailing = 0;  ///< population points with g < 0
};

/// Active learning on the limit state g (margin g, fails where g < 0) over a population of n.
Learnt learn(const std::function<double(const Eigen::VectorXd&)>& g, int d, int n, int threads = 1) {
  ActiveLearningProblem p;
  p.population = normals(d, n);
  p.evaluate = [&](int k) {
    PerformanceValue v;
    v.converged = true;
    v.margin = g(p.population.col(k));
    v.fails = v.margin < 0;
    v.runs = 1;
    return v;
  };
  p.judge = [&](int k) { return g(p.population.col(k)) < 0 ? PointVerdict::Fails : PointVerdict::Stable; };
  ActiveLearningSettings s;
  s.threads = threads;
  Learnt r;
  r.result = calibration::learnFailureDomain(p, s);
  for (int k = 0; k < n; ++k) r.exactFailing += g(p.population.col(k)) < 0;
  return r;
}

}  // namespace

// Universal kriging with a linear trend reproduces a plane exactly (the generalised least-squares
// trend fits it with zero residual), and interpolates its points.
TEST(Kriging, ReproducesAPlaneAndInterpolatesItsPoints) {
  const Eigen::MatrixXd x = normals(2, 12).transpose();
  Eigen::VectorXd y(12);
  for (int i = 0; i < 12; ++i) y[i] = 1 + 2 * x(i, 0) - 0.5 * x(i, 1);
  calibration::Kriging k;
  k.fit(x, y);
  const Eigen::MatrixXd at = normals(2, 50, 11);
  Eigen::VectorXd mean, sd;
  k.predict(at, mean, sd);
  for (int j = 0; j < 50; ++j) EXPECT_NEAR(mean[j], 1 + 2 * at(0, j) - 0.5 * at(1, j), 1e-6);
  k.predict(x.transpose(), mean, sd);
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(mean[i], y[i], 1e-6);
}

// A curved response (sin x₁ + x₂²/2) from 40 points: the prediction's error is small inside the
// points' spread, and its own standard deviation covers it (≥ 90 % within 3 sd, which a
// calibrated Gaussian process gives 99.7 %).
TEST(Kriging, PredictsACurvedResponseWithCalibratedUncertainty) {
  const Eigen::MatrixXd x = normals(2, 40).transpose();
  const auto f = [](double a, double b) { return std::sin(a) + 0.5 * b * b; };
  Eigen::VectorXd y(40);
  for (int i = 0; i < 40; ++i) y[i] = f(x(i, 0), x(i, 1));
  calibration::Kriging k;
  k.fit(x, y);
  const Eigen::MatrixXd at = normals(2, 400, 13);
  Eigen::VectorXd mean, sd;
  k.predict(at, mean, sd);
  int covered = 0, inside = 0;
  double worst = 0;
  for (int j = 0; j < 400; ++j) {
    if (at.col(j).norm() > 1.5) continue;
    ++inside;
    const double err = std::abs(mean[j] - f(at(0, j), at(1, j)));
    worst = std::max(worst, err);
    covered += err <= 3 * sd[j] + 1e-9;
  }
  EXPECT_LT(worst, 0.05);
  EXPECT_GE(covered, 0.9 * inside);
}

// A plane at β = 3 (Pf = Φ(−3) = 1.35e-3): the surrogate learns it from the initial points, and
// classifies every one of 20 000 population points as the limit state does.
TEST(ActiveLearning, ClassifiesAPlaneExactly) {
  const Learnt r = learn([](const Eigen::VectorXd& u) { return 3 - (0.6 * u[0] + 0.8 * u[1]); }, 2, 20000);
  EXPECT_TRUE(r.result.learnt);
  EXPECT_EQ(r.result.failing, r.exactFailing);
  EXPECT_GT(r.exactFailing, 0);
  EXPECT_LE(r.result.searches, 30);
  EXPECT_EQ(r.result.disagreements, 0);
}

// Echard, Gayton & Lemaire (2011), example 1: a series system of four branches,
//   g = min{3 + 0.1(u₁ − u₂)² ∓ (u₁ + u₂)/√2, ±(u₁ − u₂) + 6/√2},
// failing in four separate regions (importance sampling around one design point sees one). The
// paper's AK-MCS+U finds Pf = 4.416e-3 with 126 evaluations on 10⁶ points. Here 20 000 points: the
// surrogate must classify them as g does to within 1 % of the failing count, with at most 200
// evaluations, and the population's Wilson interval must cover the paper's 10⁶-point Pf.
TEST(ActiveLearning, FindsEveryBranchOfAFourBranchSeriesSystem) {
  const auto g = [](const Eigen::VectorXd& u) {
    const double a = 3 + 0.1 * (u[0] - u[1]) * (u[0] - u[1]), s = (u[0] + u[1]) / std::sqrt(2.0);
    const double c = 6 / std::sqrt(2.0);
    return std::min(std::min(a - s, a + s), std::min((u[0] - u[1]) + c, (u[1] - u[0]) + c));
  };
  const Learnt r = learn(g, 2, 20000, 2);
  EXPECT_TRUE(r.result.learnt);
  EXPECT_NEAR(r.result.failing, r.exactFailing, 0.01 * r.exactFailing);
  EXPECT_LE(r.result.searches, 200);
  const calibration::LearnedProbability p = calibration::probabilityOf(r.result);
  EXPECT_LE(p.interval.low, 4.416e-3);
  EXPECT_GE(p.interval.high, 4.416e-3);
  // Each of the four regions holds failing points classified as such.
  int quadrants[4] = {0, 0, 0, 0};
  const Eigen::MatrixXd u = normals(2, 20000);
  for (int k = 0; k < 20000; ++k)
    if (r.result.fails[static_cast<size_t>(k)]) {
      const double s = u(0, k) + u(1, k), t = u(0, k) - u(1, k);
      ++quadrants[std::abs(s) > std::abs(t) ? (s > 0 ? 0 : 1) : (t > 0 ? 2 : 3)];
    }
  for (int q : quadrants) EXPECT_GT(q, 0);
}

// Failure at both ends of one input (|u₁| > 3: Pf = 2Φ(−3) = 2.70e-3), the case importance
// sampling warns about: both tails are classified, and the answer is the same on 1 and 2 threads.
TEST(ActiveLearning, FailureAtBothEndsOfAnInputIsCountedOnAnyThreadCount) {
  const auto g = [](const Eigen::VectorXd& u) { return 3 - std::abs(u[0]) + 0.0 * u[1]; };
  const Learnt one = learn(g, 2, 20000, 1), two = learn(g, 2, 20000, 2);
  EXPECT_TRUE(one.result.learnt);
  EXPECT_NEAR(one.result.failing, one.exactFailing, 0.02 * one.exactFailing + 1);
  EXPECT_EQ(one.result.failing, two.result.failing);
  EXPECT_EQ(one.result.searches, two.result.searches);
  EXPECT_EQ(one.result.fails, two.result.fails);
}

// The confirmation catches a surrogate that is sure and wrong: a limit state with a narrow
// failing pocket that no initial point sees (g < 0 only within 0.3 of u = (1.5, 0)). The
// confirmation verdicts must report any contradiction, and the final classification must still
// not claim a failure where g has none.
TEST(ActiveLearning, ConfirmationVerdictsAreReportedAndNeverInventFailures) {
  const auto g = [](const Eigen::VectorXd& u) {
    return std::hypot(u[0] - 1.5, u[1]) - 0.3 + 0.0 * u[0];
  };
  const Learnt r = learn(g, 2, 5000);
  EXPECT_GE(r.result.verdicts, 1);
  int wrongFailing = 0;
  const Eigen::MatrixXd u = normals(2, 5000);
  for (int k = 0; k < 5000; ++k) wrongFailing += r.result.fails[static_cast<size_t>(k)] && g(u.col(k)) >= 0;
  EXPECT_LE(wrongFailing, r.result.unsureFailing);
  EXPECT_TRUE(r.result.learnt);
  EXPECT_NEAR(r.result.failing, r.exactFailing, 0.05 * r.exactFailing + 2);
}

// A point that was run counts by its run, whatever the surrogate says: with the search budget
// spent on the first searches, verdicts that contradict the surrogate (here every verdict says
// "fails") cannot be searched, yet each of those points must be classified failing, and the
// learning must say it did not finish.
TEST(ActiveLearning, APointThatWasRunKeepsItsVerdictWhenTheBudgetIsSpent) {
  ActiveLearningProblem p;
  p.population = normals(2, 2000);
  p.evaluate = [&](int k) {
    PerformanceValue v;
    v.converged = true;
    v.margin = 3 - p.population(0, k);
    v.fails = v.margin < 0;
    v.runs = 1;
    return v;
  };
  p.judge = [](int) { return PointVerdict::Fails; };
  ActiveLearningSettings s;
  s.maxSearches = 12;
  const ActiveLearningResult r = calibration::learnFailureDomain(p, s);
  EXPECT_FALSE(r.learnt);
  EXPECT_EQ(r.searches, 12);
  int judged = 0;
  for (const calibration::LearnedPoint& lp : r.points)
    if (lp.role == calibration::LearnedRole::Confirmation) {
      ++judged;
      EXPECT_TRUE(r.fails[static_cast<size_t>(lp.index)]) << "population point " << lp.index;
    }
  EXPECT_GT(judged, 0);
  EXPECT_GT(r.disagreements, 0);
}

// Too few of the first searches converge to fit the surrogate (d + 2 = 4 are needed): the
// learning says why, fits nothing and classifies nothing as failing by default.
TEST(ActiveLearning, TooFewConvergedSearchesAreReportedNotClassified) {
  ActiveLearningProblem p;
  p.population = normals(2, 500);
  p.evaluate = [](int k) {
    PerformanceValue v;
    v.converged = k < 2;
    v.margin = -1;
    v.fails = true;
    v.runs = 1;
    return v;
  };
  p.judge = [](int) { return PointVerdict::Fails; };
  const ActiveLearningResult r = calibration::learnFailureDomain(p, ActiveLearningSettings{});
  EXPECT_FALSE(r.learnt);
  EXPECT_EQ(r.rounds, 0);
  EXPECT_NE(r.message.find("only 2 of the first searches converged"), std::string::npos) << r.message;
  EXPECT_EQ(r.notConverged, 10);
}
