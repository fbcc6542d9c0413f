#include <algorithm>
#include <cmath>
#include <sstream>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/run_case.hpp"

namespace ddaslope::io {

int Trace::monitorIndex(const std::string& id) const {
  for (size_t i = 0; i < monitorIds.size(); ++i)
    if (monitorIds[i] == id) return static_cast<int>(i);
  return -1;
}

double Trace::largestEnergyGain() const {
  double gain = 0;
  for (const solver::EnergyBudget& e : energy) gain = std::max(gain, e.mechanical() - energy.front().mechanical());
  return gain;
}

double Trace::energyScale() const {
  double scale = 0;
  for (const solver::EnergyBudget& e : energy)
    scale = std::max({scale, e.kinetic, energy.front().potential - e.potential});
  return scale;
}

double Trace::largestStepGain(double* time) const {
  double gain = 0;
  for (size_t k = 1; k < energy.size(); ++k) {
    const double g = energy[k].mechanical() - energy[k - 1].mechanical();
    if (g > gain) {
      gain = g;
      if (time && k - 1 < steps.size()) *time = steps[k - 1].time;
    }
  }
  return gain;
}

double Trace::energyInPlay() const {
  double stored = 0;
  for (const solver::EnergyBudget& e : energy) stored = std::max(stored, e.elastic);
  return std::max(energyScale(), stored);
}

static double quantityOf(const MonitorSample& s, const std::string& q) {
  if (q == "ux") return s.ux;
  if (q == "uy") return s.uy;
  if (q == "vx") return s.vx;
  if (q == "vy") return s.vy;
  if (q == "displacement") return std::hypot(s.ux, s.uy);
  if (q == "speed") return std::hypot(s.vx, s.vy);
  throw InternalError(__FILE__, __LINE__, "unknown quantity " + q);
}

double measure(const Trace& trace, const model::Expectation& e) {
  const int m = trace.monitorIndex(e.monitor);
  DDASLOPE_ASSERT(m >= 0 && !trace.steps.empty(), "expectation on a missing monitor or empty trace");
  if (!e.time) {
    double best = -INFINITY;
    for (const auto& row : trace.samples) best = std::max(best, quantityOf(row[m], e.quantity));
    return best;
  }
  const double t = *e.time;
  for (size_t k = 1; k < trace.steps.size(); ++k) {
    const double t0 = trace.steps[k - 1].time, t1 = trace.steps[k].time;
    if (t1 < t) continue;
    const double w = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;
    return (1 - w) * quantityOf(trace.samples[k - 1][m], e.quantity) + w * quantityOf(trace.samples[k][m], e.quantity);
  }
  return quantityOf(trace.samples.back()[m], e.quantity);
}

std::vector<ExpectationResult> evaluateExpectations(const Trace& trace,
                                                    const std::vector<model::Expectation>& ex) {
  std::vector<ExpectationResult> out;
  for (const model::Expectation& e : ex) {
    ExpectationResult r{e, 0, true};
    r.runEnd = trace.steps.empty() ? 0 : trace.steps.back().time;
    // A time the run did not reach (a shortened --duration) has no value: not checked.
    if (e.time && *e.time > r.runEnd * (1 + 1e-9) + 1e-12) {
      r.reached = false;
      r.passed = false;
      out.push_back(r);
      continue;
    }
    r.actual = measure(trace, e);
    if (e.value)
      r.passed &= std::abs(r.actual - *e.value) <= std::max(e.relativeTolerance * std::abs(*e.value), e.absoluteTolerance);
    if (e.atMost) r.passed &= r.actual <= *e.atMost;
    if (e.atLeast) r.passed &= r.actual >= *e.atLeast;
    out.push_back(r);
  }
  return out;
}

std::string ExpectationResult::describe() const {
  const model::Expectation& e = expectation;
  std::ostringstream s;
  s.precision(6);
  if (!reached) {
    s << "not checked: " << e.monitor << " " << e.quantity << " at t = " << *e.time << " s lies past the run's end (t = "
      << runEnd << " s)";
    return s.str();
  }
  s << (passed ? "pass" : "FAIL") << ": " << e.monitor << " " << e.quantity;
  s << (e.time ? " at t = " + std::to_string(*e.time) + " s" : std::string(" (max over run)"));
  s << " = " << actual;
  if (e.value) s << " (expected " << *e.value << " ± " << std::max(e.relativeTolerance * std::abs(*e.value), e.absoluteTolerance) << ")";
  if (e.atMost) s << " (expected ≤ " << *e.atMost << ")";
  if (e.atLeast) s << " (expected ≥ " << *e.atLeast << ")";
  if (!e.source.empty()) s << " [" << e.source << "]";
  return s.str();
}

}  // namespace ddaslope::io
