#pragma once
// Pore pressure from a grid of measured or computed points (x, y, p), as Slide2 and RS2 take it:
// a thin-plate spline through the points (Duchon 1977; Slide2's default interpolation),
// p(q) = a0 + a1 x + a2 y + Σ wᵢ φ(|q − qᵢ|), φ(r) = r² log r, with Σ wᵢ = Σ wᵢ xᵢ = Σ wᵢ yᵢ = 0.
// It passes through every point, is smooth between them, reproduces an affine field (a
// hydrostatic pressure under a planar water table) exactly everywhere, and extends beyond the
// points as their best-fitting plane. Negative values (suction) are taken as 0.
#include <vector>

#include "ddaslope/core/types.hpp"

namespace ddaslope::model {

class PressureGrid {
 public:
  /// Throws std::invalid_argument when the points do not determine the spline: fewer than three,
  /// all on one line, or two at one place (the reader checks these first, with their paths).
  PressureGrid(std::vector<Vec2> points, std::vector<double> pressures);
  /// Pressure at q (Pa), ≥ 0.
  double at(const Vec2& q) const;
  /// The spline's value at q, suction included (for tests).
  double spline(const Vec2& q) const;
  /// The same field with every point moved by d (a scene moved to its local origin).
  PressureGrid translated(const Vec2& d) const;
  const std::vector<Vec2>& points() const { return points_; }
  const std::vector<double>& pressures() const { return pressures_; }
  /// A typical distance between neighbouring points: √(bounding-box area / n).
  double spacing() const { return spacing_; }

 private:
  std::vector<Vec2> points_;
  std::vector<double> pressures_;
  std::vector<Vec2> scaled_;  ///< the points centred and scaled, as the spline takes them
  Vec2 centre_{0, 0};
  double scale_ = 1, spacing_ = 1;
  std::vector<double> weights_;  ///< wᵢ, then a0, a1, a2 (in centred, scaled coordinates)
};

}  // namespace ddaslope::model
