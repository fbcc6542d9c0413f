#pragma once
// A Gaussian-process surrogate of a scalar response (universal kriging with a linear trend), the
// model that active learning (active_learning.hpp) fits to factors of safety in the space of the
// study's standard normals.
//
// y(x) = β₀ + βᵀx + Z(x), Z a stationary Gaussian process of variance σ² and Matérn 5/2
// correlation with one length scale per dimension (Rasmussen & Williams 2006, eq. 4.17). Given
// the length scales, β (generalised least squares) and σ² have closed-form maximum-likelihood
// values; the length scales maximise the concentrated likelihood (Sacks, Welch, Mitchell & Wynn
// 1989; Lophaven, Nielsen & Søndergaard 2002, DACE). The linear trend carries a nearly planar
// limit state far from the points that were run, where a constant trend would reverse to the mean
// and call for runs in the safe far field.
//
// The fit is deterministic (fixed starting length scales, a derivative-free local optimiser), so
// the same points give the same surrogate on any thread count.
#include <vector>

#include <Eigen/Dense>

namespace ddaslope::calibration {

class Kriging {
 public:
  /// Fits the rows of `x` (n points × d dimensions, n ≥ d + 2, no two equal) and their values.
  void fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y);

  /// The posterior mean and standard deviation of the latent response at each column of `points`
  /// (d × m): the standard deviation is that of the process, without the small nugget that keeps
  /// the correlation matrix positive definite, so it is ~0 at the fitted points.
  void predict(const Eigen::MatrixXd& points, Eigen::VectorXd& mean, Eigen::VectorXd& sd) const;

  const Eigen::VectorXd& lengthScales() const { return lengthScales_; }
  double processVariance() const { return variance_; }
  /// The trend: β₀ then β, per unit of x.
  const Eigen::VectorXd& trend() const { return beta_; }
  /// The concentrated log-likelihood's value at the fitted length scales, up to a constant.
  double logLikelihood() const { return logLikelihood_; }

  /// The relative nugget added to the correlation matrix's diagonal.
  static constexpr double kNugget = 1e-9;

 private:
  /// −2 log L (concentrated) at the length scales exp(logScales), or +∞ when the correlation
  /// matrix is not numerically positive definite; with `keep`, the fit's factors are stored.
  double objective(const std::vector<double>& logScales, bool keep);
  /// The correlation of each column of `a` (d × m) with each fitted point: n × m.
  Eigen::MatrixXd correlations(const Eigen::MatrixXd& a) const;

  Eigen::MatrixXd x_;   ///< d × n
  Eigen::VectorXd y_;
  Eigen::VectorXd lengthScales_;
  Eigen::LLT<Eigen::MatrixXd> chol_;  ///< of R
  Eigen::MatrixXd trendSolved_;       ///< L⁻¹H, n × (d + 1)
  Eigen::LLT<Eigen::MatrixXd> trendChol_;  ///< of HᵀR⁻¹H
  Eigen::VectorXd weights_;           ///< R⁻¹(y − Hβ)
  Eigen::VectorXd beta_;
  double variance_ = 0;
  double logLikelihood_ = 0;
};

}  // namespace ddaslope::calibration
