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
};

struct SeismicLoad {
  double kh = 0;  ///< horizontal coefficient: a force k_h·m·|g| along +x (negative: along −x)
  double kv = 0;  ///< vertical coefficient: a force k_v·m·|g| upward (negative: downward)
  GroundMotion ground;
  bool active() const { return kh != 0 || kv != 0 || ground.active(); }
  /// The pseudo-static body acceleration (m/s²) for gravity of magnitude g.
  Vec2 pseudoStatic(double g) const { return {kh * g, kv * g}; }
};

}  // namespace ddaslope::model
