#include "ddaslope/model/kinks.hpp"

#include <algorithm>
#include <cmath>

namespace ddaslope::model {

namespace {
constexpr double kLeastBendDeg = 0.5;  // below this a polyline's vertex is a survey point, not a kink
constexpr double kMostBendDeg = 60;    // beyond it a step (stairs of a toppling base) with its own physics

/// Signed turn (degrees) from direction `in` to direction `out`, left (counter-clockwise) > 0.
double turnDeg(const Vec2& in, const Vec2& out) { return radToDeg(std::atan2(cross(in, out), in.dot(out))); }

bool isKink(double bendDeg) { return bendDeg >= kLeastBendDeg && bendDeg <= kMostBendDeg; }
}  // namespace

std::vector<Vec2> concaveKinks(const std::vector<Vec2>& s) {
  std::vector<Vec2> kinks;
  // Going down the slope (x increasing) a turn to the left flattens the surface: a valley.
  for (size_t i = 1; i + 1 < s.size(); ++i)
    if (isKink(turnDeg(s[i] - s[i - 1], s[i + 1] - s[i]))) kinks.push_back(s[i]);
  return kinks;
}

std::vector<ConcaveKink> concaveKinksUnderBlocks(const Scene& scene) {
  std::vector<ConcaveKink> kinks;
  const double tolerance = 1e-6 * scene.modelHalfSize();  // vertices typed to a millimetre on a kilometre slope
  for (size_t f = 0; f < scene.blocks.size(); ++f) {
    const Block& fixed = scene.blocks[f];
    if (!fixed.fixed) continue;
    const std::vector<Vec2>& v = fixed.vertices;
    const size_t n = v.size();
    for (size_t i = 0; i < n; ++i) {
      // Counter-clockwise polygon: a right turn is a reflex vertex.
      const double bend = -turnDeg(v[i] - v[(i + n - 1) % n], v[(i + 1) % n] - v[i]);
      if (!isKink(bend)) continue;
      // Up the slope: towards the side whose edge rises more steeply from the kink.
      const Vec2 toPrev = (v[(i + n - 1) % n] - v[i]).normalized(), toNext = (v[(i + 1) % n] - v[i]).normalized();
      const double up = (toPrev.y() > toNext.y() ? toPrev : toNext).x() < 0 ? -1.0 : 1.0;
      int touched = 0;
      double reach = 0, height = 0;
      for (const Block& b : scene.blocks) {
        if (b.fixed) continue;
        bool here = false;
        double farthest = 0, lo = INFINITY, hi = -INFINITY;
        for (const Vec2& p : b.vertices) {
          here = here || (p - v[i]).norm() <= tolerance;
          farthest = std::max(farthest, up * (p.x() - v[i].x()));
          lo = std::min(lo, p.y()), hi = std::max(hi, p.y());
        }
        if (here && farthest > reach) reach = farthest, height = hi - lo;
        touched += here;
      }
      if (touched > 0) kinks.push_back({static_cast<int>(f), v[i], bend, reach, height, touched});
    }
  }
  return kinks;
}

}  // namespace ddaslope::model
