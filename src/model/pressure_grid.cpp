#include "ddaslope/model/pressure_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

namespace ddaslope::model {
namespace {

double kernel(double r2) { return r2 > 0 ? 0.5 * r2 * std::log(r2) : 0.0; }  // r² log r

}  // namespace

PressureGrid::PressureGrid(std::vector<Vec2> points, std::vector<double> pressures)
    : points_(std::move(points)), pressures_(std::move(pressures)) {
  const size_t n = points_.size();
  if (n < 3 || pressures_.size() != n) throw std::invalid_argument("a pressure grid needs at least three points");
  Vec2 lo = points_[0], hi = points_[0];
  for (const Vec2& p : points_) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  centre_ = 0.5 * (lo + hi);
  scale_ = std::max((hi - lo).maxCoeff(), 1e-300);
  const Vec2 extent = (hi - lo).cwiseMax(Vec2::Constant(1e-3 * scale_));
  spacing_ = std::sqrt(extent.x() * extent.y() / static_cast<double>(n));
  // The system [K P; Pᵀ 0] [w; a] = [p; 0] in coordinates centred on the points and scaled to
  // their extent (its conditioning does not depend on where the slope lies or its units).
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 3, n + 3);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 3);
  scaled_.resize(n);
  for (size_t i = 0; i < n; ++i) scaled_[i] = (points_[i] - centre_) / scale_;
  const std::vector<Vec2>& q = scaled_;
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) A(i, j) = kernel((q[i] - q[j]).squaredNorm());
    A(i, n) = A(n, i) = 1;
    A(i, n + 1) = A(n + 1, i) = q[i].x();
    A(i, n + 2) = A(n + 2, i) = q[i].y();
    b[i] = pressures_[i];
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (lu.rank() < static_cast<Eigen::Index>(n + 3))
    throw std::invalid_argument("the points do not determine a surface (all on one line, or two at one place)");
  const Eigen::VectorXd x = lu.solve(b);
  weights_.assign(x.data(), x.data() + x.size());
}

double PressureGrid::spline(const Vec2& at) const {
  const size_t n = points_.size();
  const Vec2 q = (at - centre_) / scale_;
  double v = weights_[n] + weights_[n + 1] * q.x() + weights_[n + 2] * q.y();
  for (size_t i = 0; i < n; ++i) v += weights_[i] * kernel((q - scaled_[i]).squaredNorm());
  return v;
}

double PressureGrid::at(const Vec2& q) const { return std::max(0.0, spline(q)); }

PressureGrid PressureGrid::translated(const Vec2& d) const {
  PressureGrid g = *this;
  for (Vec2& p : g.points_) p += d;
  g.centre_ += d;
  return g;
}

}  // namespace ddaslope::model
