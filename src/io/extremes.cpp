#include "ddaslope/io/extremes.hpp"

#include <chrono>
#include <cmath>
#include <optional>

#include "ddaslope/io/run_case.hpp"

namespace ddaslope::io {

namespace {

ExtremeIncline make(const std::string& name, double scale, double aspect, double young, double density, double phi,
                    double cohesion, double timeStep, double duration, bool slides) {
  model::InclineSpec s;
  s.b *= scale;
  s.h = s.b * aspect;
  s.young = young;
  s.density = density;
  s.phiDeg = phi;
  s.cohesion = cohesion;
  s.timeStep = timeStep;
  s.duration = duration;
  return {name, s, slides};
}

}  // namespace

std::vector<ExtremeIncline> extremeInclines() {
  // name, length scale, h/b, E (Pa), ρ, φ (°), c (Pa), Δt (s), duration (s), slides
  return {
      make("millimetre_block", 1e-3, 0.5, 5e9, 2600, 20, 0, 1e-3, 0.5, true),
      make("kilometre_block", 1e3, 0.5, 5e9, 2600, 20, 0, 1e-2, 5, true),
      make("sliver_1e-3", 1, 1e-3, 5e9, 2600, 20, 0, 1e-3, 0.5, true),
      make("soft_E_1MPa", 1, 0.5, 1e6, 2600, 20, 0, 1e-3, 0.5, true),
      make("stiff_E_1TPa", 1, 0.5, 1e12, 2600, 20, 0, 1e-3, 0.5, true),
      make("light_1000", 1, 0.5, 5e9, 1000, 20, 0, 1e-3, 0.5, true),
      make("heavy_5000", 1, 0.5, 5e9, 5000, 20, 0, 1e-3, 0.5, true),
      make("frictionless_phi_0", 1, 0.5, 5e9, 2600, 0, 0, 1e-3, 0.5, true),
      make("phi_85_holds", 1, 0.5, 5e9, 2600, 85, 0, 1e-3, 0.5, false),
      make("cohesion_1e8_holds", 1, 0.5, 5e9, 2600, 20, 1e8, 1e-3, 0.5, false),
      make("dt_1e-6", 1, 0.5, 5e9, 2600, 20, 0, 1e-6, 2e-3, true),
      make("dt_0.1", 1, 0.5, 5e9, 2600, 20, 0, 0.1, 2, true),
  };
}

double ExtremeResult::slideError() const {
  return closedFormSlide > 0 ? std::abs(slide - closedFormSlide) / closedFormSlide : slide;
}

ExtremeResult runExtreme(const ExtremeIncline& x) {
  const model::InclineSpec& s = x.spec;
  const model::Scene scene = model::makeInclineScene(s);
  const auto start = std::chrono::steady_clock::now();
  const RunOutcome o = runScene(scene, {});
  ExtremeResult r;
  r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.completed = o.completed;
  r.failure = o.failure;
  if (!o.completed || o.trace.samples.empty()) return r;
  r.finite = true;
  for (const auto& row : o.trace.samples)
    for (const auto& m : row)
      r.finite = r.finite && std::isfinite(m.ux) && std::isfinite(m.uy) && std::isfinite(m.vx) && std::isfinite(m.vy);
  const double a = std::max(0.0, model::slidingAcceleration(s));
  const auto centre = [&](const char* quantity, std::optional<double> time) {
    model::Expectation e;
    e.monitor = "centre";
    e.quantity = quantity;
    e.time = time;
    return measure(o.trace, e);
  };
  // Travel from t = 0, after the equilibrium: the elastic settling of a soft block is not sliding.
  const MonitorSample& first = o.trace.samples.front()[o.trace.monitorIndex("centre")];
  r.slide = std::hypot(centre("ux", s.duration) - first.ux, centre("uy", s.duration) - first.uy);
  r.peakSpeed = centre("speed", std::nullopt);
  r.closedFormPeakSpeed = a * s.duration;
  const double alpha = s.alphaDeg * M_PI / 180;
  const double weight = s.density * s.g * s.b * s.h;
  const double elongation = weight * std::sin(alpha) / (scene.settings.shearPenaltyRatio * scene.normalPenalty());
  if (x.slides) {
    r.closedFormSlide = a * s.duration * s.duration / 2;
    r.slideTolerance = 0.01 * r.closedFormSlide + elongation;
  } else {
    r.slide /= s.b;
    r.slideTolerance = 1e-3;
  }
  r.energyGain = o.trace.largestEnergyGain();
  r.heldPotential = std::abs(o.trace.energy.front().potential);
  r.energyLost = o.trace.energy.front().mechanical() - o.trace.energy.back().mechanical();
  r.frictionWork = x.slides ? std::tan(s.phiDeg * M_PI / 180) * weight * std::cos(alpha) * r.slide : 0;
  r.elasticRelease = weight * std::sin(alpha) * elongation;
  return r;
}

}  // namespace ddaslope::io
