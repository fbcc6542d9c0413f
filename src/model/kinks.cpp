#include "ddaslope/model/kinks.hpp"

#include <cmath>

namespace ddaslope::model {

namespace {
constexpr double kLeastBendDeg = 0.5;  // below this a polyline's vertex is a survey point, not a kink
constexpr double kMostBendDeg = 60;    // beyond it a step (stairs of a toppling base) with its own physics
}  // namespace

std::vector<ConcaveKink> concaveKinksUnderBlocks(const Scene& scene) {
  std::vector<ConcaveKink> kinks;
  const double tolerance = 1e-6 * scene.modelHalfSize();  // vertices typed to a millimetre on a kilometre slope
  for (size_t f = 0; f < scene.blocks.size(); ++f) {
    const Block& fixed = scene.blocks[f];
    if (!fixed.fixed) continue;
    const std::vector<Vec2>& v = fixed.vertices;
    const size_t n = v.size();
    for (size_t i = 0; i < n; ++i) {
      const Vec2 in = v[i] - v[(i + n - 1) % n], out = v[(i + 1) % n] - v[i];
      // Counter-clockwise polygon: a right turn (negative cross product) is a reflex vertex.
      const double turnDeg = radToDeg(std::atan2(cross(in, out), in.dot(out)));
      const double bend = -turnDeg;
      if (bend < kLeastBendDeg || bend > kMostBendDeg) continue;
      bool touched = false;
      for (const Block& b : scene.blocks) {
        if (b.fixed) continue;
        for (const Vec2& p : b.vertices) touched = touched || (p - v[i]).norm() <= tolerance;
      }
      if (touched) kinks.push_back({static_cast<int>(f), v[i], bend});
    }
  }
  return kinks;
}

}  // namespace ddaslope::model
