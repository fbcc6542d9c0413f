#pragma once
#include <string>

namespace ddaslope::model {

/// Rock material of a block (SI units).
struct Material {
  std::string name;
  double density = 0;       ///< kg/m³
  double youngModulus = 0;  ///< Pa
  double poissonRatio = 0;  ///< −
};

/// Mohr-Coulomb joint with tension cut-off. Angles are radians inside the code.
struct JointProperties {
  std::string name;
  double frictionAngle = 0;    ///< φ (rad)
  double cohesion = 0;         ///< c (Pa)
  double tensileStrength = 0;  ///< σt (Pa)
};

}  // namespace ddaslope::model
