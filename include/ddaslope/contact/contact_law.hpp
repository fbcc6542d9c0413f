#pragma once
// Contact-state rules of the open-close iteration (pure functions, dda-method.md §4).
#include <utility>

#include "ddaslope/contact/contact.hpp"
#include "ddaslope/contact/joint_strength.hpp"

namespace ddaslope::contact {

/// Round-off guard: a state changes only when its criterion is exceeded by this margin, so
/// contacts carrying no load (N at round-off level) do not flip state on noise every iteration.
struct StateTolerance {
  double force = 0;  ///< N/m (penalty × displacement tolerance)
  double slip = 0;   ///< m
};

/// What the latest solve says about a contact.
struct ContactResponse {
  double normalForce = 0;   ///< p·penetration (N/m), compression > 0
  /// Shear spring force about the lock anchor (N/m). Of an open contact: the shear force that
  /// would stop its sides' relative slip within the step (reduced mass × slip velocity / Δt; 0
  /// before t = 0).
  double lockedShear = 0;
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

/// Whether a bond pulled open survives it: a softening joint without tensile strength, until the
/// opening reaches the weakening distance (Simulation::commit).
bool separatesWithBond(const ContactStrength& s);

/// Original DDA rule for one vertex-to-edge contact (Shi 1988):
/// open → locked when the vertex penetrates; closed → open when the normal force is a tension
/// beyond the bond's tensile capacity (0 once broken); locked → sliding when |shear| exceeds the
/// strength; sliding → locked when the slip reverses against the friction. Opening breaks the
/// bond for good, and so does sliding, unless the joint softens with slip (`bondSurvivesSlip`):
/// then a sliding contact resists with c·L + N tanφ of its current (softened) strength, and, if
/// the joint has no tensile strength, an opened one keeps its bond (separatesWithBond).
/// One departure: a contact that closes while its sides run past each other faster than its
/// friction could stop them within the step (a corner landing on a face it moves along) closes
/// sliding. Locked, it would take the whole step's slip on its shear spring, a force hundreds of
/// times the block's weight, and the iteration would cycle and freeze states into a lock that
/// stops a block tipping over a bend of its base (docs/contact-model.md).
ContactJudgement judgeVertexContact(ContactState state, int direction, bool bonded,
                                    const ContactResponse& r, const ContactStrength& s,
                                    const StateTolerance& tol = {});

/// State of one half of an edge-to-edge contact before judgement.
struct HalfState {
  ContactState state = ContactState::Open;
  int direction = 0;
  bool bonded = false;
};

/// The founding paper's rule (Zhang et al. 2014; dda-method.md §5): the two vertex-to-edge halves
/// of one edge-to-edge contact of overlap L are judged as one contact.
/// - Shear: total S = S1 + S2 against c·L + N1 tanφ1 + N2 tanφ2 while intact, the friction after; one state
///   (locked or sliding, one direction) for both halves; the bond is lost by both at once (kept
///   while sliding if the joint softens with slip).
/// - Tension is judged at the ends: two end springs stand for a linear stress distribution whose
///   end stress is N_k/(L/2), so an end separates when N_k < −σt·L/2 (pure tension: N1 + N2 <
///   −σt·L). That half opens and the other carries on alone as a vertex-to-edge contact at the
///   pivot (toppling). A brittle bond fails as a whole there; a softening joint's pivot keeps its
///   share, and so does the opened end if the joint has no tensile strength (separatesWithBond).
/// - While either half is open the pair is not an edge contact: each half is judged alone with
///   half the bond (c·L/2, σt·L/2), as original DDA does.
/// `s1`, `s2`: each half's strength over L/2 (the halves may have slipped, so softened, apart).
std::pair<ContactJudgement, ContactJudgement> judgeEdgeContact(const HalfState& h1, const HalfState& h2,
                                                               const ContactResponse& r1,
                                                               const ContactResponse& r2,
                                                               const ContactStrength& s1,
                                                               const ContactStrength& s2,
                                                               const StateTolerance& tol = {});

/// Rule used while bringing the scene to equilibrium: strengths held, so a closed contact
/// stays locked whatever its forces; an open one closes (locked) when the vertex penetrates.
ContactJudgement judgeHeldContact(ContactState state, bool bonded, const ContactResponse& r,
                                  const StateTolerance& tol = {});

}  // namespace ddaslope::contact
