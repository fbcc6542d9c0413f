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

/// Which contacts of a joint are intact (carry c and σt) when they form.
enum class BondPolicy {
  Initial,  ///< contacts touching at t = 0 are intact; contacts formed later are not
  None,     ///< never intact: friction only
  Always,   ///< contacts formed later are intact too (a cementing joint)
};

/// Mohr-Coulomb joint with tension cut-off. Angles are radians inside the code.
struct JointProperties {
  std::string name;
  double frictionAngle = 0;    ///< φ (rad)
  double cohesion = 0;         ///< c (Pa)
  double tensileStrength = 0;  ///< σt (Pa)
  BondPolicy bond = BondPolicy::Initial;
};

}  // namespace ddaslope::model
