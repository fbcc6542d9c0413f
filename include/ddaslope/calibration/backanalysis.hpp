#pragma once
// Back-analysis: the joint strengths (or any case values) that best explain the observations.
// Misfit = Σ weight · mean(((simulated − observed)/σ)²) over the observations; a global search
// then a local polish (NLopt), and for two parameters a misfit map over the box.
#include <string>
#include <vector>

#include "ddaslope/calibration/precision.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/core/task_farm.hpp"
#include "ddaslope/io/progress.hpp"

#include "ddaslope/io/job_reader.hpp"
#include "ddaslope/model/scene.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::calibration {

/// How one observation is met at a parameter vector.
struct ObservationFit {
  std::string label;
  /// Factor of safety or runout: the simulated and observed values. Series: the RMS of
  /// simulated − observed over its times, and 0.
  double simulated = 0, observed = 0;
  double sigma = 0;
  bool series = false;
  bool converged = true;  ///< false: the forward run did not converge (no simulated value)
  /// A factor-of-safety observation: the trials of its strength-reduction search (provenance).
  std::vector<TrialRecord> trials;
};

struct BackanalysisResult {
  std::vector<std::string> names;
  std::vector<double> estimate;     ///< physical units (friction angles in degrees)
  double misfit = 0;
  std::vector<ObservationFit> fit;  ///< each observation at the estimate
  int evaluations = 0;              ///< misfit evaluations (each ≥ 1 forward run)
  int forwardRuns = 0;
  /// Runs made ahead on a spare thread (job.threads ≥ 2, no factor-of-safety observation): of
  /// DIRECT's next points, and of a precision study started at the global stage's best; and of
  /// those the ones not used (a point no optimiser asked for, a study at a point that did not
  /// stay the estimate), which are not in forwardRuns.
  int runsAhead = 0, runsAheadUnused = 0;
  /// The precision study started on the spare thread while the local stage ran, and was kept
  /// (the local stage did not move the estimate).
  bool precisionStartedEarly = false;
  std::string globalStatus, localStatus;
  double wallTime = 0;
  /// Misfit map (two parameters): axes and values[i][j] at (axis0[i], axis1[j]).
  std::vector<double> axis0, axis1;
  std::vector<std::vector<double>> map;
  /// True when the data fix only a relation between the two parameters (a factor of safety of 1
  /// alone does this): along one of them, the misfit profile stays within one standard deviation
  /// of the optimum over at least 40 % of its range.
  bool lineOnly = false;
  std::string statement;            ///< the plain statement for the user
  /// The estimate as ranges (job.precision; run-out observations), empty when not measured.
  Precision precision;
};

/// The job's case with the parameter values x (physical units) applied.
model::Scene sceneAt(const io::BackanalysisJob& job, const std::vector<double>& x);

/// Misfit of one parameter vector (physical units); counts forward runs in `runs`. `shared`: the
/// first equilibrium stage, when the parameters are joint strengths only. `searchThreads`: trial
/// factors run at once by a factor-of-safety observation's search (1 when the caller already
/// evaluates several points in parallel, as the misfit map does).
/// `fit`: if given, receives how each observation is met.
double misfitAt(const io::BackanalysisJob& job, const std::vector<double>& x, int* runs = nullptr,
                const solver::HeldEquilibrium* shared = nullptr, int searchThreads = 1,
                std::vector<ObservationFit>* fit = nullptr);

/// Misfit of a scene already built (misfitAt with sceneAt(job, x) and, say, a Δt changed).
double misfitOf(const io::BackanalysisJob& job, const model::Scene& scene, int* runs = nullptr,
                const solver::HeldEquilibrium* shared = nullptr, int searchThreads = 1,
                std::vector<ObservationFit>* fit = nullptr);

/// The search, the precision study and the misfit map of a job. Independent evaluations (a
/// grid global stage, "optimiser.global": "grid", and the map) run on `farm` (null: job.threads
/// threads in this process). Under MPI only the root's result is complete: the other ranks take
/// part in those stages only.
/// `progress`: told after every evaluation (stage global / grid / local / map, its budget, the
/// best misfit so far).
BackanalysisResult runBackanalysis(const io::BackanalysisJob& job, TaskFarm* farm = nullptr,
                                   const io::ProgressSink& progress = {});

/// For a job that fits one joint's cohesion or friction angle to one observation F = 1: the
/// `ddaslope critical` command that answers it directly (the strength at which the slope is at
/// its limit, by bisection on the stability verdict, where each evaluation of the fit is a whole
/// strength-reduction search). Empty for any other job.
std::string directSearchCommand(const io::BackanalysisJob& job);

}  // namespace ddaslope::calibration
