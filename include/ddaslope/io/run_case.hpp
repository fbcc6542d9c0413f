#pragma once
// Runs a scene and records what users read: the monitor trace, history.csv, summary.json.
#include <optional>
#include <string>
#include <vector>

#include "ddaslope/model/scene.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::io {

struct MonitorSample {
  double ux = 0, uy = 0, vx = 0, vy = 0;
};

/// Time series of all monitors, one row per accepted step (and t = 0).
struct Trace {
  std::vector<std::string> monitorIds;
  std::vector<solver::StepRecord> steps;
  std::vector<std::vector<MonitorSample>> samples;  ///< [row][monitor]
  std::vector<solver::EnergyBudget> energy;         ///< [row]
  std::vector<std::string> supportIds;
  std::vector<std::vector<double>> supportForces;   ///< [row][support]: axial force, N/m, tension positive
  /// Largest rise of the mechanical energy above its value at t = 0 (J/m): a spurious gain,
  /// since a correct run only dissipates; and the energy scale it is judged against (the
  /// largest of the kinetic energy and the potential energy released).
  double largestEnergyGain() const;
  double energyScale() const;
  /// Largest rise of the mechanical energy within one step (J/m), and the time of that step: an
  /// impact that injects energy shows here even after the run has dissipated more than it gained.
  double largestStepGain(double* time = nullptr) const;
  /// What `run`'s warning judges a gain against: the energy scale, or the largest stored elastic
  /// energy when that is more (a slope at rest releases almost nothing, yet its springs hold a lot).
  double energyInPlay() const;
  int monitorIndex(const std::string& id) const;
};

struct ExpectationResult {
  model::Expectation expectation;
  double actual = 0;
  bool passed = false;
  /// False when the expectation is at a time past the run's end: not checked (and not passed).
  bool reached = true;
  double runEnd = 0;  ///< the run's last time (s)
  std::string describe() const;
};

struct RunOutcome {
  bool completed = false;
  std::string failure;  ///< non-convergence message when not completed
  bool budgetStop = false;  ///< stopped by analysis.max_steps or wall_clock_limit (exit 3)
  Trace trace;
  solver::RunStatistics statistics;
  std::vector<model::Support> finalSupports;  ///< the supports' states and forces at the end
  double wallTime = 0;
  double stepLimit = 0, searchDistance = 0;  ///< the run's effective values (m)
  std::vector<ExpectationResult> expectations;
  int vtkFrames = 0;  ///< frames of the VTK series written (RunOptions::vtk)
  int snapshotsWritten = 0;  ///< snapshot_NN.png written (times past the run's end are not)
};

struct RunOptions {
  std::optional<std::string> outputDir;  ///< write history.csv and summary.json here
  std::string casePath;                  ///< named in summary.json
  bool progress = false;                 ///< progress line on stderr (a terminal's, redrawn)
  /// A long run states its size on stderr before it starts and, without `progress`, writes a
  /// progress line a minute (a log file, a batch job).
  bool announce = false;
  bool verbose = false;                  ///< equilibrium steps and Δt cuts on stderr
  /// Record the energy budget every step (always when writing to outputDir). A search that
  /// only reads monitors turns it off: it costs ~1 % of a step at 1000 blocks.
  bool energy = true;
  /// Times (s) at which to write snapshot_<k>.png pictures into outputDir (the first step at or
  /// after each time; t = 0 is the state after equilibrium).
  std::vector<double> snapshotTimes;
  /// Write the VTK series (io/scene_vtk.hpp) into outputDir/vtk: t = 0, the first step at or
  /// after every multiple of vtkEvery, and the last state reached, also by a run that stops.
  bool vtk = false;
  double vtkEvery = 0;  ///< s; ≤ 0: a hundredth of the duration
  /// Start the equilibrium's second stage from this state (see solver::HeldEquilibrium).
  const solver::HeldEquilibrium* sharedEquilibrium = nullptr;
  /// Threads of this one run (solver::Simulation::setThreads); the result does not depend on it.
  int threads = 1;
  /// `run --at-fos`: the factor the scene's joint strengths were reduced by, and which joints
  /// (names), for summary.json. 0: none.
  double strengthReduction = 0;
  std::vector<std::string> reducedJoints;
};

/// Runs to the scene's duration. Non-convergence is returned, not thrown; the partial history is
/// then written as history.partial.csv and summary.json says "non_convergence".
RunOutcome runScene(const model::Scene& scene, const RunOptions& options);

/// Value of an expectation's quantity on a trace (interpolated in time; max over run if no time).
double measure(const Trace& trace, const model::Expectation& e);
std::vector<ExpectationResult> evaluateExpectations(const Trace& trace,
                                                    const std::vector<model::Expectation>& ex);

}  // namespace ddaslope::io
