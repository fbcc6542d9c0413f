// The initial equilibrium (dda-method.md §6): the scene brought to rest under its static loads
// before t = 0, in up to three stages (Simulation::bringToEquilibrium): every initial contact
// held, the real contact law in static steps, and dynamic settling with kinetic damping.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/solver/energy.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::solver {

using contact::Contact;

double Simulation::restAcceleration() const {
  // At rest when the acceleration a static step implies, 2|D|/Δt², is below 1e-6 g: a measure
  // of the out-of-balance force that does not depend on the Δt the step control ended up with.
  return 1e-6 * std::max(scene_.gravity.norm(), 1e-3);
}

Simulation::Rest Simulation::settle(Regime regime, double& dt, double largestDt) {
  // A scene that moves this far while settling is failing, not settling. (Static steps carry no
  // momentum: past this, one could still find a rest a dynamic run would slide through.)
  const double failingTravel = scene_.settings.maxDisplacementRatio * w0_;
  double travel = 0;
  // Without stage 3 an unconfirmed rest is kept as a fallback while static steps from the
  // analysis Δt look for a confirmed one (many-block scenes near failure, e.g. Vajont, creep on).
  std::optional<std::pair<model::Scene, contact::ContactSet>> firstRest;
  constexpr int kConfirmationSteps = 30;
  int stepsSinceRest = 0;
  // A static step cannot settle a block held at its friction limit (its inertia is only a
  // regulariser): such a block creeps at a steady out-of-balance force, step after step, and the
  // steps cut Δt whenever the creeping contacts cycle. A relaxation whose out-of-balance force has
  // not halved over a window of steps is handed to stage 3, which settles it dynamically from
  // there, instead of spending the rest of its budget creeping (docs/performance.md).
  constexpr int kStallWindow = 20;
  const bool giveUpWhenStalled = regime == Regime::Relaxation && scene_.settings.settleDynamically;
  double windowBest = std::numeric_limits<double>::infinity(), previousWindowBest = windowBest;
  const auto fallBack = [&] {
    // Stage 3 settles a relaxation whose static steps ran out of budget or stopped converging
    // (contacts cycling in static steps: the chair slide with a block across its kink).
    if (regime == Regime::Relaxation && scene_.settings.settleDynamically) return Rest::Unsettled;
    if (!firstRest) return Rest::NotFound;
    scene_ = std::move(firstRest->first);
    contacts_ = std::move(firstRest->second);
    return Rest::Unconfirmed;
  };
  for (int s = 0; s < scene_.settings.equilibriumMaxSteps; ++s) {
    checkDeadline();
    if (firstRest && stepsSinceRest++ >= kConfirmationSteps) break;
    detectContacts(false);
    Attempt a = tryStep(dt, regime, true);
    bool cut = false;
    for (int k = 0; !a.converged && k < scene_.settings.maxStepCuts; ++k) {
      if (log_) log_("equilibrium Δt " + std::to_string(dt) + " s cut: " + a.failure);
      dt *= scene_.settings.stepCutFactor;
      a = tryStep(dt, regime, true);
      cut = true;
    }
    if (!a.converged) return fallBack();
    // Slip while the model settles under gravity switched on at once is an artefact of that start
    // (in nature the slope was loaded over its history), so it does not soften a joint; a brittle
    // bond that slides is still lost (original DDA).
    commit(a, dt, false);
    ++stats_.equilibriumSteps;
    if (equilibriumProgress_) equilibriumProgress_("equilibrium", s + 1, scene_.settings.equilibriumMaxSteps);
    const double worst = largestVertexDisplacement(a);
    stats_.equilibriumResidual = 2 * worst / (dt * dt) / std::max(scene_.gravity.norm(), 1e-3);
    travel += worst;
    if (regime == Regime::Relaxation) relaxationTravel_ = travel;
    if (regime == Regime::Relaxation && passedSettlingLimit()) return Rest::GaveWay;
    if (log_) {
      std::ostringstream m;
      m << (regime == Regime::HeldEquilibrium ? "equilibrium (contacts held)" : "equilibrium (relaxation)")
        << " step " << s + 1 << ": Δt " << dt << " s, " << a.iterations << " open-close iterations, "
        << "out-of-balance " << stats_.equilibriumResidual << " g, travel " << travel << " m"
        << fastestBlockNote(a);
      log_(m.str());
    }
    if (2 * worst / (dt * dt) < restAcceleration()) {
      // Stage 1 holds every contact, so its rest is exact. A relaxation step may be accepted
      // with cycling contacts frozen against their own criteria (on the chair slide, bonded
      // contacts held locked in 150 MN/m of tension that their law opens), and at a static Δt of
      // seconds 2|D|/Δt² hides a residual force the stiffness takes up. The analysis would
      // release either dynamically, and on a slope near its strength that release slides and
      // softens joints. So the relaxed state is confirmed by one step from rest at the analysis
      // Δt with every contact judged by its real law; unconfirmed, stage 3 settles it.
      if (regime != Regime::Relaxation || confirmedAtRest(a, restAcceleration())) return Rest::Confirmed;
      if (scene_.settings.settleDynamically) return Rest::Unconfirmed;
      if (!firstRest) firstRest.emplace(scene_, contacts_);
      if (log_) log_("equilibrium (relaxation): rest not confirmed at the analysis Δt; settling on");
      dt = scene_.settings.timeStep;
      continue;
    }
    if (travel > failingTravel) return scene_.settings.settleDynamically ? Rest::NotFound : fallBack();
    if (giveUpWhenStalled) {
      windowBest = std::min(windowBest, stats_.equilibriumResidual);
      if ((s + 1) % kStallWindow == 0) {
        if (windowBest > 0.5 * previousWindowBest) {
          if (log_) log_("equilibrium (relaxation): the out-of-balance force stopped falling; settling dynamically");
          return Rest::Unsettled;
        }
        previousWindowBest = windowBest;
        windowBest = std::numeric_limits<double>::infinity();
      }
    }
    // A cut Δt makes the static step a slow dynamic relaxation: grow it back once it passes.
    if (!cut) dt = std::min(largestDt, 3 * dt);
  }
  return fallBack();
}

Simulation::Settled Simulation::settleDynamically() {
  // Kinetic damping (Cundall's dynamic relaxation for explicit codes; here on the implicit
  // Newmark step): steps at the analysis Δt carry velocity, and whenever the kinetic energy has
  // passed a peak every velocity is set to zero, which removes the energy of the mode that
  // peaked while the out-of-balance force keeps pushing towards equilibrium. The scene is at rest
  // when a step started from zero velocity converges without freezing contacts and implies an
  // acceleration below restAcceleration(): the test confirmedAtRest() applies to stage 2.
  // Travelling g2·w0 marks a failing scene. With stopSettlingPast()'s limit set, it goes on, as a
  // dynamic run without kinetic damping (so it cannot come to rest on momentum the damping took),
  // until a block passes the limit or it has travelled twice the limit (travel sums each step's
  // largest motion, vibration included, so it outruns any block's net displacement).
  const double failingTravel = scene_.settings.maxDisplacementRatio * w0_;
  const int budget = kSettlingStepsPerEquilibriumStep * scene_.settings.equilibriumMaxSteps;
  const bool dynamic = integrator_.dynamic();
  // (A static analysis's steps carry no momentum: it stops at g2·w0.)
  const double givingUpTravel = dynamic ? std::max(failingTravel, 2 * settlingLimit_) : failingTravel;
  // Releasing the held contacts sets a large scene ringing as a sudden load does, and its
  // lightly loaded contacts cycle at any Δt, so that the settling cuts Δt again and again. A large
  // system holds a contact whose cycling breaks its law by little, as its analysis steps do
  // (open_close.cpp, kHeldViolation), and settles without those cuts. A step that held one never
  // confirms rest. Small systems and static analyses keep the strict rule: held contacts moved a
  // slope at its strength to another verdict (docs/performance.md, "Tried and dropped").
  const bool holdSmallViolations = largeSystem() && dynamic;
  // The travel of stage 2 counts: the two stages together may not move like a failing scene.
  double travel = relaxationTravel_, lastKinetic = 0;
  // Static steps leave no meaningful velocity (commit() sums 2D/Δt over them): start from rest.
  for (model::Block& b : scene_.blocks) b.velocity.setZero();
  bool fromRest = true;
  // Kinetic damping brings a stable scene to rest: the acceleration implied by a step from rest
  // falls, if not from each energy peak to the next, then over a few of them. A scene at its
  // strength can settle into a cycle instead: on the chair slide at F = 1.13 a slow slide whose
  // steps from rest imply 0.012 g, peak after peak, for the whole budget of 4000 steps. So the
  // settling gives up once the least implied acceleration so far has not halved over both
  // kStalledPeaks steps from rest and kStalledSteps steps. Both, because a slope just within its
  // strength converges after long stalls of either kind, not of both: on the chair at F = 1.1235
  // and 1.1255, runs of 25 and 20 peaks within 800-1000 steps in all; cut another way (joint offset
  // 10 m, c = 51.9 kPa), 2200 steps over only 3 peaks while a slow mode gathered energy.
  constexpr int kStalledPeaks = 10;
  constexpr int kStalledSteps = 1000;
  double leastImplied = std::numeric_limits<double>::infinity();
  int stalledPeaks = 0, lastHalved = 0;
  // A settling that stalls leaves the scene in the quietest state it reached: the state at rest
  // from which a step implied the least acceleration. Stage 2's rest, the fallback otherwise, can
  // be far from rest at the analysis Δt (docs/case-format.md, stage 3, has a case),
  // and the analysis, undamped, would start with that kick: blocks rock, the halves that open
  // lose their bond, and the verdict follows Δt.
  // Only a full step at the analysis Δt under every contact's own law measures the kick the
  // analysis will get (a cut or frozen step understates it).
  model::Scene quietestScene, candidateScene;
  contact::ContactSet quietestContacts, candidateContacts;
  double quietestImplied = std::numeric_limits<double>::infinity();
  const auto stalled = [&] {
    if (travel > failingTravel) return Settled::Failed;
    if (quietestImplied == std::numeric_limits<double>::infinity()) return Settled::Unsettled;
    scene_ = std::move(quietestScene);
    contacts_ = std::move(quietestContacts);
    stats_.equilibriumResidual = quietestImplied / std::max(scene_.gravity.norm(), 1e-3);
    return Settled::Stalled;
  };
  for (int s = 0; s < budget; ++s) {
    checkDeadline();
    detectContacts(false);
    if (fromRest) {
      candidateScene = scene_;
      candidateContacts = contacts_;
    }
    double dt = scene_.settings.timeStep;
    Attempt a = tryStep(dt, Regime::Settling, false, holdSmallViolations);
    for (int k = 0; !a.converged && k < scene_.settings.maxStepCuts; ++k) {
      if (log_) log_("settling Δt " + std::to_string(dt) + " s cut: " + a.failure);
      dt *= scene_.settings.stepCutFactor;
      a = tryStep(dt, Regime::Settling, k >= 1, holdSmallViolations);
    }
    if (!a.converged) return Settled::Unsettled;
    commit(a, dt, false);
    ++stats_.settlingSteps;
    if (equilibriumProgress_) equilibriumProgress_("settling", s + 1, budget);
    const double worst = largestVertexDisplacement(a);
    travel += worst;
    if (passedSettlingLimit()) return Settled::Failed;
    const double implied = 2 * worst / (dt * dt);
    if (log_) {
      std::ostringstream m;
      m << "settling step " << s + 1 << ": Δt " << dt << " s, " << a.iterations << " open-close iterations"
        << (fromRest ? ", from rest: " : ", ") << "implied acceleration " << implied / std::max(scene_.gravity.norm(), 1e-3)
        << " g, travel " << travel << " m" << fastestBlockNote(a);
      log_(m.str());
    }
    if (fromRest && !a.frozeContacts && implied < restAcceleration()) {
      stats_.equilibriumResidual = implied / std::max(scene_.gravity.norm(), 1e-3);
      return Settled::AtRest;
    }
    if (travel > givingUpTravel) return Settled::Failed;
    const bool failing = travel > failingTravel;
    if (fromRest) {
      if (implied < 0.5 * leastImplied) {
        stalledPeaks = 0;
        lastHalved = s;
      } else {
        ++stalledPeaks;
      }
      leastImplied = std::min(leastImplied, implied);
      if (implied < quietestImplied && !a.frozeContacts && dt == scene_.settings.timeStep) {
        quietestImplied = implied;
        quietestScene = std::move(candidateScene);
        quietestContacts = std::move(candidateContacts);
      }
      if (stalledPeaks >= kStalledPeaks && s - lastHalved >= kStalledSteps) {
        if (log_)
          log_("settling: " + std::to_string(stalledPeaks) + " steps from rest over " + std::to_string(s - lastHalved) +
               " steps came no nearer to rest");
        return stalled();
      }
    }
    double kinetic = 0;
    for (size_t b = 0; b < scene_.blocks.size(); ++b)
      if (active_[b] >= 0) kinetic += kineticEnergy(scene_.blocks[b], mass_[b]);
    // A static analysis carries no velocity: each of its steps starts from rest.
    fromRest = !failing && (!dynamic || kinetic < lastKinetic);
    if (fromRest) {
      for (model::Block& b : scene_.blocks) b.velocity.setZero();
      kinetic = 0;
    }
    lastKinetic = kinetic;
  }
  return stalled();
}

void Simulation::polishRest(double staticDt) {
  // Kinetic damping stops once a step from rest implies less than 1e-6 g; a static step from
  // there, with the contact states settled, lands on the static equilibrium of those states. A
  // wall left at 1e-6 g rings slightly through the analysis, and each of its quiet steps then
  // needs a conjugate-gradient iteration that the single-precision factor of a wall at rest does
  // not (a second substitution). The static step is kept if it converges with no contact frozen
  // against its law and implies less than 1e-6 g at its Δt, and if a step from rest at the
  // analysis Δt under the real law then implies less than 1e-6 g (stage 3's own rest test, which
  // also leaves the analysis a factor of its block terms); otherwise the settled state stands.
  const model::Scene settledScene = scene_;
  const contact::ContactSet settledContacts = contacts_;
  const double settledPenetration = stats_.maxPenetration;
  const auto implied = [&](const Attempt& a, double dt) { return 2 * largestVertexDisplacement(a) / (dt * dt); };
  const auto atRest = [&](const Attempt& a, double dt) {
    return a.converged && !a.frozeContacts && implied(a, dt) < restAcceleration();
  };
  for (model::Block& b : scene_.blocks) b.velocity.setZero();
  detectContacts(false);
  Attempt polish = tryStep(staticDt, Regime::Relaxation, false);
  recordSolverStatistics();
  if (!atRest(polish, staticDt)) return;
  commit(polish, staticDt, false);
  for (model::Block& b : scene_.blocks) b.velocity.setZero();
  detectContacts(false);
  const double dt = scene_.settings.timeStep;
  const Attempt check = tryStep(dt, Regime::Settling, false);
  recordSolverStatistics();  // the check is not committed, but its factorisation counts here
  if (!atRest(check, dt)) {
    scene_ = settledScene;
    contacts_ = settledContacts;
    stats_.maxPenetration = settledPenetration;
    if (log_) log_("equilibrium: the static step from the settled state was not confirmed; the settled state stands");
    return;
  }
  ++stats_.equilibriumSteps;
  stats_.equilibriumResidual = implied(check, dt) / std::max(scene_.gravity.norm(), 1e-3);
  if (log_) {
    std::ostringstream m;
    m << "equilibrium: one static step from the settled state; a step from rest at the analysis Δt then implies "
      << stats_.equilibriumResidual << " g";
    log_(m.str());
  }
}

bool Simulation::passedSettlingLimit() {
  if (settlingLimit_ <= 0 || heldBlocks_.size() != scene_.blocks.size()) return false;
  const double limit2 = settlingLimit_ * settlingLimit_;
  for (size_t b = 0; b < scene_.blocks.size(); ++b) {
    if (active_[b] < 0) continue;
    const std::vector<Vec2>& now = scene_.blocks[b].vertices;
    const std::vector<Vec2>& was = heldBlocks_[b].vertices;
    for (size_t v = 0; v < now.size() && v < was.size(); ++v)
      if ((now[v] - was[v]).squaredNorm() > limit2) {
        stats_.gaveWayWhileSettling = true;
        if (log_) log_("equilibrium: block \"" + scene_.blocks[b].id + "\" moved past the set limit; settling stops");
        return true;
      }
  }
  return false;
}

bool Simulation::confirmedAtRest(const Attempt& last, double restAcceleration) {
  if (last.frozeContacts) return false;
  const double dt = scene_.settings.timeStep;
  detectContacts(false);
  const Attempt check = tryStep(dt, Regime::Relaxation, false);
  if (!check.converged) return false;
  return 2 * largestVertexDisplacement(check) / (dt * dt) < restAcceleration;
}

std::vector<bool> Simulation::unsupportedBlocks() const {
  const size_t n = scene_.blocks.size();
  std::vector<bool> reached(n, false);
  std::vector<int> frontier;
  for (size_t b = 0; b < n; ++b)
    if (scene_.blocks[b].fixed) reached[b] = true;
  for (const model::FixedPoint& f : scene_.fixedPoints) reached[f.point.block] = true;
  for (size_t b = 0; b < n; ++b)
    if (reached[b]) frontier.push_back(static_cast<int>(b));
  while (!frontier.empty()) {
    const int b = frontier.back();
    frontier.pop_back();
    for (const Contact& c : contacts_.contacts()) {
      if (!c.closed()) continue;
      const int u = c.key().vertexBlock, v = c.key().edgeBlock;
      const int other = u == b ? v : (v == b ? u : -1);
      if (other >= 0 && !reached[other]) {
        reached[other] = true;
        frontier.push_back(other);
      }
    }
    // A block held by a support (an anchor into the rock) is supported too.
    for (const model::Support& s : scene_.supports) {
      const int u = s.head.block, v = s.end.block;
      const int other = u == b ? v : (v == b ? u : -1);
      if (other >= 0 && !reached[other] && s.state != model::SupportState::Broken) {
        reached[other] = true;
        frontier.push_back(other);
      }
    }
  }
  std::vector<bool> held(n);
  for (size_t b = 0; b < n; ++b) held[b] = !reached[b];
  return held;
}

HeldEquilibrium Simulation::holdEquilibrium() {
  HeldEquilibrium h;
  h.held = unsupportedBlocks();
  markActiveBlocks(h.held);
  if (nActive_ > 0) {
    // Static steps whose inertia term is 1e-8 of the contact stiffness: only a regularisation,
    // so a step solves the static problem almost exactly. A mechanism (a block free to turn)
    // trips the displacement limit, and each Δt cut raises the regularisation ~11-fold.
    double maxMass = 0;
    for (const model::Block& b : scene_.blocks)
      if (!b.fixed) maxMass = std::max(maxMass, scene_.materials[b.material].density * b.moments.area);
    h.dt = std::sqrt(2e8 * maxMass / penalty_);
    const int before = stats_.equilibriumSteps;
    h.converged = settle(Regime::HeldEquilibrium, h.dt, h.dt) != Rest::NotFound;
    h.steps = stats_.equilibriumSteps - before;
  }
  h.blocks = scene_.blocks;
  h.monitors = scene_.monitors;
  h.pointLoads = scene_.pointLoads;
  h.fixedPoints = scene_.fixedPoints;
  h.supports = scene_.supports;
  h.contacts = contacts_;
  markActiveBlocks({});
  return h;
}

HeldEquilibrium Simulation::settledState(const HeldEquilibrium& from) const {
  HeldEquilibrium h = from;
  h.blocks = scene_.blocks;
  // At rest: what velocity is left is the last step's round-off, and stage 2 starts from rest.
  for (model::Block& b : h.blocks) b.velocity.setZero();
  h.monitors = scene_.monitors;
  h.pointLoads = scene_.pointLoads;
  h.fixedPoints = scene_.fixedPoints;
  h.supports = scene_.supports;
  h.contacts = contacts_;
  return h;
}

void Simulation::bringToEquilibrium(const HeldEquilibrium* shared) {
  if (!scene_.settings.initialEquilibrium) {
    stats_.startedAtRest = false;  // not brought to rest: the analysis starts as the case is
    startSlidingWhereBlocksMove();
    return;
  }
  std::vector<Vec6> initialVelocity;
  for (const model::Block& b : scene_.blocks) initialVelocity.push_back(b.velocity);
  HeldEquilibrium own;
  if (shared) {
    DDASLOPE_ASSERT(shared->blocks.size() == scene_.blocks.size() && shared->monitors.size() == scene_.monitors.size(),
                    "a shared equilibrium must come from the same scene");
    scene_.blocks = shared->blocks;
    scene_.monitors = shared->monitors;
    scene_.pointLoads = shared->pointLoads;
    scene_.fixedPoints = shared->fixedPoints;
    scene_.supports = shared->supports;
    contacts_ = shared->contacts;
    // The joints (strengths) are this scene's own; contacts keep their joint index.
  } else {
    own = holdEquilibrium();
    shared = &own;
  }
  stats_.equilibriumConverged = shared->converged;
  heldMonitors_.clear();
  for (const model::Monitor& m : shared->monitors) heldMonitors_.push_back(m.point.current);
  heldBlocks_ = shared->blocks;
  markActiveBlocks(shared->held);
  if (nActive_ > 0) {
    detectContacts(false);
    const model::Scene heldScene = scene_;
    const contact::ContactSet heldContacts = contacts_;
    // A large system settles dynamically (stage 3) straight from stage 1's state. Each static
    // step of stage 2 costs a factorisation per open-close iteration (Δt changing, and a large
    // scene's steps take tens of iterations), and a static step cannot settle a contact held at
    // its friction limit: its inertia is only a regulariser (1e-8 of the contact stiffness), so a
    // block whose driving force its friction just balances is all but free, and a large wall
    // creeps under the relaxation instead of coming to rest. Small systems keep stage 2: their
    // steps are cheap, and the shipped cases' figures were made with it. So does a static
    // analysis, whose stage 3 has no kinetic damping. Should stage 3 fail, the analysis starts
    // from stage 1's state.
    const bool skipStaticRelaxation = scene_.settings.settleDynamically && largeSystem() &&
                                      integrator_.dynamic();
    Rest rest = Rest::Unsettled;
    relaxationTravel_ = 0;
    if (!skipStaticRelaxation) {
      // Releasing every held contact at once in one huge static step rarely converges: start the
      // relaxation at the analysis Δt and let it grow.
      double relaxDt = std::min(shared->dt, scene_.settings.timeStep);
      rest = settle(Regime::Relaxation, relaxDt, shared->dt);
    }
    stats_.relaxationConverged = rest == Rest::Confirmed || rest == Rest::Unconfirmed;
    stats_.startedAtRest = rest == Rest::Confirmed;
    // A scene that gave way (stopSettlingPast) is left where it did: neither branch takes it.
    if (rest == Rest::NotFound) {
      scene_ = heldScene;
      contacts_ = heldContacts;
    } else if ((rest == Rest::Unconfirmed || rest == Rest::Unsettled) && scene_.settings.settleDynamically) {
      const model::Scene relaxedScene = scene_;
      const contact::ContactSet relaxedContacts = contacts_;
      if (log_)
        log_(skipStaticRelaxation ? "equilibrium: a large system settles dynamically from every contact held"
             : rest == Rest::Unsettled ? "equilibrium (relaxation): no static rest; settling dynamically"
                                     : "equilibrium (relaxation): rest not confirmed at the analysis Δt; settling dynamically");
      const Settled settled = settleDynamically();
      stats_.startedAtRest = settled == Settled::AtRest;
      stats_.settling = settled == Settled::AtRest    ? "at_rest"
                        : settled == Settled::Stalled ? "stalled"
                        : settled == Settled::Failed  ? "failed"
                                                      : "unsettled";
      // Without stage 2, "relaxed" reports whether the real contact law found rest at all.
      if (skipStaticRelaxation) {
        stats_.relaxationConverged = stats_.startedAtRest;
        if (stats_.startedAtRest) polishRest(shared->dt);
      }
      if (settled == Settled::Stalled && log_) {
        std::ostringstream m;
        m << "settling: no rest found; the analysis starts, at rest, from the quietest settled state (a step from it "
          << "implies " << stats_.equilibriumResidual << " g)";
        log_(m.str());
      }
      if ((settled == Settled::Failed || settled == Settled::Unsettled) && !stats_.gaveWayWhileSettling) {
        // Failing, or no quiet state measured to start from: start from stage 2's rest, or from
        // stage 1's state if stage 2 found none, as without stage 3, so that the analysis, not the
        // settling, moves the scene.
        const bool relaxed = rest == Rest::Unconfirmed;
        if (log_)
          log_(std::string("settling: no rest found; the analysis starts from the ") +
               (relaxed ? "relaxed state" : "state with every contact held"));
        scene_ = relaxed ? relaxedScene : heldScene;
        contacts_ = relaxed ? relaxedContacts : heldContacts;
      }
    }
  } else {
    // No block to settle: at rest unless blocks are held because nothing supports them.
    stats_.startedAtRest = std::none_of(shared->held.begin(), shared->held.end(), [](bool h) { return h; });
  }
  for (size_t b = 0; b < scene_.blocks.size(); ++b) scene_.blocks[b].velocity = initialVelocity[b];
  markActiveBlocks({});
  detectContacts(false);
  startSlidingWhereBlocksMove();
}

}  // namespace ddaslope::solver
