#pragma once
// Contact-state rules of the open-close iteration (pure functions, dda-method.md §4).
#include "ddaslope/contact/contact.hpp"

namespace ddaslope::contact {

/// Strength of one contact while intact: c·Lc and σt·Lc as forces per metre of thickness.
struct ContactStrength {
  double tanPhi = 0;
  double cohesionForce = 0;   ///< N/m, acts only while bonded
  double tensileForce = 0;    ///< N/m, acts only while bonded
};

/// Round-off guard: a state changes only when its criterion is exceeded by this margin, so
/// contacts carrying no load (N at round-off level) do not flip state on noise every iteration.
struct StateTolerance {
  double force = 0;  ///< N/m (penalty × displacement tolerance)
  double slip = 0;   ///< m
};

/// What the latest solve says about a contact.
struct ContactResponse {
  double normalForce = 0;   ///< p·penetration (N/m), compression > 0
  double lockedShear = 0;   ///< shear spring force about the lock anchor (N/m)
  double slip = 0;          ///< tangential displacement this step, vertex relative to edge (m)
};

struct ContactJudgement {
  ContactState state = ContactState::Open;
  int direction = 0;
  bool bonded = false;
  bool operator==(const ContactJudgement&) const = default;
};

/// Shear strength available: c·Lc + N tanφ while bonded, N tanφ after (never negative).
double shearStrength(bool bonded, double normalForce, const ContactStrength& s);

/// Original DDA rule for one vertex-to-edge contact (Shi 1988):
/// open → locked when the vertex penetrates; closed → open when the normal force is a tension
/// beyond the bond's tensile capacity (0 once broken); locked → sliding when |shear| exceeds the
/// strength; sliding → locked when the slip reverses against the friction. Sliding or opening
/// breaks the bond for good.
ContactJudgement judgeVertexContact(ContactState state, int direction, bool bonded,
                                    const ContactResponse& r, const ContactStrength& s,
                                    const StateTolerance& tol = {});

/// Rule used while bringing the scene to equilibrium: strengths held, so a closed contact
/// stays locked whatever its forces; an open one closes (locked) when the vertex penetrates.
ContactJudgement judgeHeldContact(ContactState state, bool bonded, const ContactResponse& r,
                                  const StateTolerance& tol = {});

}  // namespace ddaslope::contact
