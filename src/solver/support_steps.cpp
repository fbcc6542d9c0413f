// The supports' part of a step (model/support.hpp, assembly/support_terms.hpp): each support is
// an axial spring between two blocks, judged in every open-close iterate beside the contacts, so
// that a support yields, slackens or breaks within the step that takes it there.
#include "ddaslope/assembly/support_terms.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "step_state.hpp"

namespace ddaslope::solver {

using model::SupportState;

void Simulation::prepareSupports(StepState& s) const {
  const size_t n = scene_.supports.size();
  s.supportV.resize(n);
  s.supportEnds.resize(n);
  s.supportElongation0.resize(n);
  s.a.supportStates.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const model::Support& b = scene_.supports[k];
    s.supportV[k] = assembly::supportElongationVector(b, scene_.blocks[b.head.block], scene_.blocks[b.end.block]);
    s.supportEnds[k] = {s.active[b.head.block], s.active[b.end.block]};
    s.supportElongation0[k] = b.elongation();
    s.a.supportStates[k] = b.state;
  }
}

void Simulation::addSupportTerms(StepState& s) {
  for (size_t k = 0; k < scene_.supports.size(); ++k) {
    const model::Support& b = scene_.supports[k];
    const auto [i, j] = s.supportEnds[k];
    if (i < 0 && j < 0) continue;
    const SupportState state = s.a.supportStates[k];
    if (state == SupportState::Slack || state == SupportState::Broken) continue;
    // Elastic: the force at the step's start plus k·Δe; yielded: the capacity, with no stiffness.
    const bool spring = state == SupportState::Elastic && b.stiffness > 0;
    const double force = model::supportForce(b, state, s.supportElongation0[k]);
    if (spring && s.stiffnessChanged) s.terms.addSpring(i, j, b.stiffness, s.supportV[k]);
    s.addTerm(i, j, -force, s.supportV[k]);
  }
}

bool Simulation::judgeSupports(StepState& s) {
  bool changed = false;
  for (size_t k = 0; k < scene_.supports.size(); ++k) {
    const auto [i, j] = s.supportEnds[k];
    if (i < 0 && j < 0) continue;
    SupportState& state = s.a.supportStates[k];
    if (state == SupportState::Broken) continue;
    const double e = s.supportElongation0[k] + s.supportV[k].dot(s.gather(i, j));
    const SupportState next = model::judgeSupport(scene_.supports[k], e);
    if (next == state) continue;
    state = next;
    changed = true;
  }
  // A followed factor follows the contact springs only: a support that changes its spring leaves
  // the factor to be made again.
  if (changed && s.followFactor) factorSprings_.invalidate();
  return changed;
}

void Simulation::commitPoints(const Attempt& a) {
  std::vector<double> before(scene_.supports.size());
  for (size_t k = 0; k < before.size(); ++k) before[k] = scene_.supports[k].elongation();
  scene_.forEachBlockPoint([&](model::BlockPoint& p) {
    const int i = active_[p.block];
    if (i >= 0)
      p.current = model::displacedPoint(scene_.blocks[p.block].moments.centroid, p.current, a.d.segment<6>(6 * i));
  });
  for (size_t k = 0; k < before.size(); ++k) {
    model::Support& b = scene_.supports[k];
    const double e = b.elongation();
    const SupportState state = k < a.supportStates.size() ? a.supportStates[k] : b.state;
    const double force = model::supportForce(b, state, e);
    // The work the blocks did on it over the step (exact for a linear spring or a constant force).
    b.work += 0.5 * (b.force + force) * (e - before[k]);
    b.plasticElongation = model::plasticElongationAfter(b, state, e);
    if (state != b.state) ++stats_.supportStateChanges;
    b.state = state;
    b.force = force;
  }
}

}  // namespace ddaslope::solver
