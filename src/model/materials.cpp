#include "ddaslope/model/materials.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace ddaslope::model {

JointProperties JointProperties::coulomb(std::string name, double frictionAngle, double cohesion,
                                         double tensileStrength) {
  JointProperties j;
  j.name = std::move(name);
  j.frictionAngle = frictionAngle;
  j.cohesion = cohesion;
  j.tensileStrength = tensileStrength;
  return j;
}

double JointProperties::residualFriction() const {
  return std::min(residualFrictionAngle.value_or(frictionAngle), frictionAngle);
}

double JointProperties::residualCohesionUsed() const { return std::min(residualCohesion, cohesion); }

JointProperties JointProperties::reducedBy(double factor) const {
  JointProperties j = *this;
  if (bartonBandis) {
    // tan(φr + JRC log10(JCS/σn)) / F: the mobilised angle's tangent, not φr's alone.
    j.bartonBandis->reduction *= factor;
    j.tensileStrength = tensileStrength / factor;
    return j;
  }
  j.cohesion = cohesion / factor;
  j.tensileStrength = tensileStrength / factor;
  j.frictionAngle = std::atan(std::tan(frictionAngle) / factor);
  j.residualCohesion = residualCohesion / factor;
  if (residualFrictionAngle) j.residualFrictionAngle = std::atan(std::tan(*residualFrictionAngle) / factor);
  return j;
}

}  // namespace ddaslope::model
