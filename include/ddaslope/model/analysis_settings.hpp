#pragma once
// Numerical settings of an analysis. Each field: unit, range, and what it trades.
#include <string>

namespace ddaslope::model {

enum class AnalysisMode { Dynamic, Static };
enum class PlaneMode { Strain, Stress };
/// How the two vertex-to-edge halves of an edge-to-edge contact are judged (docs/contact-model.md).
enum class ContactTreatment { Edge, Vertex };
/// How a scene settles (docs/accuracy.md, "Small and large systems"). small: the initial
/// equilibrium relaxes statically before it settles dynamically, and the contact law holds
/// strictly throughout. large: small law violations of cycling contacts are held while the scene
/// settles, and the static relaxation of the initial equilibrium is skipped for dynamic settling.
/// auto: large from kLargeSystemMinUnknowns unknowns. (How the linear systems are solved is
/// AnalysisSettings::factorUpdates.)
enum class SystemPath { Auto, Small, Large };

/// Unknowns (6 per deformable block, 3 per rigid one) from which `auto` takes the large-system
/// path: below it a refactorisation costs less than following the factor, above it refactorising
/// every state change of a violent start dominates the run (docs/performance.md).
inline constexpr int kLargeSystemMinUnknowns = 1000;

struct AnalysisSettings {
  /// Simulated time (s), > 0.
  double duration = 1.0;
  /// Nominal time step Δt (s), > 0. Smaller: more accurate impacts and less numerical
  /// dissipation (Newmark γ = 1), more steps. Steps are cut automatically when needed.
  double timeStep = 1e-3;
  /// Where Δt came from, for reports: "analysis.time_step", "preset balanced", "default preset
  /// balanced" (a case with neither a time step nor a preset; docs/accuracy.md), "--time-step".
  std::string timeStepOrigin = "analysis.time_step";
  /// dynamic: velocities carried between steps; static: velocities reset each step (Shi's
  /// quasi-static mode, a heavily damped path to equilibrium).
  AnalysisMode mode = AnalysisMode::Dynamic;
  /// Plane strain (benchmarks' default) or plane stress for the block elasticity.
  PlaneMode plane = PlaneMode::Strain;
  /// Rigid blocks: three unknowns each (u0, v0, r0), no strain. The linear system is half the
  /// size (the factorisation about a quarter of the work); the blocks' elastic deformation and
  /// its stresses are lost, and all compliance sits in the contact springs.
  bool rigidBlocks = false;
  /// Damping of each deformable block's own strain modes, as a fraction of critical at the lowest
  /// of them (Kelvin–Voigt: σ_v = β E ε̇, β = 2 ξ / ω₁; docs/accuracy.md, "Strain damping"). 0 is
  /// Shi's undamped block, whose strain modes ring through every stick-slip event and impact and
  /// can walk a block down a slope it should creep along (+23 % to +1500 % in 2 s on a 10 m block
  /// 0.1° past its limit); 1 makes them critically damped. Dynamic steps only: rest, rigid motion
  /// and equilibria do not change.
  double strainDamping = 1.0;
  /// edge: each edge-to-edge contact judged as one (Zhang et al. 2014, the default); vertex:
  /// original DDA, each half judged alone with c·L/2 (fails cohesive blocks too early).
  ContactTreatment contactTreatment = ContactTreatment::Edge;
  /// Normal contact penalty p (N/m per metre of thickness). 0 = automatic: penaltyFactor × max E.
  /// Stiffer: less interpenetration and settling, worse conditioning and more open-close work.
  double penalty = 0;
  /// Automatic penalty as a multiple of the largest Young's modulus (Shi recommends 10–100).
  double penaltyFactor = 40;
  /// Shear spring stiffness as a fraction of the normal penalty (Shi: 1/2.5).
  double shearPenaltyRatio = 0.4;
  /// g2: largest vertex displacement allowed in one step as a fraction of w0 (half the model
  /// size). Also sets the contact search distance 2.5·g2·w0. Smaller: finer contact resolution,
  /// more cut steps; larger: faster, coarser.
  double maxDisplacementRatio = 0.005;
  /// Open-close iterations allowed per step before the step is cut (≥ 1).
  int openCloseMaxIterations = 30;
  /// Relative change of friction forces below which a sliding contact counts as converged.
  double frictionTolerance = 1e-4;
  /// Stability verdict of the searches (docs/calibration.md): failing once a monitor moves this
  /// far (m) after t = 0. 0: 1e-3 of w0. It must exceed the bounded transients of a stable scene
  /// (decimetres for a kilometre-scale slide of many blocks) and be reached by a failing one.
  double failureDisplacement = 0;
  /// How far (m) a joint that ends on a concave bend of a fixed block is moved up the upper face,
  /// so that the block below owns the bend (model/kinks.hpp, moveJointEndsOffBends). < 0:
  /// automatic, max(5e-3 w0, 2 × the failure displacement), the automatic kink block's width; 0:
  /// where it was drawn (the block above then has its corner in the notch, and F may follow the
  /// contact stiffness: docs/research/bilinear-slab.md).
  double jointEndOffset = -1;
  /// Verdict: a monitor still faster than this (m/s) at the end, and not slowing down, is
  /// failing. 0: 1e-4 of the failure displacement per second.
  double restingSpeed = 0;
  /// Round-off guard on contact states, as a fraction of w0: a contact changes state only when
  /// its criterion is passed by this displacement, or in force by the larger of penalty × it and
  /// 1e-9 of the largest contact force. Larger: fewer open-close iterations on unloaded
  /// contacts, a blunter strength threshold.
  double contactStateTolerance = 1e-12;
  /// Budget of a run: it stops with exit 3, a partial history and a summary saying
  /// why after this many analysis steps (0: automatic, 100 × duration/Δt + 1000, which only a run
  /// whose Δt has collapsed reaches) or this many seconds of wall time (0: none).
  int maxSteps = 0;
  double wallClockLimit = 0;
  /// Largest Δt of a quiet step, as a multiple of timeStep (1: never above it). A step that
  /// changed no contact state after its first solve (at most two open-close iterations), needed
  /// no cut and moved no vertex by 2 % of the step limit lets the next grow by 1.5×, up to this:
  /// a slope creeping at a steady acceleration, which Newmark's β = ½, γ = 1 integrates exactly
  /// at any Δt, is crossed in fewer steps. Events inside a grown step (a block stopping, a bolt
  /// yielding, a corner landing) are resolved only to that step's Δt; a ground-motion record or a
  /// reservoir history is followed at timeStep until it ends (Scene::lastLoadChange), and loads
  /// that grow at a rate keep it throughout (docs/accuracy.md).
  /// 0: automatic, 1 in a run and calibration::kTrialStepGrowth in a stability trial
  /// (calibration::trialStepGrowth), whose verdict watches only where the blocks end up.
  double timeStepGrowth = 0;
  /// Successive Δt cuts allowed for one step before the analysis reports non-convergence.
  int maxStepCuts = 12;
  /// Factor applied to Δt when a step is cut (0 < f < 1).
  double stepCutFactor = 0.3;
  /// Bring the scene to gravity equilibrium before t = 0 with every initial contact held
  /// (no sliding, no opening). Avoids the penalty springs' start-up overshoot that breaks
  /// joints the static problem would keep (dda-method.md §6). Costs a few static solves.
  bool initialEquilibrium = true;
  /// Stage 3 of the equilibrium (Simulation::bringToEquilibrium): a relaxed state that is not
  /// confirmed at rest at the analysis Δt settles dynamically (kinetic damping) before t = 0, so
  /// the analysis starts at rest. Off: the analysis may start with an out-of-balance force whose
  /// release slides and softens joints (kept for comparison).
  bool settleDynamically = true;
  /// A trial of a search stops as soon as it is at rest for good (calibration/verdict.hpp, early
  /// rest); off: every stable trial runs its whole duration (for comparison).
  bool earlyRest = true;
  /// Largest number of static solves spent on the initial equilibrium.
  int equilibriumMaxSteps = 200;
  /// Two edges of different blocks within this angle (degrees) are an edge-to-edge contact.
  double edgeParallelToleranceDeg = 1.0;
  /// Initial gaps up to this fraction of w0 count as touching: the contact starts closed,
  /// bonded, and its spring's zero is at the initial gap. Negative: automatic (Scene::touchingGap).
  double initialContactTolerance = -1;
  SystemPath systemPath = SystemPath::Auto;
  /// Whether the factor follows the contacts' state changes (docs/accuracy.md, "Small and large
  /// systems"): by low-rank update/downdate with nested-dissection ordering, products with K
  /// from its terms, and iterates judged at a residual of 1e-8 until one changes no state, which
  /// is solved to round-off (the same results as refactorising, round-off apart, sooner). Off:
  /// every state change refactorises (minimum-degree ordering) and each iterate is solved to
  /// round-off (analysis.factor_updates = "off": the round-off of figures docs/accuracy.md says
  /// were made that way).
  bool factorUpdates = true;
};

/// Whether a scene of `unknowns` free unknowns takes the large-system path under these settings.
inline bool largeSystemPath(const AnalysisSettings& s, int unknowns) {
  return s.systemPath == SystemPath::Large || (s.systemPath == SystemPath::Auto && unknowns >= kLargeSystemMinUnknowns);
}


}  // namespace ddaslope::model
