#pragma once
// The extremes on the A4 sliding block (α = 30°, benchmarks.md): sizes from 1 mm to
// 1 km, a 1e-3 sliver, E from 1 MPa to 1 TPa, density 1000 to 5000, φ from 0° to 85°, c up to
// 1e8 Pa, Δt from 1e-6 to 0.1 s. One list and one evaluation serve the test suite (which asserts)
// and `ddaslope_accuracy --extremes` (which prints the closed-form errors for docs/accuracy.md).
#include <string>
#include <vector>

#include "ddaslope/model/incline_scene.hpp"

namespace ddaslope::io {

struct ExtremeIncline {
  std::string name;
  model::InclineSpec spec;
  bool slides = true;  ///< tan α > tan φ and no cohesion: the closed form a t²/2 applies
};

/// The list, each a fast variant (at most a few thousand steps).
std::vector<ExtremeIncline> extremeInclines();

struct ExtremeResult {
  bool completed = false;
  std::string failure;
  bool finite = false;        ///< every monitor value of every step finite
  double slide = 0;           ///< centre travel from t = 0 after the equilibrium (m)
  double closedFormSlide = 0; ///< a t²/2 (m); a held block: 0
  /// Allowed |slide − closed form|: 1 % plus the shear springs' elastic elongation W sin α / p_s,
  /// released when the contact starts to slide. A held block: 1e-3 b.
  double slideTolerance = 0;
  double peakSpeed = 0, closedFormPeakSpeed = 0;  ///< m/s; the closed form a·t bounds it
  double energyGain = 0;      ///< largest rise of the mechanical energy above its start (J/m)
  double heldPotential = 0;   ///< |potential energy| at the start, the round-off scale (J/m)
  double energyLost = 0;      ///< mechanical energy at the start minus at the end (J/m)
  double frictionWork = 0;    ///< tan φ · W cos α · slide (J/m), for a sliding block
  double elasticRelease = 0;  ///< W sin α · the shear springs' elongation (J/m)
  double wallSeconds = 0;

  double slideError() const;  ///< |slide − closed form| / closed form (sliding), slide / b (held)
};

ExtremeResult runExtreme(const ExtremeIncline& x);

}  // namespace ddaslope::io
