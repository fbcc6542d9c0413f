#include "ddaslope/calibration/precision.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <sstream>
#include <utility>

#include "ddaslope/calibration/backanalysis.hpp"
#include "ddaslope/core/cancellation.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/task_farm.hpp"

namespace ddaslope::calibration {

namespace {

std::vector<double> simulatedValues(const std::vector<ObservationFit>& fit) {
  std::vector<double> out;
  for (const auto& f : fit) out.push_back(f.converged ? f.simulated : NAN);
  return out;
}

std::string formatted(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

}  // namespace

void rangeWithin(ParameterRange& r, double threshold) {
  bool any = false;
  for (size_t k = 0; k < r.scan.size(); ++k) {
    if (!(r.scan[k].misfit <= threshold)) continue;
    if (!any) r.low = r.scan[k].value, r.openLow = k == 0;
    r.high = r.scan[k].value;
    r.openHigh = k + 1 == r.scan.size();
    any = true;
  }
  if (!any) r.low = r.high = r.estimate;
}

double ensembleNoise(const std::vector<EnsembleMember>& ensemble, size_t k) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& m : ensemble)
    if (k < m.simulated.size() && std::isfinite(m.simulated[k])) lo = std::min(lo, m.simulated[k]), hi = std::max(hi, m.simulated[k]);
  return hi >= lo ? (hi - lo) / 2 : NAN;
}

double scanSlope(const std::vector<ScanPoint>& scan, size_t k) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& p : scan) {
    if (k >= p.simulated.size() || !std::isfinite(p.simulated[k])) continue;
    n += 1, sx += p.value, sy += p.simulated[k], sxx += p.value * p.value, sxy += p.value * p.simulated[k];
  }
  const double d = n * sxx - sx * sx;
  return n >= 2 && d > 0 ? std::abs((n * sxy - sx * sy) / d) : 0.0;
}

double noiseResolution(const std::vector<ScanPoint>& scan, const std::vector<double>& noise,
                       const std::vector<bool>& used) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : scan) lo = std::min(lo, p.value), hi = std::max(hi, p.value);
  double resolution = NAN;
  for (size_t k = 0; k < noise.size(); ++k) {
    if (!used[k] || !std::isfinite(noise[k])) continue;
    const double slope = scanSlope(scan, k);
    if (!(slope * (hi - lo) > noise[k])) continue;  // no trend above the noise along this parameter
    const double r = noise[k] / slope;
    resolution = std::isfinite(resolution) ? std::max(resolution, r) : r;
  }
  return resolution;
}

PrecisionRuns::PrecisionRuns(const io::BackanalysisJob& job, std::vector<double> estimate,
                             const solver::HeldEquilibrium* shared)
    : job_(job), estimate_(std::move(estimate)), shared_(shared) {
  const io::PrecisionSpec& spec = job.precision;
  // The scan: each parameter over estimate ± halfWidth of its range, the others held; and the
  // Δt ensemble at the estimate. All their runs are tasks of one pool, so that the threads
  // finish together once, not once per parameter and again after the ensemble.
  scan_.resize(job.parameters.size());
  for (size_t i = 0; i < job.parameters.size(); ++i) {
    const io::ParameterSpec& p = job.parameters[i];
    const double half = spec.halfWidth * (p.max - p.min);
    for (int k = 0; k < spec.scanPoints; ++k) {
      const double v = estimate_[i] - half + 2 * half * k / (spec.scanPoints - 1);
      if (v >= p.min && v <= p.max && std::abs(v - estimate_[i]) > 1e-9 * (p.max - p.min)) {
        tasks_.emplace_back(static_cast<int>(i), static_cast<int>(scan_[i].size()));
        scan_[i].push_back({v, 0, {}});
      }
    }
  }
  for (const double factor : spec.timeStepFactors) {
    tasks_.emplace_back(-1, static_cast<int>(ensemble_.size()));
    ensemble_.push_back({factor, 0, {}});
  }
}

void PrecisionRuns::work() {
  for (;;) {
    if (failed_) return;  // a study that cannot be completed starts no more runs
    const int t = next_++;
    if (t >= static_cast<int>(tasks_.size())) return;
    const auto [i, k] = tasks_[static_cast<size_t>(t)];
    int n = 0;
    std::vector<ObservationFit> fit;
    try {
      if (i >= 0) {
        ScanPoint& point = scan_[static_cast<size_t>(i)][static_cast<size_t>(k)];
        std::vector<double> x = estimate_;
        x[static_cast<size_t>(i)] = point.value;
        point.misfit = misfitAt(job_, x, &n, shared_, 1, &fit);
        point.simulated = simulatedValues(fit);
      } else {
        EnsembleMember& member = ensemble_[static_cast<size_t>(k)];
        model::Scene scene = sceneAt(job_, estimate_);
        scene.settings.timeStep *= member.timeStepFactor;
        member.misfit = misfitOf(job_, scene, &n, shared_, 1, &fit);
        member.simulated = simulatedValues(fit);
      }
    } catch (const Cancelled&) {
      throw;
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
      failed_ = true;
    }
    counted_ += n;
    ++finished_;
  }
}

Precision measurePrecision(const io::BackanalysisJob& job, const std::vector<double>& estimate, double bestMisfit,
                           const std::vector<double>& fitAtEstimate, const solver::HeldEquilibrium* shared,
                           int& runs) {
  PrecisionRuns study(job, estimate, shared);
  const int threads = std::max(1, std::min(job.threads, study.tasks()));
  runOnThreads(threads, threads, [&](int) { study.work(); });
  return study.summary(bestMisfit, fitAtEstimate, runs);
}

Precision PrecisionRuns::summary(double bestMisfit, const std::vector<double>& fitAtEstimate, int& runs) {
  if (error_) std::rethrow_exception(error_);
  DDASLOPE_ASSERT(finished_ == static_cast<int>(tasks_.size()), "the precision study's runs are not all done");
  const io::BackanalysisJob& job = job_;
  Precision out;
  for (size_t i = 0; i < job.parameters.size(); ++i) {
    ParameterRange range;
    range.name = job.parameters[i].name;
    range.estimate = estimate_[i];
    range.scan = scan_[i];
    range.scan.push_back({estimate_[i], bestMisfit, fitAtEstimate});
    std::sort(range.scan.begin(), range.scan.end(), [](const auto& a, const auto& b) { return a.value < b.value; });
    out.parameters.push_back(std::move(range));
  }
  out.ensemble.push_back({1.0, bestMisfit, fitAtEstimate});
  out.ensemble.insert(out.ensemble.end(), ensemble_.begin(), ensemble_.end());
  runs += counted_;

  // The range within one standard deviation (misfit + Σ weights) of the best point seen, and the
  // resolution the noise allows along each parameter.
  double weights = 0, best = bestMisfit;
  for (const auto& o : job.observations) weights += o.weight;
  for (const auto& r : out.parameters)
    for (const auto& p : r.scan) best = std::min(best, p.misfit);
  for (size_t k = 0; k < job.observations.size(); ++k) out.noise.push_back(ensembleNoise(out.ensemble, k));
  std::ostringstream s;
  s << "Precision, measured around the estimate:";
  std::vector<bool> scalar;  // a series' simulated value is its misfit, not an observable
  for (const auto& o : job.observations) scalar.push_back(o.kind != io::ObservationSpec::Kind::Series);
  for (auto& r : out.parameters) {
    rangeWithin(r, best + weights);
    r.noiseResolution = noiseResolution(r.scan, out.noise, scalar);
    s << " " << r.name << " = " << formatted(r.estimate) << ", within one standard deviation of the best fit ";
    if (r.low == r.high && !r.openLow && !r.openHigh) {
      // Only the estimate itself lies within: the range ends somewhere before the nearest values
      // scanned on either side, which is all the scan can say.
      double below = -INFINITY, above = INFINITY;
      for (const auto& p : r.scan) {
        if (p.value < r.low) below = std::max(below, p.value);
        if (p.value > r.high) above = std::min(above, p.value);
      }
      s << "over less than the scan resolves: inside " << formatted(below) << " to " << formatted(above)
        << ", the nearest values scanned (" << r.scan.size()
        << " values; raise precision.scan_points or lower precision.half_width to resolve it)";
    } else {
      s << "for " << (r.openLow ? "≤ " : "") << formatted(r.low) << " to " << (r.openHigh ? "≥ " : "")
        << formatted(r.high) << " (" << r.scan.size() << " values scanned; an end marked ≤/≥ is the scan's)";
    }
    s << "; numerical noise alone "
      << (std::isfinite(r.noiseResolution) ? "±" + formatted(r.noiseResolution)
                                           : std::string("unresolved (the observables show no trend over the scan)"))
      << ".";
  }
  s << " Δt ×";
  for (size_t k = 1; k < out.ensemble.size(); ++k) s << (k > 1 ? "/" : "") << formatted(out.ensemble[k].timeStepFactor);
  s << " moves";
  for (size_t k = 0; k < job.observations.size(); ++k)
    s << (k ? "," : "") << " " << job.observations[k].label << " by ±" << formatted(out.noise[k]);
  s << ". State the parameter as its range, not the point.";
  out.better = betterThanEstimate(out, bestMisfit);
  if (out.better)
    s << " The search stopped short: the scan's misfit " << formatted(out.better->misfit) << " at "
      << out.parameters[out.better->parameter].name << " = " << formatted(out.better->value)
      << " beats the estimate's " << formatted(bestMisfit) << " by more than the Δt ensemble's misfit noise (±"
      << formatted(out.better->misfitNoise)
      << "): raise the optimiser's evaluations, or give that point as the parameters' start.";
  out.statement = s.str();
  return out;
}

std::optional<BetterPoint> betterThanEstimate(const Precision& p, double estimateMisfit) {
  double lo = estimateMisfit, hi = estimateMisfit;
  for (const EnsembleMember& m : p.ensemble)
    if (std::isfinite(m.misfit)) lo = std::min(lo, m.misfit), hi = std::max(hi, m.misfit);
  const double noise = (hi - lo) / 2;
  std::optional<BetterPoint> best;
  for (size_t i = 0; i < p.parameters.size(); ++i)
    for (const ScanPoint& s : p.parameters[i].scan)
      if (std::isfinite(s.misfit) && s.misfit < estimateMisfit - noise && (!best || s.misfit < best->misfit))
        best = BetterPoint{i, s.value, s.misfit, estimateMisfit, noise};
  return best;
}

}  // namespace ddaslope::calibration
