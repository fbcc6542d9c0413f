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

ContactStrength contactStrength(const model::JointProperties& j, double intact, double length) {
  const double tanPeak = std::tan(j.frictionAngle), tanResidual = std::tan(j.residualFriction());
  const double cResidual = j.residualCohesionUsed();
  return {tanResidual + (tanPeak - tanResidual) * intact, (cResidual + (j.cohesion - cResidual) * intact) * length,
          j.tensileStrength * intact * length, distanceOf(j) > 0};
}

}  // namespace ddaslope::contact
