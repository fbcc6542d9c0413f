#include "ddaslope/model/block.hpp"

#include <algorithm>
#include <cmath>

namespace ddaslope::model {

Mat26 displacementMatrix(const Vec2& c, const Vec2& p) {
  const double x = p.x() - c.x(), y = p.y() - c.y();
  Mat26 t;
  t << 1, 0, -y, x, 0, y / 2,
       0, 1, x, 0, y, x / 2;
  return t;
}

Vec2 displacedPoint(const Vec2& c, const Vec2& p, const Vec6& d) {
  const double x = p.x() - c.x(), y = p.y() - c.y();
  const double cr = std::cos(d[2]), sr = std::sin(d[2]);
  // Rigid part rotated exactly; strain part linear as in T.
  const double ux = d[0] + (cr - 1) * x - sr * y + d[3] * x + d[5] * y / 2;
  const double uy = d[1] + sr * x + (cr - 1) * y + d[4] * y + d[5] * x / 2;
  return {p.x() + ux, p.y() + uy};
}

void Block::applyDisplacement(const Vec6& d) {
  const Vec2 c = moments.centroid;
  for (Vec2& v : vertices) v = displacedPoint(c, v, d);
  moments = geometry::computeMoments(vertices);
  rotation += d[2];
}

double Block::vertexDisplacementBound(const Vec6& d) const {
  const Vec2& c = moments.centroid;
  double x = 0, y = 0;
  for (const Vec2& v : vertices) x = std::max(x, std::abs(v.x() - c.x())), y = std::max(y, std::abs(v.y() - c.y()));
  // T D = (d0 − y d2 + x d3 + y d5/2, d1 + x d2 + y d4 + x d5/2): each component is at most the
  // sum of its terms' sizes. The factor 1 + 1e-10 covers the round-off of both computations
  // (a few units of 1e-16 of those sums).
  const double u = std::abs(d[0]) + y * std::abs(d[2]) + x * std::abs(d[3]) + 0.5 * y * std::abs(d[5]);
  const double w = std::abs(d[1]) + x * std::abs(d[2]) + y * std::abs(d[4]) + 0.5 * x * std::abs(d[5]);
  return (1 + 1e-10) * std::sqrt(u * u + w * w);
}

double Block::maxVertexDisplacement(const Vec6& d) const {
  double worst = 0;
  for (const Vec2& v : vertices) worst = std::max(worst, (tAt(v) * d).norm());
  return worst;
}

}  // namespace ddaslope::model
