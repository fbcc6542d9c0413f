// One attempt at a step (Simulation::tryStep): configure the solver, assemble, then iterate
// {solve, judge the contacts, hold or freeze cycling ones, or solve again} until the states stand,
// and check the step limit. The caller accepts the attempt or cuts Δt. The judgement of each
// iterate is in open_close.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "ddaslope/assembly/block_terms.hpp"
#include "ddaslope/assembly/water_terms.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "step_state.hpp"

namespace ddaslope::solver {

using contact::Contact;
using contact::ContactState;

namespace {

/// Springs changed at once beyond which a new factorisation is cheaper than following them. Each
/// changed spring is one column of update/downdate; on a large wall about a thousand columns cost
/// one factorisation, and a limit a little below that break-even settled the wall fastest
/// (docs/performance.md, "Measurements behind the solver's constants").
constexpr size_t kMaxFactorModificationRank = 800;
/// CG iterations with a stale factor before a large system refactorises (see configureSolver).
constexpr int kLargeSystemCgIterations = 4;
// Relative residual to which a large system solves while its contact states change (solveIterate;
// the states are judged again on the next solution): one CG iteration with a factor that follows
// the states reaches it, against two for the full 1e-12.
constexpr double kJudgingResidual = 1e-8;

}  // namespace

Simulation::Attempt Simulation::tryStep(double dt, Regime regime, bool freezeCycling, bool holdSmallViolations) {
  StepState s(dt, regime, freezeCycling, holdSmallViolations, active_, contacts_.contacts(), kinematics_, matrix_);
  updatePattern(s.a.contacts);
  assembleBlockTerms(dt, regime, s.blockK, s.blockF, s.a.loads, s.blockMagnitude, &s.a.groundLoads);
  s.rhs.resize(6 * nActive_);
  prepareSupports(s);
  stats_.times.assembly += s.sw.lap();
  s.stateTolerance = stateTolerance(s.a.contacts);
  configureSolver(s);

  const int maxIterations = std::max(1, scene_.settings.openCloseMaxIterations);
  for (s.a.iterations = 1; s.a.iterations <= maxIterations; ++s.a.iterations) {
    assembleContactTerms(s);
    followStateChanges(s);
    if (!solveIterate(s)) return std::move(s.a);
    const IterateChanges changes = judgeIterate(s);
    if (stopCycling(s)) return std::move(s.a);
    s.stiffnessChanged = changes.states;
    s.nextSolveStrict = !changes.states;
    if (!changes.states && !changes.bonds && changes.frictionSettled && s.solvedStrictly) {
      s.a.converged = true;
      break;
    }
  }
  if (!s.a.converged) {
    s.a.iterations = maxIterations;
    s.a.failure = "open-close iteration did not converge in " + std::to_string(maxIterations) + " iterations";
    return std::move(s.a);
  }
  // A sliding contact's shear spring stays stretched to the friction it slides against (once,
  // for the converged states: only the energy budget reads it).
  const std::vector<double> carried = slidingFriction(s.a.contacts);
  for (size_t q = 0; q < s.a.contacts.size(); ++q)
    if (s.a.contacts[q].state == ContactState::Sliding) s.a.contacts[q].shearForce = carried[q];
  checkStepLimit(s.a);
  return std::move(s.a);
}

void Simulation::updatePattern(const std::vector<Contact>& contacts) {
  std::vector<std::pair<int, int>> couplings;
  for (const Contact& c : contacts) {
    const int i = active_[c.key().vertexBlock], j = active_[c.key().edgeBlock];
    if (i >= 0 && j >= 0) couplings.emplace_back(i, j);
  }
  for (const model::Support& b : scene_.supports) {
    const int i = active_[b.head.block], j = active_[b.end.block];
    if (i >= 0 && j >= 0) couplings.emplace_back(i, j);
  }
  const int dof = unknownsPerBlock();
  // The same contacts in the same order couple the same blocks: the pattern stands, and the
  // sort that normalises the list (a millisecond at 2000 blocks) is skipped.
  if (couplings != lastCouplings_ || matrix_.patternVersion() == 0 || matrix_.blockSize() != dof ||
      matrix_.size() != dof * nActive_) {
    lastCouplings_ = couplings;
    couplings = assembly::BlockSparseMatrix::normalise(std::move(couplings));
    if (!matrix_.hasPattern(nActive_, couplings, dof)) matrix_.setPattern(nActive_, couplings, dof);
  }
}

void Simulation::configureSolver(StepState& s) {
  // The factor follows the contact state changes by low-rank update/downdate
  // (solver/factor_springs.hpp) instead of being redone, unless the case asks for a
  // refactorisation at every change (analysis.factor_updates = "off": the same results to
  // round-off, slower).
  s.followFactor = factorFollowing_ && scene_.settings.factorUpdates;
  // Nested dissection orders a large wall's factor with less fill than AMD and a shallower tree,
  // whose paths each update/downdate of a spring walks. A factor made again at every change keeps
  // AMD, and the round-off of the figures made so.
  linearSolver_.setOrdering(s.followFactor ? FillOrdering::NestedDissection : FillOrdering::MinimumDegree);
  // Every system substitutes with a simplicial copy of its factor: a small system's supernodes
  // are a few columns wide, and the reference BLAS calls a supernodal solve makes for each cost
  // more than the arithmetic (a quarter of a small slope's search; docs/performance.md).
  linearSolver_.setSimplicialSolves(true);
  linearSolver_.setPanelSolves(s.followFactor && panelSolves_);
  // The right-hand side is a sum of forces that nearly cancel in a scene at rest (weights against
  // contact preloads and stresses: in a large wall the terms are some eight orders of magnitude
  // above their sum), so it is known only to the round-off of those terms. A solve on a followed
  // factor stops there instead of at a residual 1e-12 of the sum, which only conjugate-gradient
  // iterations on round-off would reach. Refactorising at every change keeps the strict rule.
  s.residualAtRoundOff = s.followFactor;
  // With that looser target a factor far from K (an equilibrium's) would converge within the
  // small systems' budget of CG iterations, which it misses at the strict target (and is then
  // redone), and stay in use at several iterations per step. A near-exact factor (one that follows
  // the states) converges in 0-3: a large system redoes a factor that needs more than 4.
  linearSolver_.setMaxIterations(s.followFactor ? kLargeSystemCgIterations : LinearSolverSettings{}.maxIterations);
  // A factor made for other block terms (the equilibrium's static steps, without strain damping,
  // at the analysis Δt) would stay within CG's budget at a few iterations per step for the whole
  // run: it is redone at once instead.
  s.blockTerms = FactorBlockTerms{s.dt, carriesVelocity(s.regime)};
  if (s.followFactor && linearSolver_.hasFactor() && !s.blockTerms.sameAs(factorBlockTerms_)) {
    linearSolver_.discardFactor();
    factorSprings_.invalidate();
  }
}

void Simulation::assembleContactTerms(StepState& s) {
  s.sw.lap();
  if (s.stiffnessChanged) s.terms.reset(unknownsPerBlock(), s.blockK);
  for (int i = 0; i < nActive_; ++i) s.rhs.segment<6>(6 * i) = s.blockF[i];
  if (s.residualAtRoundOff) {
    s.magnitude.resize(s.rhs.size());
    for (int i = 0; i < nActive_; ++i) s.magnitude.segment<6>(6 * i) = s.blockMagnitude[i];
  }
  // K's springs and b's contact terms in one pass over the contacts (a large scene's contacts
  // are read from memory, not the cache), each summed in the contacts' order.
  s.friction = slidingFriction(s.a.contacts);
  for (size_t q = 0; q < s.a.contacts.size(); ++q) {
    const Contact& c = s.a.contacts[q];
    if (!c.closed()) continue;
    if (s.stiffnessChanged) {
      const auto [i, j] = s.ends(c);
      s.terms.addSpring(i, j, normalStiffness(c), s.kin[q].normal);
      if (c.state == ContactState::Locked) s.terms.addSpring(i, j, shearStiffness(c), s.kin[q].shearLocked);
    }
    s.addTerm(c, -normalStiffness(c) * s.kin[q].penetration0, s.kin[q].normal);
    if (c.state == ContactState::Locked) {
      s.addTerm(c, -shearStiffness(c) * s.kin[q].shearLocked0, s.kin[q].shearLocked);
    } else {
      // Friction N tanφ (plus c·L while a softening bond lasts) opposite to the slip, as a pair
      // of point loads: K stays symmetric.
      s.addTerm(c, -c.slideDirection * s.friction[q], s.kin[q].shearStep());
    }
  }
  addSupportTerms(s);
  // With factor updates K is assembled only if a factorisation asks for it (products come from
  // its terms); refactorising at every change assembles it at once and multiplies by it.
  if (s.stiffnessChanged) {
    if (s.followFactor)
      s.lazySystem.changed();
    else
      s.terms.assembleInto(matrix_);
  }
  stats_.times.assembly += s.sw.lap();
}

void Simulation::followStateChanges(StepState& s) {
  const auto springsOf = [&](const Contact& c) { return std::pair{normalStiffness(c), shearStiffness(c)}; };
  if (!s.followFactor || !s.stiffnessChanged || !factorSprings_.valid() || factorSprings_.holdsSame(s.a.contacts))
    return;
  factorSprings_.changes(s.springs(springsOf), matrix_.blockSize(), s.added, s.removed);
  const size_t rank = s.added.size() + s.removed.size();
  if (rank > kMaxFactorModificationRank || !linearSolver_.modifyFactor(matrix_, s.added, s.removed))
    factorSprings_.invalidate();
  else
    stats_.factorColumns += static_cast<long>(rank);
  stats_.times.factorUpdate += s.sw.lap();
}

Simulation::ResidualFloors Simulation::residualFloors(const StepState& s) const {
  // 16 units of round-off of the terms' sizes: what b itself is known to.
  // (Rigid blocks solve for their first three unknowns only.)
  const int dof = unknownsPerBlock();
  double magnitudeNorm2 = 0;
  if (s.residualAtRoundOff)
    for (int i = 0; i < nActive_; ++i) magnitudeNorm2 += s.magnitude.segment(6 * i, dof).squaredNorm();
  const double roundOff = 16 * std::numeric_limits<double>::epsilon() * std::sqrt(magnitudeNorm2);
  // A large system solves only to kJudgingResidual while its contact states still change:
  // those states are judged again on the next solution anyway. An iteration after one that
  // changed no state solves to the full target, and only such a solution ends the iteration.
  const double floor =
      s.followFactor && !s.nextSolveStrict ? std::max(roundOff, kJudgingResidual * s.rhs.norm()) : roundOff;
  return {roundOff, floor};
}

bool Simulation::solveIterate(StepState& s) {
  if (s.stiffnessChanged) linearSolver_.matrixChanged();
  const long factorisationsBefore = linearSolver_.stats().factorisations;
  const ResidualFloors floors = residualFloors(s);
  const bool solved = nActive_ == 0 || solveSystem(s.system(), s.rhs, s.a.d, floors.solve);
  s.solvedStrictly = nActive_ == 0 || linearSolver_.lastSolveWithin(floors.roundOff);
  if (s.followFactor && linearSolver_.stats().factorisations > factorisationsBefore) {
    factorSprings_.reset(s.springs([&](const Contact& c) { return std::pair{normalStiffness(c), shearStiffness(c)}; }));
    factorBlockTerms_ = s.blockTerms;
  }
  // Time in a refactorising solve counts as factorisation, the rest as solve.
  (linearSolver_.stats().factorisations > factorisationsBefore ? stats_.times.factorisation
                                                               : stats_.times.solve) += s.sw.lap();
  if (!solved) {
    s.a.failure = "global matrix not positive definite";
    return false;
  }
  if (nActive_ == 0) s.a.d.resize(0);
  if (!s.a.d.allFinite()) {
    s.a.failure = "solution not finite";
    return false;
  }
  return true;
}

bool Simulation::solveSystem(const SystemOperator& k, const Eigen::VectorXd& rhs, Eigen::VectorXd& d,
                             double residualFloor) {
  const int dof = matrix_.blockSize();
  if (dof == 6) return linearSolver_.solve(k, rhs, d, residualFloor);
  // Rigid blocks: the matrix holds u0, v0, r0 of each block; the strains stay zero.
  Eigen::VectorXd reduced(dof * nActive_), x;
  for (int i = 0; i < nActive_; ++i) reduced.segment(dof * i, dof) = rhs.segment(6 * i, dof);
  if (!linearSolver_.solve(k, reduced, x, residualFloor)) return false;
  d = Eigen::VectorXd::Zero(6 * nActive_);
  for (int i = 0; i < nActive_; ++i) d.segment(6 * i, dof) = x.segment(dof * i, dof);
  return true;
}

void Simulation::checkStepLimit(Attempt& a) const {
  // The step limit, checked exactly only for blocks whose cheap bound does not clear it (in a
  // quiet step, none).
  bool beyondLimit = false;
  for (size_t b = 0; b < scene_.blocks.size() && !beyondLimit; ++b) {
    if (active_[b] < 0) continue;
    const model::Block& blk = scene_.blocks[b];
    const Vec6 d = a.d.segment<6>(6 * active_[b]);
    beyondLimit = blk.vertexDisplacementBound(d) > stepLimit_ && blk.maxVertexDisplacement(d) > stepLimit_;
  }
  if (!beyondLimit) return;
  const double worst = largestVertexDisplacement(a);
  a.converged = false;
  std::ostringstream msg;
  msg << "largest vertex displacement " << worst << " m exceeds the step limit " << stepLimit_
      << " m (g2·w0, at most a tenth of the thinnest block)";
  a.failure = msg.str();
}

bool Simulation::carriesVelocity(Regime regime) const {
  return (regime == Regime::Analysis || regime == Regime::Settling) && integrator_.dynamic();
}

void Simulation::assembleBlockTerms(double dt, Regime regime, std::vector<Mat6>& k, std::vector<Vec6>& f,
                                    std::vector<Vec6>& loads, std::vector<Vec6>& magnitude,
                                    std::vector<Vec6>* groundLoads) const {
  k.assign(nActive_, Mat6::Zero());
  f.assign(nActive_, Vec6::Zero());
  loads.assign(nActive_, Vec6::Zero());
  magnitude.assign(nActive_, Vec6::Zero());
  const bool carryVelocity = carriesVelocity(regime);
  // Water (and any load history) at the end of the step; equilibrium is found at t = 0.
  const double loadTime = regime == Regime::Analysis ? time_ + dt : 0.0;
  const model::WaterTable water = scene_.water.at(loadTime);
  // Seismic body acceleration (model/seismic.hpp): the pseudo-static part always; in the
  // analysis, the ground motion's mean over the step, so that the step receives exactly the
  // record's impulse however the record is sampled. A load, so that its work enters the budget.
  Vec2 inertial = scene_.seismic.pseudoStatic(scene_.gravity);
  Vec2 recordInertial = Vec2::Zero();
  if (regime == Regime::Analysis && scene_.seismic.ground.active())
    recordInertial = -model::SeismicLoad::toModelFrame(scene_.seismic.ground.meanOver(time_, time_ + dt), scene_.gravity);
  inertial += recordInertial;
  if (groundLoads) groundLoads->assign(nActive_, Vec6::Zero());
  const bool shaking = inertial.x() != 0 || inertial.y() != 0;
  for (size_t b = 0; b < scene_.blocks.size(); ++b) {
    const int i = active_[b];
    if (i < 0) continue;
    const model::Block& blk = scene_.blocks[b];
    // ρ·S₀/S: a block's mass is its initial one however its area strains (Shi's ρ·S is not).
    const double density = mass_[b] / blk.moments.area;
    const Mat6 mass = density * assembly::unitMassMatrix(blk.moments);
    const Mat6 elastic = assembly::elasticStiffness(blk.moments.area, elasticity_[blk.material]);
    k[i] = elastic + integrator_.inertiaStiffness(mass, dt);
    // Kelvin–Voigt damping of the strain rates, σ_v = β E ε̇, at the step's mean rate D/Δt: it
    // dissipates d·(β/Δt)K_e·d ≥ 0 in every step and leaves rest and rigid motion alone.
    if (carryVelocity && strainRetardation_[b] > 0)
      k[i] += (strainRetardation_[b] / dt) * elastic;
    const Vec6 body = assembly::bodyForce(blk.moments.area, density * scene_.gravity);
    const Vec6 stress = assembly::initialStressForce(blk.moments.area, blk.stress);
    f[i] = body + stress;
    magnitude[i] = body.cwiseAbs() + stress.cwiseAbs();
    if (carryVelocity) {
      const Vec6 inertia = integrator_.inertiaForce(mass, blk.velocity, dt);
      f[i] += inertia;
      magnitude[i] += inertia.cwiseAbs();
    }
    if (water.active()) loads[i] += assembly::waterForce(blk, water);
    if (shaking) loads[i] += assembly::bodyForce(blk.moments.area, density * inertial);
    if (groundLoads) (*groundLoads)[i] = assembly::bodyForce(blk.moments.area, density * recordInertial);
  }
  for (const model::PointLoad& l : scene_.pointLoads) {
    const int i = active_[l.point.block];
    // The load at the end of the step (implicit, like every other term).
    if (i >= 0)
      loads[i] += assembly::pointForce(scene_.blocks[l.point.block].moments.centroid, l.point.current, l.at(loadTime));
  }
  for (int i = 0; i < nActive_; ++i) f[i] += loads[i], magnitude[i] += loads[i].cwiseAbs();
  for (const model::FixedPoint& fp : scene_.fixedPoints) {
    const int i = active_[fp.point.block];
    if (i < 0) continue;
    const Mat26 t = scene_.blocks[fp.point.block].tAt(fp.point.current);
    k[i] += penalty_ * t.transpose() * t;
    const Vec6 pull = penalty_ * t.transpose() * (fp.point.initial - fp.point.current);
    f[i] += pull;
    magnitude[i] += pull.cwiseAbs();
  }
}

}  // namespace ddaslope::solver
