#include "ddaslope/contact/contact_law.hpp"

#include <algorithm>
#include <cmath>

namespace ddaslope::contact {

double shearStrength(bool bonded, double normalForce, const ContactStrength& s) {
  if (bonded) return std::max(0.0, s.cohesionForce + s.friction(normalForce));
  return std::max(0.0, s.friction(std::max(0.0, normalForce)));
}

bool separatesWithBond(const ContactStrength& s) {
  // A bond with tensile strength that is pulled open has cracked: it is lost (original DDA,
  // UDEC's Coulomb slip). Without tensile strength (σt = 0) UDEC and original DDA drop the
  // cohesion at any separation too; a softening joint here keeps it until the opening reaches
  // its weakening distance (Simulation::commit). The reason is numerical: with penalty springs an
  // end of an edge contact opens as soon as its block turns by the springs' penetration over the
  // edge's length (0.15 mm over 50 m on the chair slide), and losing half the bond to that made a
  // slope's strength follow the ringing that smaller time steps leave undamped
  // (docs/contact-model.md, "Separation without tensile strength").
  return s.bondSurvivesSlip && !s.cracks;
}

ContactJudgement judgeVertexContact(ContactState state, int direction, bool bonded,
                                    const ContactResponse& r, const ContactStrength& s,
                                    const StateTolerance& tol) {
  if (state == ContactState::Open) {
    if (!(r.normalForce > tol.force)) return {ContactState::Open, 0, bonded};
    // Closing while its sides slide past each other faster than its strength could stop them
    // within the step (Coulomb's impact rule: the friction impulse falls short of the slip's
    // momentum): it closes sliding (ContactResponse::lockedShear of an open contact).
    if (std::abs(r.lockedShear) > shearStrength(bonded, r.normalForce, s) + tol.force)
      return {ContactState::Sliding, r.lockedShear > 0 ? 1 : -1, bonded && s.bondSurvivesSlip};
    return {ContactState::Locked, 0, bonded};
  }
  const double tensionCapacity = bonded ? s.tensileForce : 0.0;
  if (r.normalForce < -tensionCapacity - tol.force) return {ContactState::Open, 0, bonded && separatesWithBond(s)};
  const bool bondedWhileSliding = bonded && s.bondSurvivesSlip;
  if (state == ContactState::Locked) {
    if (std::abs(r.lockedShear) > shearStrength(bonded, r.normalForce, s) + tol.force)
      return {ContactState::Sliding, r.lockedShear > 0 ? 1 : -1, bondedWhileSliding};
    return {ContactState::Locked, 0, bonded};
  }
  // Sliding: resistance opposite to `direction`; a reversed slip means it has stopped the contact.
  if (r.slip * direction < -tol.slip) return {ContactState::Locked, 0, bondedWhileSliding};
  return {ContactState::Sliding, direction, bondedWhileSliding};
}

std::pair<ContactJudgement, ContactJudgement> judgeEdgeContact(const HalfState& h1, const HalfState& h2,
                                                               const ContactResponse& r1,
                                                               const ContactResponse& r2,
                                                               const ContactStrength& s1,
                                                               const ContactStrength& s2,
                                                               const StateTolerance& tol) {
  const auto alone = [&](const HalfState& h, const ContactResponse& r, const ContactStrength& s, bool bonded) {
    return judgeVertexContact(h.state, h.direction, bonded, r, s, tol);
  };
  if (h1.state == ContactState::Open || h2.state == ContactState::Open)
    return {alone(h1, r1, s1, h1.bonded), alone(h2, r2, s2, h2.bonded)};

  bool bonded = h1.bonded && h2.bonded;
  const bool open1 = r1.normalForce < -(bonded ? s1.tensileForce : 0.0) - tol.force;
  const bool open2 = r2.normalForce < -(bonded ? s2.tensileForce : 0.0) - tol.force;
  if (open1 || open2) {
    // An end separates and the other half is the pivot. A brittle bond fails as a whole (the
    // founding paper's rule). A softening joint's pivot keeps its own share of the bond (c·L/2, as
    // a vertex-to-edge contact); the end that opened keeps its share too if the joint has no
    // tensile strength to break (separatesWithBond).
    const bool softening = s1.bondSurvivesSlip && s2.bondSurvivesSlip;
    return {alone(h1, r1, s1, softening && (!open1 || separatesWithBond(s1)) && h1.bonded),
            alone(h2, r2, s2, softening && (!open2 || separatesWithBond(s2)) && h2.bonded)};
  }
  const bool bondedWhileSliding = bonded && s1.bondSurvivesSlip && s2.bondSurvivesSlip;
  if (h1.state == ContactState::Sliding && h2.state == ContactState::Sliding && h1.direction == h2.direction) {
    const int dir = h1.direction;
    const ContactJudgement stopped{ContactState::Locked, 0, bondedWhileSliding};
    if ((r1.slip + r2.slip) * dir < -tol.slip) return {stopped, stopped};
    const ContactJudgement sliding{ContactState::Sliding, dir, bondedWhileSliding};
    return {sliding, sliding};
  }
  // Locked (or halves in different states after a change of pairing): the shear each half carries,
  // a locked spring's force or a sliding half's resistance, against the strength of the whole.
  const auto carried = [&](const HalfState& h, const ContactResponse& r, const ContactStrength& s) {
    return h.state == ContactState::Locked ? r.lockedShear : h.direction * shearStrength(h.bonded, r.normalForce, s);
  };
  const double shear = carried(h1, r1, s1) + carried(h2, r2, s2);
  // The strength of the whole: c·L + Σ N_i tan φ_i. Each half's friction counts with its own
  // tan φ, as the sliding resistance does (halves of a softening joint have slipped different
  // distances): with one mean tan φ a locked pair could fail below the resistance it meets
  // once sliding, and stick and slip in turn for ever.
  const double friction = s1.friction(r1.normalForce) + s2.friction(r2.normalForce);
  const double strength = std::max(0.0, friction + (bonded ? s1.cohesionForce + s2.cohesionForce : 0.0));
  if (std::abs(shear) > strength + tol.force) {
    const int dir = shear > 0 ? 1 : -1;
    const ContactJudgement sliding{ContactState::Sliding, dir, bondedWhileSliding};
    return {sliding, sliding};
  }
  if (!(h1.state == ContactState::Locked && h2.state == ContactState::Locked)) bonded = bondedWhileSliding;
  return {{ContactState::Locked, 0, bonded}, {ContactState::Locked, 0, bonded}};
}

ContactJudgement judgeHeldContact(ContactState state, bool bonded, const ContactResponse& r,
                                  const StateTolerance& tol) {
  if (state == ContactState::Open && r.normalForce <= tol.force) return {ContactState::Open, 0, bonded};
  return {ContactState::Locked, 0, bonded};
}
}  // namespace ddaslope::contact
