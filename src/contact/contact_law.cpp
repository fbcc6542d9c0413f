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

std::pair<ContactJudgement, ContactJudgement> judgeEdgeContact(const HalfState& h1, const HalfState& h2,
                                                               const ContactResponse& r1,
                                                               const ContactResponse& r2,
                                                               const ContactStrength& whole,
                                                               const StateTolerance& tol) {
  const ContactStrength half{whole.tanPhi, whole.cohesionForce / 2, whole.tensileForce / 2};
  const auto alone = [&](const HalfState& h, const ContactResponse& r, bool bonded) {
    return judgeVertexContact(h.state, h.direction, bonded, r, half, tol);
  };
  if (h1.state == ContactState::Open || h2.state == ContactState::Open)
    return {alone(h1, r1, h1.bonded), alone(h2, r2, h2.bonded)};

  bool bonded = h1.bonded && h2.bonded;
  const double endTension = bonded ? half.tensileForce : 0.0;
  if (r1.normalForce < -endTension - tol.force || r2.normalForce < -endTension - tol.force) {
    // An end separates: the bond fails as a whole, the other half is the pivot.
    return {alone(h1, r1, false), alone(h2, r2, false)};
  }
  const double n = r1.normalForce + r2.normalForce;
  if (h1.state == ContactState::Sliding && h2.state == ContactState::Sliding && h1.direction == h2.direction) {
    const int dir = h1.direction;
    if ((r1.slip + r2.slip) * dir < -tol.slip) return {{ContactState::Locked, 0, false}, {ContactState::Locked, 0, false}};
    return {{ContactState::Sliding, dir, false}, {ContactState::Sliding, dir, false}};
  }
  // Locked (or halves in different states after a change of pairing): the shear each half carries,
  // a locked spring's force or a sliding half's friction, against the strength of the whole.
  const auto carried = [&](const HalfState& h, const ContactResponse& r) {
    return h.state == ContactState::Locked ? r.lockedShear : h.direction * whole.tanPhi * std::max(0.0, r.normalForce);
  };
  const double shear = carried(h1, r1) + carried(h2, r2);
  if (std::abs(shear) > shearStrength(bonded, n, whole) + tol.force) {
    const int dir = shear > 0 ? 1 : -1;
    return {{ContactState::Sliding, dir, false}, {ContactState::Sliding, dir, false}};
  }
  bonded = bonded && h1.state == ContactState::Locked && h2.state == ContactState::Locked;
  return {{ContactState::Locked, 0, bonded}, {ContactState::Locked, 0, bonded}};
}

ContactJudgement judgeHeldContact(ContactState state, bool bonded, const ContactResponse& r,
                                  const StateTolerance& tol) {
  if (state == ContactState::Open && r.normalForce <= tol.force) return {ContactState::Open, 0, bonded};
  return {ContactState::Locked, 0, bonded};
}
}  // namespace ddaslope::contact
