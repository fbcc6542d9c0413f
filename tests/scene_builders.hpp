#pragma once
// Scenes built in code for the verification tests (benchmarks.md §A).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "ddaslope/io/run_case.hpp"
#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/model/incline_scene.hpp"

namespace ddaslope::scenes {

using InclineSpec = model::InclineSpec;
inline model::Scene makeIncline(const InclineSpec& s) { return model::makeInclineScene(s); }
inline double slidingAcceleration(const InclineSpec& s) { return model::slidingAcceleration(s); }

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

/// Hoek & Bray planar failure (benchmarks.md §C): a slope with a 60° face and a horizontal crest
/// 20 m above the point (0, 0) where a sliding plane of dip ψ daylights on the face; the face
/// continues 5 m below it to the ground, so the wedge slides out into the air. A dry vertical
/// tension crack at x = 20 m is left open by 5 cm so that it carries nothing (as Hoek & Bray
/// assume).
struct Planar {
  model::Scene scene;
  double crackDepthToPlane = 0;  ///< depth of the tension crack from the crest to the plane (m)
  double weight = 0;   ///< W (N/m)
  double length = 0;   ///< A, length of the sliding plane (m)
  double psi = 0;      ///< rad
  double factor(double c, double phi) const {
    return (c * length + weight * std::cos(psi) * std::tan(phi)) / (weight * std::sin(psi));
  }
};

inline Planar planar(double psiDeg, double c, double phiDeg) {
  const double h = 20, xc = 20, gap = 0.05, psi = psiDeg * M_PI / 180, t = std::tan(psi);
  model::Scene s;
  s.materials.push_back({"rock", 2600, 10e9, 0.25});
  s.joints.push_back(model::JointProperties::coulomb("plane", phiDeg * M_PI / 180, c));
  model::Block base, block;
  base.id = "rock mass";
  base.fixed = true;
  const double cot60 = 1 / std::tan(60 * M_PI / 180);
  base.vertices = {{-10, -10}, {xc + 20, -10}, {xc + 20, h},     {xc + gap, h},
                   {xc + gap, (xc + gap) * t}, {0, 0}, {-5 * cot60, -5}, {-10, -5}};
  block.id = "wedge";
  block.vertices = {{0, 0}, {xc, xc * t}, {xc, h}, {h * cot60, h}};
  for (model::Block* b : {&base, &block}) b->moments = geometry::computeMoments(b->vertices);
  s.blocks = {base, block};
  const Vec2 c0 = block.moments.centroid;
  s.monitors.push_back({"wedge", {1, c0, c0}});
  s.settings.duration = 1.0;
  s.settings.timeStep = 1e-3;
  return {s, h - xc * t, 2600 * 9.81 * block.moments.area, xc / std::cos(psi), psi};
}

}  // namespace ddaslope::scenes
