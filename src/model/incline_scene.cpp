#include "ddaslope/model/incline_scene.hpp"

#include <algorithm>
#include <cmath>

namespace ddaslope::model {

Scene makeInclineScene(const InclineSpec& s) {
  Scene sc;
  const double a = degToRad(s.alphaDeg);
  const Vec2 u(std::cos(a), std::sin(a)), n(-std::sin(a), std::cos(a));
  const double len = 10 + s.b + 10, s0 = 10;
  sc.description = "block on an incline";
  sc.gravity = {0, -s.g};
  sc.materials.push_back({"rock", s.density, s.young, 0.25});
  sc.joints.push_back(model::JointProperties::coulomb("interface", degToRad(s.phiDeg), s.cohesion));
  Block ramp;
  ramp.id = "ramp";
  ramp.fixed = true;
  ramp.vertices = {{0, -2}, {len * u.x(), -2}, len * u, {0, 0}};
  Block blk;
  blk.id = "block";
  const auto p = [&](double along, double up) -> Vec2 { return along * u + up * n; };
  blk.vertices = {p(s0, 0), p(s0 + s.b, 0), p(s0 + s.b, s.h), p(s0, s.h)};
  for (Block* bl : {&ramp, &blk}) bl->moments = geometry::computeMoments(bl->vertices);
  sc.blocks = {ramp, blk};
  const auto monitor = [&](const std::string& id, Vec2 at) { sc.monitors.push_back({id, {1, at, at}}); };
  monitor("centre", p(s0 + s.b / 2, s.h / 2));
  monitor("toe", p(s0, 0));
  monitor("top", p(s0 + s.b, s.h));
  sc.settings.duration = s.duration;
  sc.settings.timeStep = s.timeStep;
  return sc;
}

double slidingAcceleration(const InclineSpec& s) {
  const double a = degToRad(s.alphaDeg), phi = degToRad(s.phiDeg);
  return s.g * (std::sin(a) - std::cos(a) * std::tan(phi));
}

double criticalCohesion(const InclineSpec& s) {
  const double w = s.density * s.g * s.b * s.h;
  return std::max(0.0, w * slidingAcceleration(s) / s.g / s.b);
}

}  // namespace ddaslope::model
