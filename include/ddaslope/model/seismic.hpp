#pragma once
// Seismic loading (docs/seismic.md). Pseudo-static coefficients are a constant body force
// m·|g|·(k_h, k_v), part of the loads the slope must stand under, from its initial equilibrium
// on, as in limit equilibrium (a load switched on at once would ring the contact springs up to
// twice their static share and fail a slope short of its yield acceleration). A ground motion
// record acts from t = 0 of the analysis: the fixed blocks are the foundation and the ground moves
// them rigidly, so in their frame every movable block feels the inertial force −m·a_g(t).
#include <vector>

#include "ddaslope/core/types.hpp"

namespace ddaslope::model {

/// A ground acceleration history, linear between samples and zero outside them.
struct GroundMotion {
  std::vector<double> times;       ///< s of analysis time, increasing
  std::vector<double> horizontal;  ///< a_g along +x (m/s²)
  std::vector<double> vertical;    ///< a_g upward (m/s²); empty: none
  bool active() const { return !times.empty(); }
  /// a_g at time t (m/s²).
  Vec2 at(double t) const;
  /// The mean of a_g over [t0, t1] (m/s²): the exact integral of the piecewise-linear record over
  /// the interval, divided by its length. What a step from t0 to t1 applies: the impulse the
  /// record delivers in that step, whatever the record's sampling against the step.
  Vec2 meanOver(double t0, double t1) const;
};

struct SeismicLoad {
  double kh = 0;  ///< horizontal coefficient: a force k_h·m·|g| along +x (negative: along −x)
  double kv = 0;  ///< vertical coefficient: a force k_v·m·|g| upward (negative: downward)
  GroundMotion ground;
  bool active() const { return kh != 0 || kv != 0 || ground.active(); }
  /// The pseudo-static body acceleration (m/s²) under `gravity`: k_h·|g| along the horizontal
  /// (the model's +x turned to lie perpendicular to gravity) and k_v·|g| up (against gravity).
  Vec2 pseudoStatic(const Vec2& gravity) const;
  /// A (horizontal, up) pair of accelerations as a vector of the model's frame under `gravity`
  /// (the identity for gravity along −y).
  static Vec2 toModelFrame(const Vec2& horizontalUp, const Vec2& gravity);
};

}  // namespace ddaslope::model
