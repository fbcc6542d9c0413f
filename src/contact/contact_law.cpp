#include "ddaslope/contact/contact_law.hpp"

#include <algorithm>
#include <cmath>

namespace ddaslope::contact {

double shearStrength(bool bonded, double normalForce, const ContactStrength& s) {
  if (bonded) return std::max(0.0, s.cohesionForce + normalForce * s.tanPhi);
  return std::max(0.0, normalForce) * s.tanPhi;
}

ContactJudgement judgeVertexContact(ContactState state, int direction, bool bonded,
                                    const ContactResponse& r, const ContactStrength& s,
                                    const StateTolerance& tol) {
  if (state == ContactState::Open) {
    if (r.normalForce > tol.force) return {ContactState::Locked, 0, bonded};
    return {ContactState::Open, 0, bonded};
  }
  const double tensionCapacity = bonded ? s.tensileForce : 0.0;
  if (r.normalForce < -tensionCapacity - tol.force) return {ContactState::Open, 0, false};
  if (state == ContactState::Locked) {
    if (std::abs(r.lockedShear) > shearStrength(bonded, r.normalForce, s) + tol.force)
      return {ContactState::Sliding, r.lockedShear > 0 ? 1 : -1, false};
    return {ContactState::Locked, 0, bonded};
  }
  // Sliding: friction opposite to `direction`; a reversed slip means friction has stopped it.
  if (r.slip * direction < -tol.slip) return {ContactState::Locked, 0, false};
  return {ContactState::Sliding, direction, false};
}

ContactJudgement judgeHeldContact(ContactState state, bool bonded, const ContactResponse& r,
                                  const StateTolerance& tol) {
  if (state == ContactState::Open && r.normalForce <= tol.force) return {ContactState::Open, 0, bonded};
  return {ContactState::Locked, 0, bonded};
}
}  // namespace ddaslope::contact
