#include "ddaslope/assembly/water_terms.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ddaslope::assembly {
namespace {

/// Calls f(point, pressure·length weight) at 2-point Gauss points of every sub-segment of a → b
/// on which the pressure is linear and positive.
template <class F>
void integrateEdge(const Vec2& a, const Vec2& b, const model::WaterTable& w, F&& f) {
  if (w.grid) {
    // A grid's spline is smooth: 2-point Gauss on pieces a quarter of its points' spacing long.
    const double length = (b - a).norm();
    const int pieces = std::clamp(static_cast<int>(std::ceil(4 * length / w.grid->spacing())), 2, 64);
    const double g = 1 / std::sqrt(3.0), half = 0.5 / pieces;
    for (int k = 0; k < pieces; ++k)
      for (double s : {-g, g}) {
        const Vec2 p = a + ((k + 0.5) / pieces + s * half) * (b - a);
        f(p, w.grid->at(p) * half * length);
      }
    return;
  }
  // Breakpoints: where the edge passes a vertex of the phreatic line (its slope changes there).
  std::vector<double> ts{0.0, 1.0};
  if (b.x() != a.x())
    for (const Vec2& v : w.line) {
      const double t = (v.x() - a.x()) / (b.x() - a.x());
      if (t > 0 && t < 1) ts.push_back(t);
    }
  std::sort(ts.begin(), ts.end());
  const double length = (b - a).norm();
  const auto head = [&](double t) { return w.headAt(a.x() + t * (b.x() - a.x())) - (a.y() + t * (b.y() - a.y())); };
  const double g = 1 / std::sqrt(3.0);
  for (size_t k = 0; k + 1 < ts.size(); ++k) {
    double t0 = ts[k], t1 = ts[k + 1];
    const double h0 = head(t0), h1 = head(t1);
    if (h0 <= 0 && h1 <= 0) continue;
    // Clip to the submerged part (the head is linear on the sub-segment).
    if (h0 < 0) t0 = t0 + (t1 - t0) * (-h0) / (h1 - h0);
    if (h1 < 0) t1 = t0 + (t1 - t0) * h0 / (h0 - h1);
    const double half = 0.5 * (t1 - t0);
    for (double s : {-g, g}) {
      const double t = 0.5 * (t0 + t1) + s * half;
      const Vec2 p = a + t * (b - a);
      f(p, w.unitWeight * std::max(0.0, head(t)) * half * length);
    }
  }
}

}  // namespace

Vec2 edgeWaterResultant(const Vec2& a, const Vec2& b, const model::WaterTable& water) {
  const Vec2 d = (b - a).normalized();
  const Vec2 inward(-d.y(), d.x());
  Vec2 r(0, 0);
  integrateEdge(a, b, water, [&](const Vec2&, double weight) { r += weight * inward; });
  return r;
}

Vec6 waterForce(const model::Block& block, const model::WaterTable& water) {
  Vec6 f = Vec6::Zero();
  const auto& v = block.vertices;
  for (size_t e = 0; e < v.size(); ++e) {
    const Vec2 &a = v[e], &b = v[(e + 1) % v.size()];
    const Vec2 d = (b - a).normalized();
    const Vec2 inward(-d.y(), d.x());
    integrateEdge(a, b, water, [&](const Vec2& p, double weight) { f += block.tAt(p).transpose() * (weight * inward); });
  }
  return f;
}

}  // namespace ddaslope::assembly
