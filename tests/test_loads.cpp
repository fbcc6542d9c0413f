// Point loads, fixed points, per-pair joints and static mode against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "ddaslope/io/run_case.hpp"
#include "scene_builders.hpp"

using namespace ddaslope;
using scenes::InclineSpec;

namespace {
using scenes::measureAt;
const auto run = scenes::runTrace;
/// The A4 incline with its block lifted clear of the ramp and no gravity: a free block.
model::Scene freeBlock() {
  model::Scene s = scenes::makeIncline(InclineSpec{});
  for (Vec2& v : s.blocks[1].vertices) v.y() += 20;
  s.blocks[1].moments = geometry::computeMoments(s.blocks[1].vertices);
  for (auto& m : s.monitors) m.point.initial = m.point.current = m.point.initial + Vec2(0, 20);
  s.gravity = {0, 0};
  return s;
}
}  // namespace

// A constant point force through the centroid of a free block: u = F t²/(2m), integrated exactly
// by Newmark β = 1/2, γ = 1 (round-off only).
TEST(Loads, PointForceThroughCentroidAcceleratesAtFOverM) {
  model::Scene s = freeBlock();
  const double mass = 2600 * 2.0;  // A4 block 2 × 1 m
  const Vec2 f(1000, -500);
  s.pointLoads.push_back({s.monitors[0].point, f});
  const io::Trace t = run(s);
  EXPECT_NEAR(measureAt(t, "centre", "ux", 1.0), f.x() / (2 * mass), 1e-9 * f.x() / (2 * mass));
  EXPECT_NEAR(measureAt(t, "centre", "uy", 1.0), f.y() / (2 * mass), 1e-9 * std::abs(f.y()) / (2 * mass));
}

// A free block hanging on a fixed point at its centroid under gravity: static stretch of the
// point's penalty spring u = m g / p (static mode reaches it; Hooke's law).
TEST(Loads, FixedPointHoldsWithPenaltyStretch) {
  model::Scene s = freeBlock();
  s.gravity = {0, -9.81};
  s.fixedPoints.push_back({s.monitors[0].point});
  s.settings.mode = model::AnalysisMode::Static;
  s.settings.duration = 0.05;
  const io::Trace t = run(s);
  const double stretch = 2600 * 2.0 * 9.81 / s.normalPenalty();
  EXPECT_NEAR(measureAt(t, "centre", "uy", 0.05), -stretch, 1e-6 * stretch);
}

// joint_pairs overrides the default joint for one pair: φ = 40° on a 30° slope holds, while the
// default φ = 20° slides at g (sin α − cos α tan φ) (benchmarks.md A4).
TEST(Loads, PairJointOverridesDefault) {
  InclineSpec spec;
  model::Scene s = scenes::makeIncline(spec);
  const double slide = scenes::slidingAcceleration(spec) / 2;
  EXPECT_NEAR(measureAt(run(s), "centre", "displacement", 1.0), slide, 0.005 * slide);
  s.joints.push_back(model::JointProperties::coulomb("rough", 40 * M_PI / 180, 0));
  s.pairJoints[{0, 1}] = 1;
  EXPECT_LT(measureAt(run(s), "centre", "displacement", std::nullopt), 1e-3 * spec.b);
}

// Static mode (velocities reset each step) on a stable slope ends at rest, with the same
// elastic settling as the dynamic run.
TEST(Loads, StaticModeStableBlockStaysPut) {
  InclineSpec spec{40, 10, 10, 40.1, 0, 2000, 10};
  model::Scene s = scenes::makeIncline(spec);
  s.settings.mode = model::AnalysisMode::Static;
  EXPECT_LT(measureAt(run(s), "centre", "displacement", std::nullopt), 1e-3 * spec.b);
}

// A point force growing linearly, F = r t, through the centroid of a free block: x = r t³/(6m).
// The load is taken at the end of each step (implicit), a first-order error in Δt: 0.3 % at
// Δt = 1 ms over 1 s (the tolerance), shrinking tenfold at Δt = 0.1 ms.
TEST(Loads, RampedForceFollowsTheCubicLaw) {
  model::Scene s = freeBlock();
  const double mass = 2600 * 2.0, rate = 3000;
  s.pointLoads.push_back({s.monitors[0].point, {0, 0}, {rate, 0}});
  const double expected = rate / (6 * mass);
  double previousError = 0;
  for (double dt : {1e-3, 1e-4}) {
    s.settings.timeStep = dt;
    const double x = measureAt(run(s), "centre", "ux", 1.0);
    const double error = std::abs(x - expected) / expected;
    EXPECT_LT(error, 3e-3) << "dt " << dt;
    if (previousError > 0) {
      EXPECT_LT(error, 0.2 * previousError);  // first order: ~10× smaller
    }
    previousError = error;
  }
}
