// The energy budget through impacts (issue #14): no single step may create energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scene_builders.hpp"

using namespace ddaslope;

namespace {

/// Largest rise of the mechanical energy from one step to the next (J/m).
double largestStepGain(const io::Trace& t) {
  double gain = 0;
  for (size_t k = 1; k < t.energy.size(); ++k)
    gain = std::max(gain, t.energy[k].mechanical() - t.energy[k - 1].mechanical());
  return gain;
}

/// A wedge dropped past the corner of a bench into water. Its acute corner P starts 4 cm beyond
/// the line of the bench's vertical face, above the bench top (which rises away from the corner
/// at 30°): outside the bench, but behind the extension of that face. The corner Q of the bench
/// meets the wedge's lower face, and the wedge slides off it onto the floor under 1 m of water.
/// Of the entrances of the corner-to-corner contact, P on the face's extension has the better
/// angle; Q on the wedge's face is the open one.
model::Scene wedgePastACorner(double dt) {
  model::Scene s;
  s.materials.push_back({"rock", 2600, 1e10, 0.25});
  s.joints.push_back(model::JointProperties::coulomb("joint", degToRad(20)));
  const double bench = 2, rise = std::tan(degToRad(30));
  model::Block ground;
  ground.id = "ground";
  ground.fixed = true;
  ground.vertices = {{-10, -2}, {12, -2}, {12, 0}, {0, 0}, {0, bench}, {-10, bench + 10 * rise}};
  const Vec2 p(-0.04, bench + 0.3);
  const double face = degToRad(56);
  model::Block wedge;
  wedge.id = "wedge";
  wedge.vertices = {p, p + 2 * Vec2(std::cos(face), -std::sin(face)), p + Vec2(2, 0)};
  wedge.velocity[1] = -2;
  for (model::Block* b : {&ground, &wedge}) {
    b->moments = geometry::computeMoments(b->vertices);
    s.blocks.push_back(*b);
  }
  const Vec2 c = s.blocks[1].moments.centroid;
  s.monitors.push_back({"wedge", {1, c, c}});
  s.water.line = {{0, 1.0}, {1, 1.0}};
  s.settings.duration = 1.5;
  s.settings.timeStep = dt;
  return s;
}

}  // namespace

// Before the fix the corner-to-corner contact took the entrance with the better angle, P on the
// bench face's extension, and its spring started 4 cm deep (½ p d² = 3.2e8 J/m) in a scene whose
// whole budget is 4-5e4 J/m. At every Δt one step gained 1.5e6-2.5e8 J/m, 1.0-1.2 times the
// energy scale it inflated, and the wedge was shot off at 25-130 m/s. Now no step gains more
// than 2e-5 of the scale, and the wedge never moves faster than its fall allows:
// √(2² + 2 g · 2.5 m) = 7.3 m/s.
TEST(EnergyBudget, WedgeFallingPastACornerIntoWaterGainsNoEnergy) {
  for (double dt : {0.01, 0.005, 0.0025, 0.001}) {
    const io::Trace t = scenes::runTrace(wedgePastACorner(dt));
    ASSERT_GT(t.energy.size(), 2u);
    const double scale = t.energyScale();
    ASSERT_GT(scale, 1e4) << "dt " << dt;  // the wedge falls: 4-5e4 J/m released
    EXPECT_LT(largestStepGain(t), 1e-3 * scale) << "dt " << dt;
    EXPECT_LT(t.largestEnergyGain(), 1e-3 * scale) << "dt " << dt;
    EXPECT_LT(scenes::measureAt(t, "wedge", "speed", std::nullopt), 7.5) << "dt " << dt;
  }
}
