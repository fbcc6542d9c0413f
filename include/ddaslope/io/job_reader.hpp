#pragma once
// Reads a back-analysis job (JSON, docs/calibration.md): the case, the parameters to estimate,
// the observations and the optimiser settings. Plain data; calibration/ runs it.
#include <string>
#include <vector>

#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/model/settings_override.hpp"

namespace ddaslope::io {

struct ParameterSpec {
  std::string name;
  /// Either a joint property ("cohesion", "residual_cohesion", "tensile_strength" Pa;
  /// "friction_angle", "residual_friction_angle" degrees; "weakening_distance" m) of
  /// `joint`, or any number of the case at `jsonPath`.
  std::string joint, property, jsonPath;
  double min = 0, max = 0;
  double start = 0;  ///< where the local search starts if there is no global one
  bool hasStart = false;
};

struct ObservationSpec {
  enum class Kind { Series, FactorOfSafety, Runout };
  Kind kind = Kind::Series;
  std::string label;
  std::string monitor, quantity = "displacement";  ///< Series and Runout
  std::vector<double> times, values;                ///< Series (from CSV)
  double target = 0;                                ///< FactorOfSafety or Runout
  std::vector<std::string> joints;                  ///< FactorOfSafety: joints reduced (empty: all)
  double sigma = 0;                                 ///< measurement uncertainty (units of the value)
  double weight = 1;
};

/// optimiser.global's name for a grid scan (grid_points per parameter; its evaluations are
/// independent, so they spread over threads and MPI ranks) instead of an NLopt algorithm.
inline constexpr const char* kGridSearch = "grid";

struct OptimiserSpec {
  std::string global = "GN_DIRECT_L";  ///< "" for none
  std::string local = "LN_BOBYQA";     ///< "" for none
  int globalEvaluations = 60;
  int localEvaluations = 60;
  double xtolRel = 1e-4;               ///< local search stops when steps are this small (of the range)
};

/// How the estimate's precision is measured (calibration/precision.hpp): on by default when an
/// observation is a run-out (a rough objective), or when the job asks.
struct PrecisionSpec {
  bool enabled = false;
  int scanPoints = 7;              ///< per parameter, over estimate ± halfWidth of its search range
  double halfWidth = 0.1;          ///< fraction of the search range on each side
  std::vector<double> timeStepFactors{0.8, 0.9, 1.1, 1.25};  ///< the Δt ensemble at the estimate
};

struct BackanalysisJob {
  std::string jobPath;
  std::string casePath;  ///< resolved relative to the job file
  /// The case file's content, read once with the job: every trial parses the same text, even if
  /// the file changes while the search runs.
  std::string caseText;
  std::vector<ParameterSpec> parameters;
  std::vector<ObservationSpec> observations;
  OptimiserSpec optimiser;
  PrecisionSpec precision;
  int gridPoints = 15;   ///< per axis, for the misfit map of two parameters (0: none)
  int threads = 2;
  /// Imposed on every forward run's case, in order: the job's own "preset" and "blocks", then the
  /// command line's. Empty: the case's own settings (a case without a time step runs `balanced`).
  std::vector<model::SettingsOverride> model;
  /// Numbers of the case changed before it is read (the command line's --set).
  std::vector<CaseOverride> caseOverrides;
};

/// Throws InputError (file, JSON path, expected vs found) on bad input.
BackanalysisJob readJob(const std::string& path);

}  // namespace ddaslope::io
