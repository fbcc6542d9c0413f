#pragma once
// The block-on-incline scene of benchmarks.md §A–B, built in code (tests, comparison table).
#include "ddaslope/model/scene.hpp"

namespace ddaslope::model {

struct InclineSpec {
  double alphaDeg = 30;   ///< slope angle
  double b = 2;           ///< block length along the slope (m)
  double h = 1;           ///< block height (m)
  double phiDeg = 20;     ///< joint friction angle
  double cohesion = 0;    ///< Pa
  double density = 2600;  ///< kg/m³
  double g = 9.81;
  double young = 5e9;
  double duration = 1.0;
  double timeStep = 1e-3;
};

/// A fixed ramp whose top is the slope line through the origin and a b×h block on it, its
/// downslope corner 10 m up the slope. Monitors: "centre", "toe" (downslope corner), "top"
/// (upslope top corner).
Scene makeInclineScene(const InclineSpec& s);

/// Closed-form sliding acceleration g (sin α − cos α tan φ) (benchmarks.md A2).
double slidingAcceleration(const InclineSpec& s);
/// Closed-form critical cohesion (W sin α − W cos α tan φ)/b, 0 when friction alone holds (B1).
double criticalCohesion(const InclineSpec& s);

}  // namespace ddaslope::model
