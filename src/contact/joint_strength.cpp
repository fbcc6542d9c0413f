#include "ddaslope/contact/joint_strength.hpp"

#include <algorithm>
#include <cmath>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/types.hpp"

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
  JointStrength s{std::tan(j.frictionAngle), std::tan(j.residualFriction()), j.cohesion, j.residualCohesionUsed(),
                  j.tensileStrength, distanceOf(j) > 0};
  if (j.bartonBandis) {
    s.bartonBandis = true;
    s.jrc = j.bartonBandis->jrc;
    s.jcs = j.bartonBandis->jcs;
    s.reduction = j.bartonBandis->reduction;
    s.jrcWears = j.bartonBandis->wears;
  }
  return s;
}

ContactStrength contactStrength(const JointStrength& j, double intact, double length) {
  ContactStrength s{j.tanResidual + (j.tanPeak - j.tanResidual) * intact,
                    (j.residualCohesion + (j.cohesion - j.residualCohesion) * intact) * length,
                    j.tensileStrength * intact * length, j.softens, j.tensileStrength > 0};
  if (j.bartonBandis) {
    s.bartonBandis = true;
    s.jrc = j.jrcWears ? j.jrc * intact : j.jrc;  // roughness worn away with slip, to φr alone
    s.jcs = j.jcs;
    s.length = length;
    s.reduction = j.reduction;
  }
  return s;
}

double ContactStrength::friction(double normalForce) const {
  if (!bartonBandis) return normalForce * tanPhi;
  const double phiR = std::atan(tanPhi);
  if (!(normalForce > 0) || !(length > 0)) return normalForce * tanPhi / reduction;
  const double kMaxAngle = degToRad(70);
  const double sigma = normalForce / length;
  const double angle = std::clamp(phiR + degToRad(jrc * std::log10(jcs / sigma)), phiR, std::max(phiR, kMaxAngle));
  return normalForce * std::tan(angle) / reduction;
}

}  // namespace ddaslope::contact
