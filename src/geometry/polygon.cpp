#include "ddaslope/geometry/polygon.hpp"

#include "ddaslope/geometry/cutting.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ddaslope::geometry {

double signedArea(const std::vector<Vec2>& pts) {
  // Shoelace about the first vertex: avoids cancellation for far-from-origin coordinates.
  const Vec2 o = pts.front();
  double twice = 0;
  for (size_t k = 1; k + 1 < pts.size(); ++k) twice += cross(pts[k] - o, pts[k + 1] - o);
  return 0.5 * twice;
}

PolygonMoments computeMoments(const std::vector<Vec2>& pts) {
  PolygonMoments m;
  const Vec2 o = pts.front();
  // Pass 1: area and centroid from the triangle fan about the first vertex.
  double twiceArea = 0;
  Vec2 firstMoment(0, 0);
  for (size_t k = 1; k + 1 < pts.size(); ++k) {
    const Vec2 a = pts[k] - o, b = pts[k + 1] - o;
    const double c = cross(a, b);
    twiceArea += c;
    firstMoment += c * (a + b) / 3.0;  // triangle (0, a, b): area c/2, centroid (a+b)/3
  }
  m.area = 0.5 * twiceArea;
  m.centroid = o + firstMoment / twiceArea;
  // Pass 2: second moments of each edge triangle about the centroid (exact for linear fields):
  // ∫ x² over triangle (0,a,b) = (c/12)(ax² + ax bx + bx²), ∫ xy = (c/24)(2ax ay + ax by + bx ay + 2bx by).
  for (size_t k = 0; k < pts.size(); ++k) {
    const Vec2 a = pts[k] - m.centroid, b = pts[(k + 1) % pts.size()] - m.centroid;
    const double c = cross(a, b);
    m.sxx += c * (a.x() * a.x() + a.x() * b.x() + b.x() * b.x()) / 12.0;
    m.syy += c * (a.y() * a.y() + a.y() * b.y() + b.y() * b.y()) / 12.0;
    m.sxy += c * (2 * a.x() * a.y() + a.x() * b.y() + b.x() * a.y() + 2 * b.x() * b.y()) / 24.0;
  }
  return m;
}

static int orientationSign(const Vec2& a, const Vec2& b, const Vec2& c, double tol) {
  const double v = cross(b - a, c - a);
  return v > tol ? 1 : (v < -tol ? -1 : 0);
}

static bool onSegment(const Vec2& a, const Vec2& b, const Vec2& p, double tol) {
  return p.x() >= std::min(a.x(), b.x()) - tol && p.x() <= std::max(a.x(), b.x()) + tol &&
         p.y() >= std::min(a.y(), b.y()) - tol && p.y() <= std::max(a.y(), b.y()) + tol;
}

bool segmentsIntersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double scale = std::max({(b - a).norm(), (d - c).norm(), 1e-300});
  const double tol = 1e-12 * scale * scale;
  const int o1 = orientationSign(a, b, c, tol), o2 = orientationSign(a, b, d, tol);
  const int o3 = orientationSign(c, d, a, tol), o4 = orientationSign(c, d, b, tol);
  if (o1 != o2 && o3 != o4) return true;
  const double lt = 1e-12 * scale;
  if (o1 == 0 && onSegment(a, b, c, lt)) return true;
  if (o2 == 0 && onSegment(a, b, d, lt)) return true;
  if (o3 == 0 && onSegment(c, d, a, lt)) return true;
  if (o4 == 0 && onSegment(c, d, b, lt)) return true;
  return false;
}

bool isSimple(const std::vector<Vec2>& pts) { return pts.size() >= 3 && !simplicityDefect(pts); }

std::optional<SimplicityDefect> simplicityDefect(const std::vector<Vec2>& pts) {
  using Kind = SimplicityDefect::Kind;
  const size_t n = pts.size();
  if (n < 3) return SimplicityDefect{Kind::RepeatedVertex, 0, n > 1 ? size_t{1} : size_t{0}};
  const Aabb box = boundingBox(pts);
  const double size = std::max((box.hi - box.lo).maxCoeff(), 1e-300);
  for (size_t i = 0; i < n; ++i)
    if ((pts[(i + 1) % n] - pts[i]).norm() <= 1e-12 * size) return SimplicityDefect{Kind::RepeatedVertex, i, (i + 1) % n};
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      const bool adjacent = (j == i + 1) || (i == 0 && j == n - 1);
      if (adjacent) continue;
      if (segmentsIntersect(pts[i], pts[(i + 1) % n], pts[j], pts[(j + 1) % n])) return SimplicityDefect{Kind::CrossingEdges, i, j};
    }
  }
  // Adjacent edges folding back on each other (a spike) also make a degenerate polygon.
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = pts[(i + n - 1) % n], b = pts[i], c = pts[(i + 1) % n];
    const Vec2 u = (a - b).normalized(), v = (c - b).normalized();
    if (std::abs(cross(u, v)) < 1e-12 && u.dot(v) > 0) return SimplicityDefect{Kind::Fold, i, i};
  }
  return std::nullopt;
}

int removeCollinearVertices(std::vector<Vec2>& pts, double relativeTolerance, double absoluteTolerance) {
  const size_t n = pts.size();
  if (n <= 3) return 0;
  const auto at = [&](size_t k) -> const Vec2& { return pts[k % n]; };
  // Start from the most prominent corner (farthest from its neighbours' chord, against the chord's
  // length): a simple polygon keeps it whatever the rest.
  size_t anchor = 0;
  double prominent = -1;
  for (size_t k = 0; k < n; ++k) {
    const Vec2 chord = at(k + 1) - at(k + n - 1);
    const double s = std::abs(cross(chord, at(k) - at(k + n - 1))) / std::max(chord.squaredNorm(), 1e-300);
    if (s > prominent) prominent = s, anchor = k;
  }
  // Vertices from..to (exclusive, indices past anchor) all lie on the chord at(from)–at(to),
  // their projections in order along it.
  const auto onChord = [&](size_t from, size_t to) {
    const Vec2 a = at(from), d = at(to) - a;
    const double len = d.norm();
    if (!(len > 0)) return false;
    const Vec2 u = d / len;
    double last = 0;
    for (size_t k = from + 1; k < to; ++k) {
      const Vec2 r = at(k) - a;
      const double along = r.dot(u);
      if (std::abs(cross(u, r)) > std::max(relativeTolerance * len, absoluteTolerance) || along <= last || along >= len)
        return false;
      last = along;
    }
    return true;
  };
  std::vector<size_t> kept{anchor};
  size_t from = anchor;
  // The last run closes on the anchor (k = anchor + n).
  for (size_t k = anchor + 2; k <= anchor + n; ++k) {
    if (onChord(from, k)) continue;
    from = k - 1;  // the chord cannot reach k: the vertex before it is a corner
    kept.push_back(from % n);
  }
  const int removed = static_cast<int>(n - kept.size());
  if (removed == 0) return 0;
  // In their order, from the first one kept: an outline without such vertices is left as it was.
  std::rotate(kept.begin(), std::min_element(kept.begin(), kept.end()), kept.end());
  std::vector<Vec2> out;
  out.reserve(kept.size());
  for (size_t k : kept) out.push_back(pts[k]);
  pts = std::move(out);
  return removed;
}

int insertPointsOnEdges(std::vector<Vec2>& pts, const std::vector<Vec2>& points, double tol) {
  std::vector<Vec2> out;
  int inserted = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    const Vec2 a = pts[k], b = pts[(k + 1) % pts.size()];
    out.push_back(a);
    std::vector<std::pair<double, Vec2>> on;
    for (const Vec2& p : points) {
      double t;
      if (distanceToSegment(p, a, b, &t) > tol || (p - a).norm() <= tol || (p - b).norm() <= tol) continue;
      on.push_back({t, p});
    }
    std::sort(on.begin(), on.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& [t, p] : on)
      if ((p - out.back()).norm() > tol) out.push_back(p), ++inserted;
  }
  pts = std::move(out);
  return inserted;
}

std::vector<Vec2> unionAlongSharedEdges(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tol) {
  const size_t na = a.size(), nb = b.size();
  const auto same = [&](const Vec2& p, const Vec2& q) { return (p - q).norm() <= tol; };
  // An edge of a (i → i+1) that b runs the other way (j+1 → j... as j → j+1 = i+1 → i).
  for (size_t i = 0; i < na; ++i)
    for (size_t j = 0; j < nb; ++j) {
      if (!same(a[i], b[(j + 1) % nb]) || !same(a[(i + 1) % na], b[j])) continue;
      // a from its vertex i+1 round to i, then b from its vertex j+1 round to j, each shared
      // end once: the shared edge drops out.
      std::vector<Vec2> u;
      for (size_t k = 0; k < na; ++k) u.push_back(a[(i + 1 + k) % na]);
      for (size_t k = 1; k + 1 < nb; ++k) u.push_back(b[(j + 1 + k) % nb]);
      // Further shared edges next to this one fold back on themselves (… p, q, p …): remove them.
      for (bool folded = true; folded && u.size() >= 3;) {
        folded = false;
        for (size_t k = 0; k < u.size() && u.size() >= 3; ++k) {
          const size_t prev = (k + u.size() - 1) % u.size(), next = (k + 1) % u.size();
          if (same(u[prev], u[next])) {
            // Drop u[k] and one of its two equal neighbours.
            const size_t first = std::min(k, next), second = std::max(k, next);
            u.erase(u.begin() + static_cast<std::ptrdiff_t>(second));
            u.erase(u.begin() + static_cast<std::ptrdiff_t>(first));
            folded = true;
            break;
          }
        }
      }
      const double area = signedArea(a) + signedArea(b);
      if (u.size() >= 3 && isSimple(u) && std::abs(signedArea(u) - area) <= 1e-9 * std::abs(area)) return u;
      return {};
    }
  return {};
}

void orientCounterClockwise(std::vector<Vec2>& pts) {
  if (signedArea(pts) < 0) std::reverse(pts.begin(), pts.end());
}

bool containsPoint(const std::vector<Vec2>& pts, const Vec2& p, double tol) {
  const size_t n = pts.size();
  for (size_t i = 0; i < n; ++i) {
    double t;
    if (distanceToSegment(p, pts[i], pts[(i + 1) % n], &t) <= tol) return true;
  }
  bool inside = false;  // crossing number
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = pts[i];
    const Vec2& b = pts[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

Aabb boundingBox(const std::vector<Vec2>& pts) {
  Aabb box{pts.front(), pts.front()};
  for (const Vec2& p : pts) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b, double* t) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  double s = len2 > 0 ? (p - a).dot(ab) / len2 : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  if (t) *t = s;
  return (p - (a + s * ab)).norm();
}

double perimeter(const std::vector<Vec2>& pts) {
  double sum = 0;
  for (size_t i = 0; i < pts.size(); ++i) sum += (pts[(i + 1) % pts.size()] - pts[i]).norm();
  return sum;
}

namespace {

/// Adds to `o` (and to twice its area) the pieces of a's boundary that lie inside b: each edge is
/// split where b's boundary crosses or touches it, and a piece is kept when its midpoint is inside
/// b. A piece on b's boundary is kept only when `keepShared` and b's edge there runs the same way
/// (the two boundaries coincide around one region, counted once, from a); running the opposite
/// way, the polygons are neighbours along it.
void addBoundaryInside(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tol, bool keepShared,
                       Overlap& o, double& twiceArea) {
  const size_t na = a.size(), nb = b.size();
  std::vector<double> ts;
  for (size_t i = 0; i < na; ++i) {
    const Vec2 p = a[i], q = a[(i + 1) % na], d = q - p;
    const double len = d.norm();
    if (!(len > tol)) continue;
    ts.assign({0.0, 1.0});
    for (size_t j = 0; j < nb; ++j) {
      const Vec2 c = b[j], e = b[(j + 1) % nb], f = e - c;
      const double denom = cross(d, f);
      if (std::abs(denom) > 1e-12 * len * f.norm()) {
        const double t = cross(c - p, f) / denom, u = cross(c - p, d) / denom;
        if (t > 0 && t < 1 && u >= -tol / f.norm() && u <= 1 + tol / f.norm()) ts.push_back(t);
      }
      // b's corners on the edge split it too (collinear stretches, T-junctions).
      double t;
      if (distanceToSegment(c, p, q, &t) <= tol) ts.push_back(t);
    }
    std::sort(ts.begin(), ts.end());
    for (size_t k = 0; k + 1 < ts.size(); ++k) {
      if ((ts[k + 1] - ts[k]) * len <= tol) continue;
      const Vec2 s = p + ts[k] * d, e = p + ts[k + 1] * d, m = 0.5 * (s + e);
      double nearest = std::numeric_limits<double>::infinity();
      size_t edge = 0;
      for (size_t j = 0; j < nb; ++j) {
        double t2;
        const double dist = distanceToSegment(m, b[j], b[(j + 1) % nb], &t2);
        if (dist < nearest) nearest = dist, edge = j;
      }
      const bool keep = nearest <= tol ? keepShared && (b[(edge + 1) % nb] - b[edge]).dot(d) > 0
                                       : containsPoint(b, m, 0);
      if (!keep) continue;
      twiceArea += cross(s, e);
      o.perimeter += (e - s).norm();
      o.point = m;
    }
  }
}

/// Triangles of a counter-clockwise simple polygon, by ear clipping. A polygon whose rounding
/// leaves no clean ear (near-collinear vertices) loses its most convex corner instead: a sliver
/// of round-off size, harmless to an area.
std::vector<std::array<Vec2, 3>> triangles(std::vector<Vec2> p) {
  std::vector<std::array<Vec2, 3>> out;
  const auto strictlyInside = [](const Vec2& x, const Vec2& u, const Vec2& v, const Vec2& w) {
    return cross(v - u, x - u) > 0 && cross(w - v, x - v) > 0 && cross(u - w, x - w) > 0;
  };
  size_t start = 0;
  while (p.size() > 3) {
    const size_t n = p.size();
    size_t ear = n, fallback = 0;
    double mostConvex = -std::numeric_limits<double>::infinity();
    for (size_t step = 0; step < n && ear == n; ++step) {
      const size_t i = (start + step) % n;
      const Vec2 &u = p[(i + n - 1) % n], &v = p[i], &w = p[(i + 1) % n];
      const double c = cross(v - u, w - v);
      if (c > mostConvex) mostConvex = c, fallback = i;
      if (!(c > 0)) continue;
      bool empty = true;
      for (size_t k = 0; k < n && empty; ++k)
        if (k != i && k != (i + 1) % n && k != (i + n - 1) % n && strictlyInside(p[k], u, v, w)) empty = false;
      if (empty) ear = i;
    }
    if (ear == n) ear = fallback;
    out.push_back({p[(ear + n - 1) % n], p[ear], p[(ear + 1) % n]});
    p.erase(p.begin() + static_cast<std::ptrdiff_t>(ear));
    start = ear == 0 ? 0 : ear - 1;  // the neighbours are the likeliest next ears
  }
  if (p.size() == 3) out.push_back({p[0], p[1], p[2]});
  return out;
}

/// The area two counter-clockwise simple polygons share, as the sum over their triangles of the
/// convex intersections (Sutherland–Hodgman). Every term is a clipped region's own area, so a
/// boundary that nearly coincides with the other's adds at most a sliver: the Green's-theorem sum
/// below needs each piece classified consistently from both sides, and a piece classified
/// differently there leaves a loop unclosed, adding the area of a triangle to a far origin.
double sharedAreaByTriangles(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  const auto ta = triangles(a), tb = triangles(b);
  std::vector<Aabb> boxesB;
  boxesB.reserve(tb.size());
  for (const auto& u : tb) boxesB.push_back(boundingBox({u[0], u[1], u[2]}));
  double area = 0;
  for (const auto& t : ta) {
    const Aabb bt = boundingBox({t[0], t[1], t[2]});
    for (size_t j = 0; j < tb.size(); ++j) {
      const Aabb& bu = boxesB[j];
      if (bu.lo.x() > bt.hi.x() || bt.lo.x() > bu.hi.x() || bu.lo.y() > bt.hi.y() || bt.lo.y() > bu.hi.y()) continue;
      std::vector<Vec2> piece{t[0], t[1], t[2]};
      for (int e = 0; e < 3 && piece.size() >= 3; ++e) piece = clipToLeft(piece, tb[j][e], tb[j][(e + 1) % 3] - tb[j][e]);
      if (piece.size() >= 3) area += std::max(0.0, signedArea(piece));
    }
  }
  return area;
}

}  // namespace

Overlap overlapOf(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tol) {
  // About a's first corner: far from the origin the cross products would lose the overlap.
  const Vec2 origin = a.front();
  std::vector<Vec2> la(a), lb(b);
  for (Vec2& v : la) v -= origin;
  for (Vec2& v : lb) v -= origin;
  Overlap o;
  double twiceArea = 0;
  addBoundaryInside(la, lb, tol, true, o, twiceArea);
  addBoundaryInside(lb, la, tol, false, o, twiceArea);
  // Green's theorem over the pieces leaves neighbours along a common edge, within tol, sharing
  // exactly nothing; the triangles bound it where a piece was classified differently from each side.
  // (Only where the sum finds an area: the triangles cost a triangulation of each outline.)
  o.area = std::max(0.0, 0.5 * twiceArea);
  if (o.area > 0) o.area = std::min(o.area, sharedAreaByTriangles(la, lb));
  o.point += origin;
  return o;
}

}  // namespace ddaslope::geometry
