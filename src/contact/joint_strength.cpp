#include "ddaslope/contact/joint_strength.hpp"

#include <algorithm>
#include <cmath>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::contact {

namespace {
double distanceOf(const model::JointProperties& j) {
  DDASLOPE_ASSERT(j.weakeningDistance.has_value(), "joint '" + j.name + "': weakening distance not resolved");
  return *j.weakeningDistance;
}
}  // namespace

double remainingStrength(const model::JointProperties& j, double slip) {
  const double distance = distanceOf(j);
  if (distance <= 0) return slip > 0 ? 0.0 : 1.0;
  const double x = slip / distance;
  return j.weakeningLaw == model::WeakeningLaw::Linear ? std::max(0.0, 1 - x) : std::exp(-x);
}

JointStrength jointStrength(const model::JointProperties& j) {
  return {std::tan(j.frictionAngle), std::tan(j.residualFriction()), j.cohesion, j.residualCohesionUsed(),
          j.tensileStrength, distanceOf(j) > 0};
}

ContactStrength contactStrength(const JointStrength& j, double intact, double length) {
  return {j.tanResidual + (j.tanPeak - j.tanResidual) * intact,
          (j.residualCohesion + (j.cohesion - j.residualCohesion) * intact) * length,
          j.tensileStrength * intact * length, j.softens};
}

}  // namespace ddaslope::contact
