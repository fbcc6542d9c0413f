#include "ddaslope/geometry/cutting.hpp"

#include <cmath>

#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::geometry {

std::vector<Vec2> cleanPolygon(std::vector<Vec2> pts, double tol) {
  bool changed = true;
  while (changed && pts.size() >= 3) {
    changed = false;
    for (size_t i = 0; i < pts.size() && pts.size() >= 3; ++i) {
      const size_t n = pts.size();
      const Vec2 &a = pts[(i + n - 1) % n], &b = pts[i], &c = pts[(i + 1) % n];
      const bool repeated = (b - a).norm() <= tol;
      const bool straight = std::abs(cross(b - a, c - b)) <= tol * ((b - a).norm() + (c - b).norm()) &&
                            (b - a).dot(c - b) > 0;
      if (repeated || straight) {
        pts.erase(pts.begin() + static_cast<long>(i));
        changed = true;
        --i;
      }
    }
  }
  return pts.size() >= 3 ? pts : std::vector<Vec2>{};
}

std::vector<Vec2> clipToLeft(const std::vector<Vec2>& pts, const Vec2& p, const Vec2& d) {
  std::vector<Vec2> out;
  const size_t n = pts.size();
  const auto side = [&](const Vec2& x) { return cross(d, x - p); };
  const Aabb box = boundingBox(pts);
  const double tol = 1e-12 * std::max((box.hi - box.lo).maxCoeff(), 1e-300);
  for (size_t i = 0; i < n; ++i) {
    const Vec2 &a = pts[i], &b = pts[(i + 1) % n];
    const double sa = side(a), sb = side(b);
    if (sa >= 0) out.push_back(a);
    if ((sa > 0 && sb < 0) || (sa < 0 && sb > 0)) out.push_back(a + (b - a) * (sa / (sa - sb)));
  }
  return cleanPolygon(out, tol * d.norm());
}

int lineCrossings(const std::vector<Vec2>& pts, const Vec2& p, const Vec2& d) {
  int count = 0;
  const size_t n = pts.size();
  const auto side = [&](const Vec2& x) { return cross(d, x - p); };
  for (size_t i = 0; i < n; ++i) {
    // Count sign changes of the vertex sequence (vertices on the line take the previous sign).
    const double sa = side(pts[i]), sb = side(pts[(i + 1) % n]);
    if ((sa > 0 && sb < 0) || (sa < 0 && sb > 0)) ++count;
    else if (sb == 0) {
      // Touching the line at a vertex: a crossing only if the sides before and after differ.
      const double sc = side(pts[(i + 2) % n]);
      if ((sa > 0 && sc < 0) || (sa < 0 && sc > 0)) ++count;
    }
  }
  return count;
}

}  // namespace ddaslope::geometry
