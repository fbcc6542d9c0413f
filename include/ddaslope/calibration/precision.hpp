#pragma once
// The honest precision of a back-analysed estimate when the objective is rough (run-out
// observables: a travel or a peak speed jumps when the contact history changes, so a misfit of
// 0.007 at the optimum says nothing about how well the data fix the parameter).
// Two measurements around the estimate:
// - a scan of each parameter (the others held at the estimate): the values whose misfit lies
//   within one standard deviation of the best seen (best + Σ weights, as judgeConstraint uses)
//   form the range the data allow;
// - an ensemble of forward runs at the estimate with Δt scaled by factors inside its documented
//   range (which should not matter): the spread of each simulated observable is the objective's
//   numerical noise, and divided by the observable's slope along the scan, a resolution.
#include <atomic>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ddaslope/io/job_reader.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::calibration {

struct ScanPoint {
  double value = 0;                ///< the parameter (physical units)
  double misfit = 0;
  std::vector<double> simulated;   ///< each observation's simulated value (NaN: not converged)
};

struct ParameterRange {
  std::string name;
  double estimate = 0;
  double low = 0, high = 0;        ///< scanned values within one standard deviation of the best
  bool openLow = false, openHigh = false;  ///< the range reaches the scan's end: it is at least this
  /// ± in parameter units from the numerical noise (largest over the observations that trend
  /// along this parameter); NaN when none does.
  double noiseResolution = 0;
  std::vector<ScanPoint> scan;     ///< sorted by value, the estimate included
};

struct EnsembleMember {
  double timeStepFactor = 1;
  double misfit = 0;
  std::vector<double> simulated;
};

/// A scan point that fits better than the estimate (see betterThanEstimate).
struct BetterPoint {
  size_t parameter = 0;  ///< index of the scanned parameter
  double value = 0;      ///< its value there (the others at the estimate)
  double misfit = 0;
  double estimateMisfit = 0;
  double misfitNoise = 0;  ///< half the spread of the Δt ensemble's misfits
};

struct Precision {
  std::vector<ParameterRange> parameters;
  std::vector<EnsembleMember> ensemble;  ///< at the estimate, the unperturbed run first
  std::vector<double> noise;             ///< per observation: half the ensemble's spread (max − min)/2
  std::string statement;
  /// Set when the scan found a clearly better point: the search stopped short of the optimum.
  std::optional<BetterPoint> better;
};

/// The scan point of lowest misfit, when it beats `estimateMisfit` by more than the Δt
/// ensemble's misfit noise (half the spread of its members' misfits): then the optimiser's
/// estimate is not the best fit, and its budget was too small. Nothing otherwise.
std::optional<BetterPoint> betterThanEstimate(const Precision& p, double estimateMisfit);

/// The forward runs of measurePrecision at an estimate (each parameter's scan and the Δt
/// ensemble), as tasks that any number of threads take in turn: a spare thread may start them
/// before the optimiser's last stage has confirmed the estimate, and others join in once it has.
class PrecisionRuns {
 public:
  PrecisionRuns(const io::BackanalysisJob& job, std::vector<double> estimate, const solver::HeldEquilibrium* shared);
  PrecisionRuns(const PrecisionRuns&) = delete;
  PrecisionRuns& operator=(const PrecisionRuns&) = delete;
  /// Runs tasks until none is left to start (several threads at once). A task's error is kept
  /// for summary(), and no task starts after it; a cancellation (`Cancelled`,
  /// core/cancellation.hpp) passes through and leaves the study unfinished.
  void work();
  const std::vector<double>& estimate() const { return estimate_; }
  /// Forward runs its finished tasks made.
  int runsMade() const { return counted_; }
  /// Its forward-run tasks.
  int tasks() const { return static_cast<int>(tasks_.size()); }
  /// Once every task is done: the study, with the optimiser's best misfit and its simulated
  /// values at the estimate as the scan's centre and the ensemble's factor 1. Adds the forward
  /// runs to `runs`; rethrows a task's error.
  Precision summary(double bestMisfit, const std::vector<double>& fitAtEstimate, int& runs);

 private:
  const io::BackanalysisJob& job_;
  std::vector<double> estimate_;
  const solver::HeldEquilibrium* shared_;
  std::vector<std::pair<int, int>> tasks_;     ///< (parameter, scan point) or (−1, ensemble member)
  std::vector<std::vector<ScanPoint>> scan_;   ///< each parameter's scan, without the estimate
  std::vector<EnsembleMember> ensemble_;       ///< without the factor-1 member
  std::atomic<int> next_{0}, finished_{0}, counted_{0};
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  std::exception_ptr error_;
};

/// Scans each parameter around `estimate` and runs the Δt ensemble there (job.precision), in
/// parallel on job.threads. `bestMisfit` and `fitAtEstimate` (simulated values, one per
/// observation) are the optimiser's, reused as the scan's centre and the ensemble's factor 1.
/// Counts forward runs in `runs`.
Precision measurePrecision(const io::BackanalysisJob& job, const std::vector<double>& estimate, double bestMisfit,
                           const std::vector<double>& fitAtEstimate, const solver::HeldEquilibrium* shared,
                           int& runs);

/// The range of values within `threshold` of misfit among scan points (sorted by value): the
/// smallest and largest such value, and whether each is the scan's end.
void rangeWithin(ParameterRange& r, double threshold);

/// Half the spread (max − min)/2 of observation `k` over the ensemble (NaN members skipped).
double ensembleNoise(const std::vector<EnsembleMember>& ensemble, size_t k);

/// |d simulated_k / d value| from a least-squares line through the scan's converged points.
double scanSlope(const std::vector<ScanPoint>& scan, size_t k);

/// The parameter change that matches the numerical noise: noise_k / slope_k, largest over the
/// observations k marked `used` whose trend over the scan (slope × the scan's width) exceeds
/// their noise. An observation that does not trend along this parameter (the factor of safety
/// along the residual friction) says nothing about its resolution; dividing by its slope of
/// round-off gave ±1e12. NaN when no observation trends.
double noiseResolution(const std::vector<ScanPoint>& scan, const std::vector<double>& noise,
                       const std::vector<bool>& used);

}  // namespace ddaslope::calibration
