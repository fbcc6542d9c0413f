#include "ddaslope/calibration/kriging.hpp"

#include <cmath>
#include <limits>

#include <nlopt.hpp>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::calibration {
namespace {

/// Matérn 5/2 at the scaled distance r.
double matern52(double r) {
  const double s = std::sqrt(5.0) * r;
  return (1 + s + s * s / 3) * std::exp(-s);
}

/// The trend's basis at the columns of x: rows [1, xᵀ].
Eigen::MatrixXd trendBasis(const Eigen::MatrixXd& x) {
  Eigen::MatrixXd h(x.cols(), x.rows() + 1);
  h.col(0).setOnes();
  h.rightCols(x.rows()) = x.transpose();
  return h;
}

// Length scales searched, in units of the standard normals: from a twentieth of a standard
// deviation (a response that turns within the population's spread) to 50 (a plane: the trend
// alone).
constexpr double kMinScale = 0.05, kMaxScale = 50;

}  // namespace

Eigen::MatrixXd Kriging::correlations(const Eigen::MatrixXd& a) const {
  const Eigen::Index n = x_.cols(), m = a.cols();
  Eigen::MatrixXd k(n, m);
  const Eigen::ArrayXd inv = lengthScales_.array().inverse();
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = 0; i < n; ++i)
      k(i, j) = matern52(((x_.col(i) - a.col(j)).array() * inv).matrix().norm());
  return k;
}

double Kriging::objective(const std::vector<double>& logScales, bool keep) {
  const Eigen::Index n = x_.cols(), d = x_.rows();
  for (Eigen::Index k = 0; k < d; ++k) lengthScales_[k] = std::exp(logScales[static_cast<size_t>(k)]);
  Eigen::MatrixXd r = correlations(x_);
  r.diagonal().array() += kNugget;
  Eigen::LLT<Eigen::MatrixXd> chol(r);
  if (chol.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const auto lower = chol.matrixL();
  Eigen::MatrixXd lh = lower.solve(trendBasis(x_));
  const Eigen::VectorXd ly = lower.solve(y_);
  Eigen::LLT<Eigen::MatrixXd> g(lh.transpose() * lh);
  if (g.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const Eigen::VectorXd beta = g.solve(lh.transpose() * ly);
  const Eigen::VectorXd res = ly - lh * beta;
  // A response the trend fits exactly has σ² = 0: floored so that the likelihood stays finite.
  const double scale = std::max(y_.squaredNorm() / static_cast<double>(n), 1e-300);
  const double variance = std::max(res.squaredNorm() / static_cast<double>(n), 1e-14 * scale);
  double logDet = 0;
  for (Eigen::Index i = 0; i < n; ++i) logDet += 2 * std::log(chol.matrixLLT()(i, i));
  const double value = static_cast<double>(n) * std::log(variance) + logDet;
  if (!std::isfinite(value)) return std::numeric_limits<double>::infinity();
  if (keep) {
    chol_ = chol;
    trendSolved_ = std::move(lh);
    trendChol_ = g;
    beta_ = beta;
    weights_ = lower.transpose().solve(res);
    variance_ = variance;
    logLikelihood_ = -0.5 * value;
  }
  return value;
}

void Kriging::fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  const Eigen::Index d = x.cols(), n = x.rows();
  DDASLOPE_ASSERT(n == y.size() && n >= d + 2, "kriging needs at least d + 2 points");
  x_ = x.transpose();
  y_ = y;
  lengthScales_.resize(d);
  const auto f = [](const std::vector<double>& v, std::vector<double>&, void* self) {
    return static_cast<Kriging*>(self)->objective(v, false);
  };
  // Three starts (fine, unit and broad scales), each refined by BOBYQA: the likelihood of a few
  // dozen points often has more than one local optimum.
  std::vector<double> best;
  double bestValue = std::numeric_limits<double>::infinity();
  for (double start : {0.3, 1.0, 3.0}) {
    std::vector<double> v(static_cast<size_t>(d), std::log(start));
    nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(d));
    opt.set_lower_bounds(std::vector<double>(static_cast<size_t>(d), std::log(kMinScale)));
    opt.set_upper_bounds(std::vector<double>(static_cast<size_t>(d), std::log(kMaxScale)));
    opt.set_min_objective(f, this);
    opt.set_maxeval(60 * static_cast<int>(d) + 40);
    opt.set_xtol_abs(1e-3);
    double value = std::numeric_limits<double>::infinity();
    try {
      opt.optimize(v, value);
    } catch (const std::exception&) {
      // Round-off or an infinite objective at BOBYQA's trial point: keep the best point it reached.
      value = objective(v, false);
    }
    if (value < bestValue) bestValue = value, best = v;
  }
  if (!std::isfinite(bestValue)) best.assign(static_cast<size_t>(d), std::log(kMaxScale));
  if (!std::isfinite(objective(best, true)))
    throw NonConvergenceError("kriging: the correlation matrix of the points run is not positive definite (two points "
                         "nearly equal)");
}

void Kriging::predict(const Eigen::MatrixXd& points, Eigen::VectorXd& mean, Eigen::VectorXd& sd) const {
  const Eigen::MatrixXd k = correlations(points);
  const Eigen::MatrixXd h = trendBasis(points);
  mean = h * beta_ + k.transpose() * weights_;
  const Eigen::MatrixXd v = chol_.matrixL().solve(k);
  // The trend's share of the variance: w = h − (L⁻¹H)ᵀ v, wᵀ(HᵀR⁻¹H)⁻¹w.
  const Eigen::MatrixXd w = h.transpose() - trendSolved_.transpose() * v;
  const Eigen::MatrixXd gw = trendChol_.solve(w);
  sd.resize(points.cols());
  for (Eigen::Index j = 0; j < points.cols(); ++j) {
    const double s = 1 - v.col(j).squaredNorm() + w.col(j).dot(gw.col(j));
    sd[j] = std::sqrt(std::max(0.0, variance_ * s));
  }
}

}  // namespace ddaslope::calibration
