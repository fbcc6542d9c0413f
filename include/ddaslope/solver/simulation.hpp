#pragma once
#include <optional>
#include <chrono>
// The DDA forward model. One step reads top-down (STYLE.md):
// broad phase → contacts → (assemble → factorise → solve → judge states)* → accept or cut Δt
// → update geometry → commit contacts.
// Where each part lives in src/solver/: simulation.cpp (construction, advance, commit, energy,
// monitors), contact_update.cpp (broad and narrow phase, the persistent contact set), step.cpp (one
// attempt: the solver's path, assembly, solves, the step limit), open_close.cpp (the judgement of
// each iterate: contact rules, holding and freezing, cycles), equilibrium.cpp (the initial
// equilibrium's three stages); the time integrator is solver/newmark.hpp.
#include <cmath>
#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ddaslope/assembly/block_sparse_matrix.hpp"
#include "ddaslope/assembly/contact_terms.hpp"
#include "ddaslope/contact/contact_law.hpp"
#include "ddaslope/contact/contact_set.hpp"
#include "ddaslope/contact/pair_cache.hpp"
#include "ddaslope/model/scene.hpp"
#include "ddaslope/solver/energy.hpp"
#include "ddaslope/solver/factor_springs.hpp"
#include "ddaslope/solver/linear_solver.hpp"
#include "ddaslope/solver/newmark.hpp"
#include "ddaslope/solver/time_step.hpp"

namespace ddaslope::solver {

/// Wall time (s) spent in each phase, summed over the run.
struct PhaseTimes {
  double broadPhase = 0, contacts = 0, assembly = 0, factorisation = 0, solve = 0,
         stateChecks = 0, update = 0;
  double factorUpdate = 0;  ///< the factor following contact state changes (factor updates)
};

struct StepRecord {
  double time = 0;     ///< simulated time after the step (s)
  double dt = 0;       ///< Δt of the accepted attempt (s)
  int iterations = 0;  ///< open-close iterations of the accepted attempt
  int cuts = 0;        ///< Δt cuts before the step was accepted
};

struct RunStatistics {
  int steps = 0;
  int cuts = 0;
  long iterations = 0;
  int cycles = 0;                  ///< attempts ended early: the open-close states cycled
  int frozenSteps = 0;             ///< steps accepted with cycling contacts held (frozen)
  int equilibriumSteps = 0;
  double equilibriumResidual = 0;  ///< last equilibrium step's implied acceleration 2|D|/Δt², in g
  bool equilibriumConverged = true;  ///< stage 1 (contacts held) reached rest
  bool relaxationConverged = true;   ///< stage 2 (real contact law) reached rest and was kept
  int settlingSteps = 0;             ///< stage 3: dynamic steps at the analysis Δt (kinetic damping)
  bool startedAtRest = true;         ///< the analysis starts from a confirmed rest (stage 2 or 3;
                                     ///< false without initial_equilibrium)
  bool gaveWayWhileSettling = false;  ///< stages 2–3 ended as a block passed stopSettlingPast()'s limit
  /// How stage 3 ended: "" (it did not run), "at_rest", "stalled" (the analysis starts from its
  /// quietest state), "failed" (it moved like a failing scene; the analysis starts from stage 2's
  /// state, or stage 1's) or "unsettled" (no quiet state measured: a step did not converge, or no
  /// step from rest at the analysis Δt converged unfrozen; from stage 2's or stage 1's state too).
  const char* settling = "";
  int symbolicAnalyses = 0;
  long factorisations = 0;         ///< numeric Cholesky factorisations
  long factorUpdates = 0;          ///< low-rank factor updates that replaced one (factor updates)
  long factorColumns = 0;          ///< rank-one terms (springs switched on or off) they applied
  long linearSolves = 0;           ///< systems solved (one per open-close iteration)
  long cgIterations = 0;           ///< conjugate-gradient iterations on a reused factor
  /// Substitutions timed by the cache probe (setSolveCacheProbe), and their seconds: as they
  /// ran, and repeated at once with the factor in cache.
  long probedSubstitutions = 0;
  double probeFirstSeconds = 0, probeRepeatSeconds = 0;
  double factorEntries = 0;        ///< entries of the Cholesky factor's L, last analysis
  long panelSubstitutions = 0;     ///< substitutions with the factor's panels (rounded or exact)
  double panelBytes = 0;           ///< bytes of the last panels built
  /// Contact state changes between open-close iterates (the profile of sudden loading, docs/performance.md):
  /// between locked and sliding, and between open and closed (locked or sliding).
  long stickSlipChanges = 0;
  long supportStateChanges = 0;  ///< accepted steps' changes of a support's state (elastic, yielded, slack, broken)
  long openCloseChanges = 0;
  /// Block pairs whose contacts the narrow phase reused from an earlier search, and pairs it
  /// searched (contact/pair_cache.hpp), summed over the detections.
  long pairsReused = 0, pairsSearched = 0;
  /// Of the pairs searched, those searched without certifying the search (their blocks kept
  /// moving: contact/pair_cache.hpp, Entry::reuses).
  long pairsUncertified = 0;
  int maxContacts = 0;
  double maxPenetration = 0;       ///< largest penetration of a closed contact (m)
  /// Contacts that started closed across a gap wider than 1e-6 w0 (the automatic touching gap's
  /// floor: coordinates rounded in the file), and the widest such gap (m).
  int closedAcrossGaps = 0;
  double widestClosedGap = 0;
  PhaseTimes times;
};

/// The scene after the first equilibrium stage (every initial contact held). It does not depend
/// on joint strengths, so trials that differ only in strength can start from one shared copy.
/// Simulation::settledState packs a later rest the same way.
struct HeldEquilibrium {
  std::vector<model::Block> blocks;
  std::vector<model::Monitor> monitors;
  std::vector<model::PointLoad> pointLoads;
  std::vector<model::FixedPoint> fixedPoints;
  std::vector<model::Support> supports;
  contact::ContactSet contacts;
  std::vector<bool> held;  ///< blocks not supported, kept still during equilibrium
  double dt = 0;           ///< the static step the stage ended with
  bool converged = true;
  int steps = 0;
};

class Simulation {
 public:
  explicit Simulation(model::Scene scene);

  /// Brings the scene to rest under its static loads before t = 0 (dda-method.md §6), in two
  /// stages of static solves: (1) every initial contact held, so gravity is applied without the
  /// springs' dynamic overshoot; (2) the real contact law, so contacts whose share of the load
  /// exceeds their strength (the heel of a block on a slope) slip quasi-statically and hand it
  /// to their neighbours. If stage 2 finds no rest (the scene is failing), the stage-1 state is
  /// kept and the analysis starts from it. Blocks not resting on a fixed block are held still.
  /// (3) If stage 2's rest is not confirmed at the analysis Δt (a static step of seconds froze
  /// contacts that cycle, or hid an out-of-balance force), or its static steps found no rest
  /// without travelling like a failing scene, the scene settles dynamically at the
  /// analysis Δt under the real law with kinetic damping, its slip not softening any joint, until
  /// a step from rest stays at rest; if it travels as far as a failing scene, stage 2's state is
  /// kept (the scene is failing).
  /// `shared`: start stage 2 from this stage-1 state (from holdEquilibrium() of a scene that
  /// differs from this one at most in joint strengths) instead of computing stage 1.
  void bringToEquilibrium(const HeldEquilibrium* shared = nullptr);
  /// Ends stages 2 and 3 of the equilibrium as soon as a vertex of a block has moved more than
  /// `displacement` (m) from where stage 1 left it, and leaves the scene there: for a verdict
  /// whose rule (0) is then decided (the slope gave way before t = 0), settling on towards a rest
  /// or a failing travel, and the analysis after it, would be spent on a settled question. Stage 3
  /// then also goes on past a failing travel (g2·w0), without kinetic damping, up to twice the
  /// limit. 0 (the default): off, the equilibrium runs its course.
  void stopSettlingPast(double displacement) { settlingLimit_ = displacement; }
  /// Runs stage 1 only and returns its state (the scene is left in it).
  HeldEquilibrium holdEquilibrium();
  /// The scene as it stands now, after bringToEquilibrium(`from`) found rest, packed as a start
  /// for runs of the same scene with other joint strengths (their stages 2 and 3 begin there;
  /// `from`'s held blocks and static step are kept). A strength-reduction search starts its
  /// trials from the rest at the case's own strengths this way.
  HeldEquilibrium settledState(const HeldEquilibrium& from) const;
  /// One accepted step. Throws NonConvergenceError once maxStepCuts cuts have failed.
  StepRecord advance();
  bool finished() const;
  /// Lengthens the run by `extra` seconds (a verdict that needs more time to decide).
  void extendDuration(double extra) { scene_.settings.duration += extra; }
  /// Steps also end on the multiples of `period` rather than cross them: a run extended past a
  /// duration of `period` then takes the steps of a run that long from t = 0 (0: none).
  void landStepsOn(double period) { landingPeriod_ = period; }

  const model::Scene& scene() const { return scene_; }
  double time() const { return time_; }
  double modelHalfSize() const { return w0_; }
  double searchDistance() const { return searchDistance_; }
  /// Largest vertex displacement per step (m): g2·w0, at most a tenth of the thinnest block.
  double stepLimit() const { return stepLimit_; }
  const RunStatistics& statistics() const { return stats_; }
  const contact::ContactSet& contacts() const { return contacts_; }
  /// Monitor positions at the end of stage 1 of the equilibrium (every contact held: the elastic
  /// settlement under the loads), before any contact could slip; the case's positions until then.
  const std::vector<Vec2>& monitorsAfterHeldEquilibrium() const { return heldMonitors_; }
  /// The blocks as stage 1 of the equilibrium left them (empty before bringToEquilibrium).
  const std::vector<model::Block>& blocksAfterHeldEquilibrium() const { return heldBlocks_; }
  /// The scene's mechanical energy now; load work counts from t = 0 (after the equilibrium).
  EnergyBudget energy() const;
  /// Velocity of monitor m's point (m/s).
  Vec2 monitorVelocity(int m) const;
  /// Receives one line per equilibrium step and per Δt cut (diagnostics; off by default).
  void setLog(std::function<void(const std::string&)> log) { log_ = std::move(log); }
  /// Receives each step of the initial equilibrium: its stage ("equilibrium", "settling"), the
  /// stage's step count and its steps at most, for a progress line (off by default).
  void setEquilibriumProgress(std::function<void(const char* stage, int step, int budget)> progress) {
    equilibriumProgress_ = std::move(progress);
  }
  /// On (the default): the factor follows the contact state changes by update/downdate when the
  /// case's analysis.factor_updates asks for it. Off: every such change refactorises, whatever the
  /// case says, for comparisons in the bench (--refactorise-only) and the tests.
  void setFactorFollowing(bool on) { factorFollowing_ = on; }
  /// On (the default): a block pair's narrow-phase decisions are reused while its blocks move less
  /// than the search certified (contact/pair_cache.hpp). Off: every pair is searched at every
  /// detection, for comparisons in the bench (--no-pair-cache) and the tests.
  void setPairCache(bool on) { pairCacheOn_ = on; }
  /// Diagnostics: each solve's first substitution also repeated at once and both timed
  /// (LinearSolver::setCacheProbe; RunStatistics::probe*). The run is unchanged.
  void setSolveCacheProbe(bool on) { linearSolver_.setCacheProbe(on); }
  /// On (the default): followed factors substitute with their panels, rounded or exact, once
  /// they pay (solver/panel_factor.hpp). Off: with CHOLMOD's double-precision factor only, for
  /// comparisons in the bench (--double-factor-only) and the tests.
  void setPanelSolves(bool on) { panelSolves_ = on; }
  /// Threads this run's contact search, linearisation and contact judgement may use (1 by
  /// default: a search runs its forward runs side by side instead). The result does not depend
  /// on it (core/parallel.hpp).
  void setThreads(int threads) { threads_ = std::max(1, threads); }

 private:
  /// Settling: dynamic steps before t = 0 (velocity carried, loads at t = 0).
  enum class Regime { Analysis, HeldEquilibrium, Relaxation, Settling };
  /// How settle() ended: at a rest confirmed at the analysis Δt, at an unconfirmed one, with no
  /// static rest but no sign of failure either (stage 3 settles it), or failing.
  /// GaveWay: a block passed stopSettlingPast()'s limit.
  enum class Rest { Confirmed, Unconfirmed, Unsettled, NotFound, GaveWay };
  struct Attempt {
    bool converged = false;
    std::string failure;
    int iterations = 0;
    bool frozeContacts = false;  ///< converged only because cycling contacts were frozen
    Eigen::VectorXd d;  ///< solution, 6 per active block
    std::vector<Vec6> loads;  ///< water and point loads on each active block (their work: loads·d)
    std::vector<Vec6> groundLoads;  ///< the record's inertial force among them (its work, reported apart)
    std::vector<contact::Contact> contacts;
    std::vector<model::SupportState> supportStates;  ///< each support's state as judged
  };
  struct StepState;       ///< what an attempt carries from stage to stage (src/solver/step_state.hpp)
  struct IterateChanges;  ///< what judging an iterate changed (src/solver/step_state.hpp)
  /// The residuals an iterate's solve stops at: the round-off of b's terms, and the one asked for.
  struct ResidualFloors {
    double roundOff = 0, solve = 0;
  };

  // The run around the step (simulation.cpp).
  void markActiveBlocks(const std::vector<bool>& held);
  /// A system of the size that settles by the large-system path (analysis.system_path: ≥ 1000
  /// unknowns unless the case says; the shipped cases have at most 28 blocks).
  bool largeSystem() const;
  /// Unknowns per block in K: 6, or 3 for rigid blocks.
  int unknownsPerBlock() const;
  /// Accepts an attempt (its contacts move into the contact set); `weakens`: its slip softens
  /// the joints (analysis steps only).
  void commit(Attempt& a, double dt, bool weakens);
  /// The linear solver's counters into stats_ (after each committed step, and after a check).
  void recordSolverStatistics();
  /// Largest vertex displacement of an attempt's solution over the active blocks (m), and the
  /// block that has it (-1 if none is active).
  std::pair<double, int> fastestBlock(const Attempt& a) const;
  double largestVertexDisplacement(const Attempt& a) const;  ///< fastestBlock(a).first
  std::string fastestBlockNote(const Attempt& a) const;  ///< the block that moved most, for logs

  // The contact update (contact_update.cpp).
  void detectContacts(bool initial);
  /// Finds the two halves of every edge-to-edge contact (partner_).
  void pairEdgeHalves();
  /// Locked contacts between blocks that the case sets moving along them start sliding.
  void startSlidingWhereBlocksMove();

  // The initial equilibrium (equilibrium.cpp).
  /// Blocks that rest on no fixed block or fixed point through closed contacts.
  std::vector<bool> unsupportedBlocks() const;
  /// Static steps in `regime` until at rest (implied acceleration < 1e-6 g); NotFound if the
  /// scene travels more than g2·w0 (failing) or the step budget runs out. A relaxation rest is
  /// Unconfirmed unless confirmedAtRest().
  Rest settle(Regime regime, double& dt, double largestDt);
  /// How stage 3 ended.
  enum class Settled {
    AtRest,   ///< a step from rest stayed at rest
    Stalled,  ///< it stopped nearing rest, or spent its budget, without travelling like a failing
              ///< scene: the scene is left in the quietest state it reached (the least implied
              ///< acceleration from rest), at rest
    Failed,   ///< it travelled g2·w0 (a failing scene) or passed stopSettlingPast()'s limit
    Unsettled,  ///< a step did not converge, or it stalled without one full, unfrozen step from
                ///< rest at the analysis Δt: no quiet state was measured to start from
  };
  /// Stage 3: dynamic steps at the analysis Δt with kinetic damping until a step from rest stays
  /// at rest, or until the scene travels g2·w0, stops nearing rest or the budget runs out.
  Settled settleDynamically();
  /// True (and recorded in the statistics) once a vertex of an active block is farther than
  /// stopSettlingPast()'s limit from where stage 1 left it.
  bool passedSettlingLimit();
  /// Acceleration (m/s²) below which a step from rest counts as rest: 1e-6 g.
  double restAcceleration() const;
  /// True when `last` (a step at rest) froze no contact and one step from rest at the analysis
  /// Δt, every contact judged by its real law, converges with an implied acceleration below
  /// `restAcceleration`: the analysis will start at rest.
  bool confirmedAtRest(const Attempt& last, double restAcceleration);
  /// After stage 3 of a large system: one static step to the static equilibrium of the settled
  /// contact states, kept if it converges with no contact frozen, implies less than 1e-6 g, and a
  /// step from rest at the analysis Δt confirms it (the rest test of stage 3).
  void polishRest(double staticDt);

  // The step (step.cpp): one attempt at Δt, its open-close iteration and the step limit.
  /// `freezeCycling`: a contact that keeps changing state within the step keeps its state
  /// whatever its law says; `holdSmallViolations`: only while that breaks its law by a small
  /// fraction of the largest contact force (open_close.cpp).
  Attempt tryStep(double dt, Regime regime, bool freezeCycling, bool holdSmallViolations = false);
  /// K's pattern for the blocks these contacts couple.
  void updatePattern(const std::vector<contact::Contact>& contacts);
  /// Whether a step in `regime` carries the blocks' velocity (dynamic analysis and settling).
  bool carriesVelocity(Regime regime) const;
  /// Block terms of a step; `loads` receives the water, point-load and seismic part of f (its work),
  /// `magnitude` the sum of the absolute values of the terms that make up f (its round-off scale).
  void assembleBlockTerms(double dt, Regime regime, std::vector<Mat6>& k, std::vector<Vec6>& f,
                          std::vector<Vec6>& loads, std::vector<Vec6>& magnitude,
                          std::vector<Vec6>* groundLoads = nullptr) const;
  /// The solver's path for the step: fill ordering, CG budget, residual target, a factor kept or
  /// dropped.
  void configureSolver(StepState& s);
  /// K's contact springs (if the states changed) and b, for the attempt's contact states.
  void assembleContactTerms(StepState& s);
  // The supports' part of a step (support_steps.cpp): their elongation vectors on the step's
  // start geometry, their terms in K and b, their states judged in each iterate, and their
  // forces after an accepted step.
  void prepareSupports(StepState& s) const;
  void addSupportTerms(StepState& s);
  /// True if a support's state changed (the iterate is solved again).
  bool judgeSupports(StepState& s);
  /// Moves the points the blocks carry and the supports' forces with an accepted attempt.
  void commitPoints(const Attempt& a);
  /// A large system's factor follows the springs switched on and off (or is dropped).
  void followStateChanges(StepState& s);
  ResidualFloors residualFloors(const StepState& s) const;
  /// Solves the iterate; false (with the attempt's failure) if K is not positive definite or
  /// the solution not finite.
  bool solveIterate(StepState& s);
  /// Solves K d = rhs (6 per active block); rigid blocks solve for their 3 unknowns.
  /// residualFloor: the residual below which the right-hand side is round-off (0: none).
  bool solveSystem(const SystemOperator& k, const Eigen::VectorXd& rhs, Eigen::VectorXd& d, double residualFloor);
  /// Fails a converged attempt whose largest vertex displacement exceeds the step limit.
  void checkStepLimit(Attempt& a) const;

  // The open-close judgement (open_close.cpp).
  /// The round-off guard of the contact rules, from the step's contacts.
  contact::StateTolerance stateTolerance(const std::vector<contact::Contact>& contacts) const;
  /// Every contact's forces and slip under the iterate's solution.
  std::vector<contact::ContactResponse> contactResponses(const StepState& s) const;
  /// Judges every contact, holds or freezes those that cycle, and applies the states.
  IterateChanges judgeIterate(StepState& s);
  /// States after a solve: vertex rule per contact, or edge rule per pair (contact_treatment).
  std::vector<contact::ContactJudgement> judgeContacts(const std::vector<contact::Contact>& cs,
                                                       const std::vector<contact::ContactResponse>& response,
                                                       Regime regime, const contact::StateTolerance& tol) const;
  /// By how much holding contact q in its state breaks its law, against the judgement j.
  double heldViolation(const StepState& s, size_t q, const contact::ContactJudgement& j,
                       const std::vector<contact::ContactResponse>& response) const;
  /// The judgement a changed contact q gets: held or frozen once it has cycled (as the attempt
  /// allows), or its own (counted as a flip).
  contact::ContactJudgement holdOrFreeze(StepState& s, size_t q, contact::ContactJudgement j,
                                         const std::vector<contact::ContactResponse>& response, double allowed) const;
  /// Contact q takes judgement j under response r (its lock anchor, strength, forces).
  void applyJudgement(StepState& s, size_t q, const contact::ContactJudgement& j,
                      const contact::ContactResponse& r) const;
  /// True (with the attempt's failure) once the contact states repeat in a cycle.
  bool stopCycling(StepState& s);
  contact::ContactStrength strengthOf(const contact::Contact& c) const;
  /// The normal and shear springs of contact c (N/m): its joint's kn·L and ks·L over the share L
  /// of the edge-to-edge contact it stands for, or the model's penalties.
  double normalStiffness(const contact::Contact& c) const {
    const double kn = jointNormalStiffness_[c.joint];
    return kn > 0 && c.geometry.overlap > 0 ? kn * 0.5 * c.geometry.overlap : penalty_;
  }
  /// How far contact c stands open after the step just solved (m): an open contact's stored
  /// normal force is still its spring's, the penalty times its (negative) penetration.
  double openingAfterStep(const contact::Contact& c) const {
    return c.closed() ? 0.0 : std::max(0.0, -c.normalForce / normalStiffness(c));
  }
  double shearStiffness(const contact::Contact& c) const {
    const double ks = jointShearStiffness_[c.joint];
    return ks > 0 && c.geometry.overlap > 0 ? ks * 0.5 * c.geometry.overlap : shearPenalty_;
  }
  /// Shear a sliding contact resists with: N tanφ, plus c·L while a softening bond lasts.
  double slidingResistance(const contact::Contact& c) const;
  /// The friction force each sliding contact applies (0 for the others): its own resistance, but
  /// the two ends of an edge-to-edge contact that slide together apply half their sum each.
  std::vector<double> slidingFriction(const std::vector<contact::Contact>& cs) const;
  double edgeLength(const contact::Contact& c) const;

  model::Scene scene_;
  NewmarkIntegrator integrator_;  ///< the time integration (newmark.hpp)
  double w0_ = 1;
  std::vector<double> mass_;   ///< per block (kg/m), fixed at the start: ρ·S₀
  /// The block terms a large system's factor was made with: its Δt, and whether its steps carry
  /// velocity (strain damping then stiffens K_e by β/Δt). A change refactorises.
  struct FactorBlockTerms {
    double dt = 0;
    bool carriesVelocity = false;
    /// Δt to 1e-9: the last step of a run or before a load change is shortened by round-off.
    bool sameAs(const FactorBlockTerms& o) const {
      return carriesVelocity == o.carriesVelocity && std::abs(dt - o.dt) <= 1e-9 * std::max(dt, o.dt);
    }
  };
  FactorBlockTerms factorBlockTerms_;
  std::vector<double> strainRetardation_;  ///< per block: β = 2ξ/ω₁ of its strain damping (s), 0 if none
  std::vector<contact::JointStrength> jointStrength_;  ///< per joint, resolved at the start
  double stepLimit_ = 0;       ///< largest vertex displacement in one step (m)
  /// Where the next step must end rather than cross (advance): the first multiple after time_ of
  /// the quiet steps' growth cap (StepSizeController::growthCap) or of landingPeriod_ (infinity if
  /// neither).
  double nextLanding() const;
  double landingPeriod_ = 0;  ///< landStepsOn()
  double lastLoadChange_ = 0;  ///< model::Scene::lastLoadChange()
  /// Whether a quiet step from time_ may grow: growth is allowed and the loads no longer change.
  bool growing() const { return stepSize_.growthCap() > 0 && time_ >= lastLoadChange_; }
  double searchDistance_ = 0;  ///< 2.5 × stepLimit_
  /// Fixed blocks' vertices where another fixed block continues the face flush (a seam in the
  /// base): no corner for the free blocks (contact::NarrowPhaseSettings::flatCorners).
  std::vector<std::vector<char>> flatCorners_;
  double penalty_ = 0;
  double shearPenalty_ = 0;  ///< penalty_ × the shear ratio
  /// Each joint's kn and ks (Pa/m), 0 where it has none.
  std::vector<double> jointNormalStiffness_, jointShearStiffness_;
  double lightestPenetration_ = INFINITY;  ///< 1e-3 of the lightest free block's W/p (m)
  double time_ = 0;
  double loadWork_ = 0;  ///< work of water and point loads since t = 0 (J/m)
  double groundMotionWork_ = 0;  ///< the record's share of it (J/m)
  double relaxationTravel_ = 0;  ///< summed largest vertex displacement of stage 2's steps (m)
  double settlingLimit_ = 0;     ///< see stopSettlingPast(); 0: off
  std::vector<int> active_;  ///< dof block index per block, −1 when fixed or held
  int nActive_ = 0;
  contact::ContactSet contacts_;
  std::vector<assembly::ContactKinematics> kinematics_;
  std::vector<int> partner_;  ///< other half of the same edge-to-edge contact, or −1
  long partnerVersion_ = -1;  ///< the contacts' pairingVersion() partner_ was made for
  std::vector<int> sweepOrder_;  ///< the broad phase's order of the blocks, kept between steps
  std::vector<Vec2> heldMonitors_;  ///< see monitorsAfterHeldEquilibrium()
  std::vector<model::Block> heldBlocks_;  ///< see blocksAfterHeldEquilibrium()
  assembly::BlockSparseMatrix matrix_;
  std::vector<std::pair<int, int>> lastCouplings_;  ///< block pairs of the contacts matrix_'s pattern was made for
  bool panelSolves_ = true;
  LinearSolver linearSolver_;
  FactorSprings factorSprings_;  ///< the contact springs the factor holds (with factor updates)
  bool factorFollowing_ = true;
  contact::PairCache pairCache_;
  bool pairCacheOn_ = true;
  int threads_ = 1;
  StepSizeController stepSize_;
  std::vector<Eigen::Matrix3d> elasticity_;
  RunStatistics stats_;
  /// analysis.wall_clock_limit as a deadline from construction (equilibrium included), or none.
  std::optional<std::chrono::steady_clock::time_point> deadline_;
  /// Throws BudgetExceededError once the deadline has passed, and Cancelled once the thread's
  /// cancellation scope (core/cancellation.hpp) is told to stop.
  void checkDeadline() const;
  std::function<void(const std::string&)> log_;
  std::function<void(const char*, int, int)> equilibriumProgress_;
};

/// Runs a scene from equilibrium to its duration; `observe` sees t = 0 and every step.
/// Stage 3's budget, in steps per analysis.equilibrium_max_steps (200 by default: 4000 steps).
constexpr int kSettlingStepsPerEquilibriumStep = 20;

using StepObserver = std::function<void(const Simulation&, const StepRecord&)>;
void runAnalysis(Simulation& sim, const StepObserver& observe, const HeldEquilibrium* shared = nullptr);

}  // namespace ddaslope::solver
