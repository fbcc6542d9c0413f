// The judgement of each open-close iterate (dda-method.md §4): every contact's response to the
// solution against its law, the rules that hold or freeze a contact that keeps changing state,
// and the states, bonds and anchors that the next iterate is assembled with.
#include <algorithm>
#include <cmath>
#include <string>

#include "ddaslope/contact/contact_law.hpp"
#include "ddaslope/core/parallel.hpp"
#include "ddaslope/core/prefetch.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "step_state.hpp"

namespace ddaslope::solver {

using contact::Contact;
using contact::ContactJudgement;
using contact::ContactResponse;
using contact::ContactState;

namespace {

// Last resort against cycling (load passed back and forth between coupled contacts): when
// allowed, a contact that changed state kFlipsBeforeFreeze times in this step keeps its state
// for the rest of it; an open one may still close. Steps accepted so are counted.
constexpr int kFlipsBeforeFreeze = 4;
// Sudden loading (gravity switched on at step 1) sets the blocks ringing: a wave crosses a
// 0.5 m brick in 0.25 ms, so within a 1 ms step a lightly loaded contact (a brick corner at a
// T-junction) is closed part of the time and open part of it, and no single state satisfies
// its law; the states cycle (open → locked → sliding → open, period 2-4) and cutting Δt does
// not end it. Holding such a contact in its state is an error in its law; it is accepted
// early (before any cut) only while that error is below this fraction of the largest contact
// force of the iterate (heldViolation). (Shi's DDA keeps every contact closed up to a
// separation of 2e-7·w0, so that a contact can carry a tension of the order of the largest
// contact force: docs/performance.md, "Known limitations".) A hold must not anchor a block
// either: a locked contact kept closed in tension counts its whole shear (its strength is nil),
// or a block sliding on a plane is held by its unloaded heel and topples (BenchmarkA7). Contacts
// whose law a hold would break by more still cut Δt, and are frozen unconditionally only after
// two cuts.
constexpr double kHeldViolation = 1e-2;

}  // namespace

contact::StateTolerance Simulation::stateTolerance(const std::vector<Contact>& contacts) const {
  // Round-off guard: the larger of the penalty force of a round-off displacement and 1e-9 of the
  // largest contact force of the last solve (forces are only known to that relative precision).
  // The displacement stays below 1e-3 of the lightest block's own penetration under its weight,
  // or a millimetre block in a 10 m model could never change state.
  const double noise = std::min(scene_.settings.contactStateTolerance * w0_, lightestPenetration_);
  double largestForce = 0;
  for (const Contact& c : contacts) largestForce = std::max(largestForce, std::abs(c.normalForce));
  return {std::max(penalty_ * noise, 1e-9 * largestForce), noise};
}

std::vector<ContactResponse> Simulation::contactResponses(const StepState& s) const {
  std::vector<ContactResponse> response(s.a.contacts.size());
  parallelFor(static_cast<int>(s.a.contacts.size()), threads_, [&](int k) {
    const size_t q = static_cast<size_t>(k);
    const Vec12 d = s.gather(s.a.contacts[q]);
    response[q].normalForce = normalStiffness(s.a.contacts[q]) * s.kin[q].penetration(d);
    const Contact& c = s.a.contacts[q];
    response[q].slip = s.kin[q].slip(d);
    if (c.closed()) {
      response[q].lockedShear = shearStiffness(c) * s.kin[q].shearFromAnchor(d);
    } else if (response[q].normalForce > 0 && s.regime == Regime::Analysis &&
               scene_.settings.mode == model::AnalysisMode::Dynamic) {
      // An open contact that closes: the force that would stop its sides' relative slip within the step,
      // their reduced mass times the slip velocity the step started with over Δt (not the
      // iterate's slip, which an iterate with the contact open may throw anywhere). The blocks'
      // whole masses: a bound that leans towards sliding, which the next iterate's slip reversal
      // corrects (rotational inertia and the share of an edge's two ends are left out). Before
      // t = 0, and in static mode (every step from rest), the velocities are not motion: none
      // (a closing contact locks there, as in original DDA).
      const model::Block& vb = scene_.blocks[c.key().vertexBlock];
      const model::Block& eb = scene_.blocks[c.key().edgeBlock];
      Vec12 v;
      v.head<6>() = vb.velocity;
      v.tail<6>() = eb.velocity;
      const double mv = mass_[c.key().vertexBlock], me = mass_[c.key().edgeBlock];
      const double reduced = vb.fixed ? me : eb.fixed ? mv : mv * me / (mv + me);
      response[q].lockedShear = reduced * s.kin[q].slip(v) / s.dt;
    }
  });
  return response;
}

Simulation::IterateChanges Simulation::judgeIterate(StepState& s) {
  // Judge every contact against the new solution.
  const std::vector<ContactResponse> response = contactResponses(s);
  const std::vector<ContactJudgement> verdict = judgeContacts(s.a.contacts, response, s.regime, s.stateTolerance);
  double largestNormal = 0;
  for (size_t q = 0; q < s.a.contacts.size(); ++q)
    if (s.a.contacts[q].closed()) largestNormal = std::max(largestNormal, std::abs(response[q].normalForce));
  const double allowed = kHeldViolation * largestNormal;
  // Before t = 0 a contact pulled open by the start (gravity switched on at once) keeps its
  // bond, as slip then does not soften: that is the slope's loading history, not damage.
  // Only an open contact: it carries nothing either way, so a rest found so is a rest under
  // the analysis law too. (Keeping the bond of a closed contact, e.g. the pivot half of a
  // brittle edge-to-edge contact whose other half opens, would let settling lean on a
  // strength the first analysis step removes: the planar multi-block slide then "rested" at
  // 122 kPa and ran away at t = 0. Such a brittle pair loses its bond, as in original DDA.)
  const bool openKeepsBond =
      scene_.settings.settleDynamically && (s.regime == Regime::Relaxation || s.regime == Regime::Settling);
  IterateChanges changes;
  double frictionDrift = 0, forceScale = 0;
  for (size_t q = 0; q < s.a.contacts.size(); ++q) {
    const Contact& c = s.a.contacts[q];
    const ContactResponse& r = response[q];
    ContactJudgement j = verdict[q];
    if (openKeepsBond) j.bonded = j.bonded || (c.bonded && j.state == ContactState::Open);
    if (j.state != c.state || j.direction != c.slideDirection) j = holdOrFreeze(s, q, j, response, allowed);
    if (c.state == ContactState::Sliding && j.state == ContactState::Sliding)
      frictionDrift = std::max(frictionDrift, std::abs(r.normalForce - c.normalForce));
    if (j.state != ContactState::Open) forceScale = std::max(forceScale, std::abs(r.normalForce));
    if (j.state != c.state || j.direction != c.slideDirection) changes.states = true;
    if (j.state != c.state)
      ++((j.state == ContactState::Open || c.state == ContactState::Open) ? stats_.openCloseChanges
                                                                            : stats_.stickSlipChanges);
    if (j.bonded != c.bonded) changes.bonds = true;
    applyJudgement(s, q, j, r);
  }
  if (judgeSupports(s)) changes.states = true;
  stats_.times.stateChecks += s.sw.lap();
  changes.frictionSettled = frictionDrift <= scene_.settings.frictionTolerance * forceScale;
  return changes;
}

double Simulation::heldViolation(const StepState& s, size_t q, const ContactJudgement& j,
                                 const std::vector<ContactResponse>& response) const {
  // By how much holding contact q in its state breaks its law, against the judgement j: the
  // tension it keeps, plus, if locked, the shear its spring keeps above the strength (all of
  // it in tension: a locked heel held closed also anchors the block against sliding), or, if
  // sliding against a reversed slip, the shear spring force of that slip.
  const Contact& c = s.a.contacts[q];
  const ContactResponse& r = response[q];
  if (c.state == ContactState::Sliding && j.state == ContactState::Sliding) return double(INFINITY);
  if (c.state == ContactState::Sliding)
    return std::max(0.0, -r.normalForce) + (j.state == ContactState::Locked ? shearStiffness(c) * std::abs(r.slip) : 0.0);
  const auto excess = [&](size_t k) {
    const Contact& h = s.a.contacts[k];
    return std::abs(response[k].lockedShear) - contact::shearStrength(h.bonded, response[k].normalForce, strengthOf(h));
  };
  // An edge-to-edge pair slides as a whole: count its other half's excess too.
  const int p = partner_[q];
  const double shear = excess(q) + (p >= 0 && s.a.contacts[p].state == ContactState::Locked ? excess(p) : 0.0);
  return std::max(0.0, -r.normalForce) + std::max(0.0, shear);
}

ContactJudgement Simulation::holdOrFreeze(StepState& s, size_t q, ContactJudgement j,
                                          const std::vector<ContactResponse>& response, double allowed) const {
  const Contact& c = s.a.contacts[q];
  const bool closing = c.state == ContactState::Open;
  if (s.flips[q] >= kFlipsBeforeFreeze && !closing &&
      (s.freezeCycling || (s.holdSmallViolations && heldViolation(s, q, j, response) <= allowed))) {
    j = {c.state, c.slideDirection, j.bonded && c.bonded};
    s.a.frozeContacts = true;
  } else if (s.holdSmallViolations && s.flips[q] >= kFlipsBeforeFreeze && c.state == ContactState::Locked &&
             j.state == ContactState::Open && -response[q].normalForce <= allowed) {
    // A locked contact whose shear breaks its law by more is still kept touching in the
    // small tension, but with its shear released: sliding, its friction max(0, N)·tanφ.
    j = {ContactState::Sliding, response[q].lockedShear > 0 ? 1 : -1, j.bonded && c.bonded};
    s.a.frozeContacts = true;
  } else {
    ++s.flips[q];
  }
  return j;
}

void Simulation::applyJudgement(StepState& s, size_t q, const ContactJudgement& j, const ContactResponse& r) const {
  Contact& c = s.a.contacts[q];
  if (j.state == ContactState::Locked && c.state != ContactState::Locked) {
    // The locked spring starts at the step-start position; a contact that sticks after
    // sliding keeps the friction force it carried (force continuity), or the load it drops
    // would jump onto its neighbours and break them.
    c.lockRatio = c.geometry.ratio;
    if (c.state == ContactState::Sliding) c.lockRatio -= c.slideDirection * s.friction[q] / (shearStiffness(c) * edgeLength(c));
    s.kin.replace(q, assembly::linearise(scene_.blocks[c.key().vertexBlock], scene_.blocks[c.key().edgeBlock], c));
  }
  // A brittle joint's contact drops to its residual strength the moment it slides.
  if (j.state == ContactState::Sliding && *scene_.joints[c.joint].weakeningDistance <= 0) c.intact = 0;
  c.stepSlip = j.state == ContactState::Sliding ? r.slip : 0.0;
  c.state = j.state;
  c.slideDirection = j.direction;
  c.bonded = j.bonded;
  c.normalForce = r.normalForce;
  c.shearForce = c.state == ContactState::Locked ? r.lockedShear : 0.0;
}

bool Simulation::stopCycling(StepState& s) {
  const int period = s.cycles.record(s.a.contacts);
  if (period == 0) return false;
  s.a.failure = "open-close iteration cycles: the contact states repeat every " + std::to_string(period) +
                " iterations (from iteration " +
                std::to_string(s.a.iterations - StateCycleDetector::kRepeats * period) + ")";
  ++stats_.cycles;
  return true;
}

std::vector<ContactJudgement> Simulation::judgeContacts(const std::vector<Contact>& cs,
                                                        const std::vector<ContactResponse>& response, Regime regime,
                                                        const contact::StateTolerance& tol) const {
  std::vector<ContactJudgement> out(cs.size());
  const bool edge = scene_.settings.contactTreatment == model::ContactTreatment::Edge;
  // A pair is judged at its first half, which reads its second half's contact and response from
  // further on in the arrays (a neighbouring block's contacts): asked for kPartnerAhead contacts
  // early, so that the wait for memory overlaps the judgements in between.
  constexpr size_t kPartnerAhead = 16;
  const bool pairs = edge && regime != Regime::HeldEquilibrium;
  for (size_t q = 0; q < cs.size(); ++q) {
    if (pairs && q + kPartnerAhead < cs.size()) {
      const int ahead = partner_[q + kPartnerAhead];
      if (ahead > static_cast<int>(q + kPartnerAhead)) {
        prefetchBytes(&cs[static_cast<size_t>(ahead)], sizeof(Contact));
        prefetchBytes(&response[static_cast<size_t>(ahead)], sizeof(ContactResponse));
      }
    }
    const Contact& c = cs[q];
    if (regime == Regime::HeldEquilibrium) {
      out[q] = contact::judgeHeldContact(c.state, c.bonded, response[q], tol);
      continue;
    }
    const int p = partner_[q];
    if (!edge || p < 0) {
      out[q] = contact::judgeVertexContact(c.state, c.slideDirection, c.bonded, response[q], strengthOf(c), tol);
      continue;
    }
    if (p < static_cast<int>(q)) continue;  // judged with its partner
    const Contact& o = cs[p];
    const auto [j1, j2] = contact::judgeEdgeContact({c.state, c.slideDirection, c.bonded},
                                                    {o.state, o.slideDirection, o.bonded}, response[q],
                                                    response[p], strengthOf(c), strengthOf(o), tol);
    out[q] = j1;
    out[p] = j2;
  }
  return out;
}

double Simulation::edgeLength(const Contact& c) const {
  const auto& v = scene_.blocks[c.key().edgeBlock].vertices;
  return (v[(c.key().edge + 1) % v.size()] - v[c.key().edge]).norm();
}

contact::ContactStrength Simulation::strengthOf(const Contact& c) const {
  // Original DDA: each vertex-to-edge half of an edge-to-edge contact carries c·L/2.
  return contact::contactStrength(jointStrength_[c.joint], c.intact, c.geometry.overlap / 2);
}

double Simulation::slidingResistance(const Contact& c) const {
  return contact::shearStrength(c.bonded, c.normalForce, strengthOf(c));
}

std::vector<double> Simulation::slidingFriction(const std::vector<Contact>& cs) const {
  // The ends of a sliding edge share its friction equally. With each end's own N tan φ the friction
  // follows the difference of the normal forces, which the block's rotation and shear strain set;
  // that difference stretches a deformable block along the edge, and Poisson's ratio turns the
  // stretch into a normal squeeze that changes the normal forces again. This non-symmetric coupling
  // is a flutter instability of steady sliding, which walks a block down a slope it should creep
  // along (docs/accuracy.md, "Strain damping and friction flutter"). Shared, the friction depends
  // on the sum of the normal forces only and the loop is cut; both forces lie on the edge, so a
  // rigid block moves the same either way, and only a deformable block's stretch along the edge,
  // ∫ x τ dx, loses the friction gradient. Only deformable blocks under the edge treatment share,
  // where the pair is one contact judged against the whole edge's strength: the vertex treatment
  // (original DDA) judges each end against its own, which must then be the friction it meets.
  // Rigid blocks do not flutter (no strain for the loop to run through) and keep per-end friction:
  // a pair that sticks keeps the shear it slid with, and a shared half on a heel that then lifts
  // would drop half the edge's friction at once.
  std::vector<double> friction(cs.size(), 0.0);
  for (size_t q = 0; q < cs.size(); ++q)
    if (cs[q].state == ContactState::Sliding) friction[q] = slidingResistance(cs[q]);
  if (scene_.settings.contactTreatment != model::ContactTreatment::Edge || scene_.settings.rigidBlocks)
    return friction;
  for (size_t q = 0; q < cs.size(); ++q) {
    const int p = partner_[q];
    if (p <= static_cast<int>(q) || cs[q].state != ContactState::Sliding) continue;
    const Contact& o = cs[p];
    if (o.state != ContactState::Sliding || o.slideDirection != cs[q].slideDirection) continue;
    friction[q] = friction[p] = 0.5 * (friction[q] + friction[p]);
  }
  return friction;
}

}  // namespace ddaslope::solver
