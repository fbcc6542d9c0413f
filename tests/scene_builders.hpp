#pragma once
// Scenes built in code for the verification tests (benchmarks.md §A).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "ddaslope/io/run_case.hpp"
#include "ddaslope/model/scene.hpp"

namespace ddaslope::scenes {

struct InclineSpec {
  double alphaDeg = 30;   ///< slope angle
  double b = 2;           ///< block length along the slope (m)
  double h = 1;           ///< block height (m)
  double phiDeg = 20;     ///< joint friction angle
  double cohesion = 0;    ///< Pa
  double density = 2600;  ///< kg/m³
  double g = 9.81;
  double young = 5e9;
  double duration = 1.0;
  double timeStep = 1e-3;
};

/// A fixed ramp whose top is the slope line through the origin and a b×h block on it, its
/// downslope corner 10 m up the slope. Monitors: "centre", "toe" (downslope corner), "top"
/// (upslope top corner).
inline model::Scene makeIncline(const InclineSpec& s) {
  model::Scene sc;
  const double a = s.alphaDeg * M_PI / 180;
  const Vec2 u(std::cos(a), std::sin(a)), n(-std::sin(a), std::cos(a));
  const double len = 10 + s.b + 10, s0 = 10;
  sc.gravity = {0, -s.g};
  sc.materials.push_back({"rock", s.density, s.young, 0.25});
  sc.joints.push_back({"interface", s.phiDeg * M_PI / 180, s.cohesion, 0});
  model::Block ramp;
  ramp.id = "ramp";
  ramp.fixed = true;
  ramp.vertices = {{0, -2}, {len * u.x(), -2}, len * u, {0, 0}};
  model::Block blk;
  blk.id = "block";
  const auto p = [&](double along, double up) -> Vec2 { return along * u + up * n; };
  blk.vertices = {p(s0, 0), p(s0 + s.b, 0), p(s0 + s.b, s.h), p(s0, s.h)};
  for (model::Block* bl : {&ramp, &blk}) bl->moments = geometry::computeMoments(bl->vertices);
  sc.blocks = {ramp, blk};
  const auto monitor = [&](const std::string& id, Vec2 at) { sc.monitors.push_back({id, {1, at, at}}); };
  monitor("centre", p(s0 + s.b / 2, s.h / 2));
  monitor("toe", p(s0, 0));
  monitor("top", p(s0 + s.b, s.h));
  sc.settings.duration = s.duration;
  sc.settings.timeStep = s.timeStep;
  return sc;
}

/// Closed-form sliding acceleration g (sin α − cos α tan φ) (benchmarks.md A2).
inline double slidingAcceleration(const InclineSpec& s) {
  const double a = s.alphaDeg * M_PI / 180, phi = s.phiDeg * M_PI / 180;
  return s.g * (std::sin(a) - std::cos(a) * std::tan(phi));
}

/// Runs a scene without output files; the test fails if the run does not complete.
inline io::Trace runTrace(const model::Scene& s) {
  const io::RunOutcome o = io::runScene(s, {});
  EXPECT_TRUE(o.completed) << o.failure;
  return o.trace;
}

/// A monitor quantity at a time (interpolated) or, without a time, its maximum over the run.
inline double measureAt(const io::Trace& t, const std::string& monitor, const std::string& quantity,
                        std::optional<double> time) {
  model::Expectation e;
  e.monitor = monitor;
  e.quantity = quantity;
  e.time = time;
  return io::measure(t, e);
}

}  // namespace ddaslope::scenes
