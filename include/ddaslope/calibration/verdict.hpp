#pragma once
// Stability verdict of one forward run: the function the bisection and back-analysis loops search.
#include <functional>
#include <optional>
#include <string>

#include "ddaslope/model/scene.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::calibration {

/// A run is failing when, for any monitor or any point of a free block (monitors are where the user
/// looks; a slope fails wherever it moves, so every free block takes part):
/// (0) it moved more than `failureDisplacement` while the scene came to rest before t = 0, once
///     its contacts could slip (stages 2 and 3 of the equilibrium; stage 1's elastic settlement
///     with every contact held does not count): a slope that gives way there and locks again
///     metres further on has failed, even if it then stands. The equilibrium stops at the step a
///     point passes it (Simulation::stopSettlingPast), and no analysis follows;
/// (a) it moves more than `failureDisplacement` from where it is at t = 0, after the equilibrium;
///     the run stops there: its verdict is certain; or
/// (b) at the end of the run it is still moving: over the last quarter of the run its net
///     displacement is above the noise floor and at least 90 % of its net displacement over the
///     quarter before (a slide just past failure accelerates: 7/5 of it from rest), and either the
///     largest motion since t = 0 is at least 10 % of `failureDisplacement`, or the motion grows
///     (net speed over the last window up by 10 % or more at each of two extensions of the run).
///     A point that its last window's pace, not slowing, carries past `failureDisplacement` within
///     one more window is not judged on its trend: the run goes on (one extension by its
///     duration, stopping at the threshold). Rule (a) decides it if it gets there; if it does not,
///     the windows of the longer run do, as after any extension. The path is the one a longer
///     run follows, so the verdict is the one a search's re-run of a trend failure would reach.
///     In a search (VerdictSettings::runOnLength), a trend failure is run on further, to the
///     length of the review's re-run, and judged afresh there.
/// A still-moving motion under 10 % of `failureDisplacement` that neither grows nor stops within
/// three extensions of the run (each by its duration) is **undecided**: reported as such, never as
/// failure: a contact chattering at a T-junction moves a little and steadily, and is no failure.
/// Motion is judged on net displacements over windows of simulated time, never on instantaneous
/// speeds, so contact-spring vibration cannot trip it. The noise floor of a point is the larger
/// of `restingSpeed` × window and 5 × the scatter of its path about a least-squares quadratic over
/// the last two windows (a steady slide or a smooth acceleration has none; a vibration of
/// amplitude A has about A/√2, and moves a point at most 2A net). A block's path is its centroid
/// and its rotation times its reach, sampled 64 times per run duration. A verdict that is
/// marginal, a net motion within twice the floor or a window ratio in [0.75, 1.25] (a steady creep,
/// or a transient that neither grows nor dies), is not guessed: the run is extended once by its
/// duration and judged again on quarters of the longer run. Neither rule depends on Δt: sliding
/// at constant acceleration is integrated exactly by Newmark β = 1/2, γ = 1.
///
/// **Early rest** (analysis.early_rest, on by default): a run stops as stable before its duration
/// once it cannot change by itself. Checked from an eighth of the duration on, at each of the 64
/// samples of the blocks' paths, with windows the quarters of the time so far: (1) nothing in the
/// scene changes with time (no ground motion record, load rates or water level series; a record or
/// level history that stops changing by the middle of the run counts from then on, the time since
/// it stopped being the time so far, so that the end-of-run windows lie after it too); (2) no
/// contact or support changed state, and no step was cut or held contacts frozen, over the last
/// two windows; (3) every monitor and free block is still: its net motion over each window is
/// round-off noise (within 5× its scatter about a smooth path, the scatter under 1e-3 of the
/// end-of-run floor), or its last window's motion, grown to the end of the run by a doubling every
/// window (or faster if it grew faster), stays under half the floor rule (b) applies at the end.
/// Then every contact and support stays as it is, the scene is an elastic system at rest under
/// constant loads, and the end-of-run verdict could only be "at rest".
struct VerdictSettings {
  /// m; ≤ 0: 1e-3 of the model half-size w0.
  double failureDisplacement = 0;
  /// m/s; ≤ 0: 1e-4 of failureDisplacement per second. A net motion slower than this over a
  /// window counts as rest whatever the noise.
  double restingSpeed = 0;
  /// > 1: a run judged failing on its trend (rule b) before this many times its duration goes on
  /// in place to that length and is judged afresh there, on quarters of the whole (its extensions
  /// then each that long), as a run that long from t = 0 along the same path would be
  /// (TrialResult::runOn). A search sets its review's re-run length (kReRunLength) so that no
  /// trend failure is run twice; 1: judged at the duration.
  double runOnLength = 1;
  /// The trial's length in the case's durations (a review's re-run: kReRunLength): its steps
  /// land on the multiples of the case's duration (trialStepGrowth).
  double length = 1;
};

/// Which rule decided a verdict.
enum class VerdictRule {
  AtRest,             ///< stable: net motion over the last window below the noise floor
  SlowingDown,        ///< stable: net motion over the last window < 90 % of the window before
  PassedDisplacement, ///< failing: rule (a)
  StillMoving,        ///< failing: rule (b)
  MovedWhileSettling, ///< failing: rule (0)
  NotConverged,       ///< failing: the run did not converge
  Undecided,          ///< neither: a small motion that neither grew nor stopped within the extensions
};
const char* describe(VerdictRule rule);
/// Short name for tables and JSON: "at_rest", "slowing_down", "failure_displacement",
/// "still_moving", "moved_while_settling", "not_converged", "undecided".
const char* name(VerdictRule rule);

struct TrialResult {
  bool stable = true;
  /// Neither stable nor failing (VerdictRule::Undecided); `stable` is false, and a search counts
  /// the trial as failing (the safe side) and says so.
  bool undecided = false;
  VerdictRule rule = VerdictRule::AtRest;
  /// Largest displacement after t = 0 of a monitor or of any point of a free block (m).
  double maxDisplacement = 0;
  /// Largest such displacement in stages 2–3 of the equilibrium (m).
  double settlingDisplacement = 0;
  std::string movedMost;           ///< the point that moved most: "monitor ID" or "block ID"
  std::string decidedBy;           ///< the point whose windows decided rule (b) or rest
  double failureDisplacement = 0;  ///< the threshold of rule (a) in force (m)
  double finalSpeed = 0;           ///< largest speed of a monitor or a free block's point at the end (m/s)
  double lastWindowMotion = 0;     ///< net displacement over the last window, deciding point (m)
  double previousWindowMotion = 0; ///< over the window before (m)
  double noiseFloor = 0;           ///< that point's floor (m)
  /// Simulated time when the trial stopped, or (rule a) when the first point passed the failure
  /// displacement, interpolated within the step that passed it (s).
  double timeReached = 0;
  int steps = 0;                   ///< accepted steps after t = 0
  int equilibriumSteps = 0;        ///< steps before t = 0: the equilibrium's static and settling steps
  bool extended = false;           ///< run longer than its duration (a marginal verdict, a small motion, or a slide run on)
  int extensions = 0;              ///< how many times (by the duration, or by the run-on length once run on)
  bool marginal = false;           ///< still marginal after the extension: decided by the 90 % rule
  bool converged = true;           ///< false if the run hit non-convergence (counted as failing)
  bool earlyRest = false;          ///< stopped before its duration: at rest for good (early rest)
  /// Judged failing on its trend and run on to VerdictSettings::runOnLength times its duration:
  /// the verdict is that of the longer run (a search's review takes it as its own re-run).
  bool runOn = false;
  /// How the equilibrium's settling ended (solver::RunStatistics::settling): "at_rest",
  /// "stalled" (the analysis starts from the quietest state it reached), "failed" (it moved like a
  /// failing scene), "unsettled" (no quiet state measured; both from stage 2's or stage 1's
  /// state), or "" (no settling: stage 2 confirmed rest, or none was asked for).
  std::string settling;
  /// With settling "stalled": the acceleration a step from the quietest state implied, in g, the
  /// kick the analysis starts with (a failing slope's own out-of-balance force among it); else 0.
  double startAcceleration = 0;
  const char* reason = "";         ///< describe(rule)
};

/// analysis.time_step_growth left automatic in a stability trial: the verdict judges where the
/// blocks end up, not when a contact changed state within a step, so quiet steps grow up to this.
inline constexpr int kTrialStepGrowth = 10;

/// The Δt growth a stability trial takes: the case's analysis.time_step_growth, or
/// kTrialStepGrowth when it is automatic. Its steps also land on the multiples of the case's
/// duration (Simulation::landStepsOn), so that a trend failure run on past it takes the steps its
/// re-run from t = 0 would.
double trialStepGrowth(const model::AnalysisSettings& settings);

/// Sees a trial's simulation as it ended, with its verdict (to write its final state out).
using TrialEndObserver = std::function<void(const solver::Simulation&, const TrialResult&)>;

/// Runs the scene (equilibrium first, from `shared` when given: see solver::HeldEquilibrium)
/// until its duration or until rule (a) fires; then `atEnd`, if any, sees the final state.
/// `settled` (with `shared`): receives the state at t = 0 when the equilibrium found rest
/// (Simulation::settledState), and is left alone otherwise.
TrialResult judgeStability(const model::Scene& scene, const VerdictSettings& settings = {},
                           const solver::HeldEquilibrium* shared = nullptr, const TrialEndObserver& atEnd = {},
                           std::optional<solver::HeldEquilibrium>* settled = nullptr);

/// What a window judgement sees of one monitor: its net displacement over the last two windows
/// and its noise floor. Pure, for tests.
struct WindowMotion {
  double last = 0, previous = 0, floor = 0;
};
enum class WindowVerdict { AtRest, SlowingDown, StillMoving };
WindowVerdict judgeWindows(const WindowMotion& m, bool* marginal = nullptr);

}  // namespace ddaslope::calibration
