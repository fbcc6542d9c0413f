#include "ddaslope/contact/narrow_phase.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::contact {
namespace {

/// Entrances of a corner-to-corner contact whose gaps differ by less than this fraction of the
/// search distance count as equally open.
constexpr double kGapTieFraction = 1e-3;

struct Poly {
  int block;
  const std::vector<Vec2>& p;
  int n() const { return static_cast<int>(p.size()); }
  /// Vertex k, for k from −1 to n (every caller steps at most one past either end): a wrap
  /// without the two divisions of a general modulo, which the hot loops below paid per access.
  int wrap(int k) const { return k < 0 ? k + n() : k >= n() ? k - n() : k; }
  const Vec2& at(int k) const { return p[static_cast<size_t>(wrap(k))]; }
  bool convex(int k) const { return cross(at(k) - at(k - 1), at(k + 1) - at(k)) > 0; }
};

/// How well the line of edge e (of poly E) separates the corner at vertex v of poly V:
/// the smallest outward component of the corner's two unit edge directions.
double clearance(const Poly& V, int v, const Poly& E, int e) {
  const Vec2 a = E.at(e), b = E.at(e + 1);
  const Vec2 d = (b - a).normalized();
  const Vec2 nOut(d.y(), -d.x());
  const Vec2 p = V.at(v);
  const double u1 = (V.at(v - 1) - p).normalized().dot(nOut);
  const double u2 = (V.at(v + 1) - p).normalized().dot(nOut);
  return std::min(u1, u2);
}

ContactCandidate makeCandidate(const Poly& V, int v, const Poly& E, int e, double sinParallelTol) {
  ContactCandidate c;
  c.key = {V.block, v, E.block, e};
  const Vec2 a = E.at(e), b = E.at(e + 1), p = V.at(v);
  const double len = (b - a).norm();
  const Vec2 d = (b - a) / len;
  c.gap = cross(d, p - a) * -1.0;  // outward normal is (dy, −dx): gap = (p − a)·n
  c.ratio = (p - a).dot(d) / len;
  // Edge-to-edge: one of the corner's edges lies against edge e, antiparallel (both CCW).
  for (int k : {v - 1, v}) {
    const Vec2 q0 = V.at(k), q1 = V.at(k + 1);
    const Vec2 dq = (q1 - q0).normalized();
    if (dq.dot(d) >= 0 || std::abs(cross(dq, d)) > sinParallelTol) continue;
    const double s0 = (q0 - a).dot(d), s1 = (q1 - a).dot(d);
    const double overlap = std::min(std::max(s0, s1), len) - std::max(std::min(s0, s1), 0.0);
    if (overlap > 1e-9 * len && overlap > c.overlap) {
      c.overlap = overlap;
      c.pairedEdge = V.wrap(k);
    }
  }
  return c;
}

/// The region where the two blocks can touch: their boxes' overlap grown by the search distance.
/// Only vertices inside it and edges crossing it need the exact tests.
struct Region {
  geometry::Aabb box;
  bool contains(const Vec2& p) const {
    return p.x() >= box.lo.x() && p.x() <= box.hi.x() && p.y() >= box.lo.y() && p.y() <= box.hi.y();
  }
  bool meets(const Vec2& a, const Vec2& b) const {
    return std::max(a.x(), b.x()) >= box.lo.x() && std::min(a.x(), b.x()) <= box.hi.x() &&
           std::max(a.y(), b.y()) >= box.lo.y() && std::min(a.y(), b.y()) <= box.hi.y();
  }
};

Region contactRegion(const std::vector<Vec2>& pa, const std::vector<Vec2>& pb, double d) {
  const geometry::Aabb a = geometry::boundingBox(pa), b = geometry::boundingBox(pb);
  const Vec2 margin(d, d);
  return {{a.lo.cwiseMax(b.lo) - margin, a.hi.cwiseMin(b.hi) + margin}};
}

void vertexOnEdges(const Poly& V, const Poly& E, const Region& region, const NarrowPhaseSettings& s,
                   std::vector<ContactCandidate>& out) {
  const double minClearance = -s.sinParallelTolerance;
  for (int v = 0; v < V.n(); ++v) {
    const Vec2& p = V.at(v);
    if (!region.contains(p) || !V.convex(v)) continue;  // a reflex vertex cannot touch an edge from outside
    for (int e = 0; e < E.n(); ++e) {
      const Vec2 a = E.at(e), b = E.at(e + 1);
      if (!region.meets(a, b)) continue;
      double t;
      if (geometry::distanceToSegment(p, a, b, &t) > s.searchDistance) continue;
      // Near an end of the edge: the vertex-to-vertex rule decides.
      if ((p - a).norm() < s.searchDistance || (p - b).norm() < s.searchDistance) continue;
      if (clearance(V, v, E, e) < minClearance) continue;
      ContactCandidate c = makeCandidate(V, v, E, e, s.sinParallelTolerance);
      // Deeper than a step can carry a vertex (0.4 of the search distance): behind the edge, not
      // this edge's contact.
      if (c.gap < -0.5 * s.searchDistance) continue;
      out.push_back(c);
    }
  }
}

struct Option {
  const Poly* vertexPoly;
  int v;
  const Poly* edgePoly;
  int e;
  double clearance;
};

/// At most four entrances (two per corner): a fixed array, not a vector allocated per vertex.
struct Options {
  std::array<Option, 4> item;
  int count = 0;
  void add(const Option& o, double minClearance) {
    if (!(o.clearance < minClearance)) item[static_cast<size_t>(count++)] = o;
  }
  const Option* begin() const { return item.data(); }
  const Option* end() const { return item.data() + count; }
};

/// The vertex of B nearest to point p (the first of equals).
int nearestVertex(const Vec2& p, const Poly& B) {
  int nearest = 0;
  double best = (p - B.at(0)).squaredNorm();
  for (int q = 1; q < B.n(); ++q) {
    const double d = (p - B.at(q)).squaredNorm();
    if (d < best) nearest = q, best = d;
  }
  return nearest;
}

void vertexToVertex(const Poly& A, const Poly& B, const Region& region, const NarrowPhaseSettings& s,
                    const std::function<bool(const ContactKey&)>& known, std::vector<ContactCandidate>& out) {
  const double minClearance = -s.sinParallelTolerance;
  const auto candidate = [&](const Option& o) {
    return makeCandidate(*o.vertexPoly, o.v, *o.edgePoly, o.e, s.sinParallelTolerance);
  };
  for (int p = 0; p < A.n(); ++p) {
    if (!region.contains(A.at(p))) continue;
    // Only the nearest vertex of B can be the corner P touches: with blocks not much larger than
    // the search distance, farther corners are within reach too and would give false contacts.
    const int q = nearestVertex(A.at(p), B);
    if ((A.at(p) - B.at(q)).norm() >= s.searchDistance) continue;
    const bool pConvex = A.convex(p), qConvex = B.convex(q);
    if (!pConvex && !qConvex) continue;
    Options options;
    if (pConvex)
      for (int e : {q - 1, q}) options.add({&A, p, &B, B.wrap(e), clearance(A, p, B, B.wrap(e))}, minClearance);
    if (qConvex)
      for (int e : {p - 1, p}) options.add({&B, q, &A, A.wrap(e), clearance(B, q, A, A.wrap(e))}, minClearance);
    if (options.count == 0) continue;
    if (!qConvex || !pConvex) {
      // A convex corner in a reflex corner touches both of its edges.
      for (const Option& o : options) {
        const ContactCandidate c = candidate(o);
        if (c.gap >= -0.5 * s.searchDistance) out.push_back(c);
      }
      continue;
    }
    // Two convex corners: one contact, on the entrance edge that best separates them.
    // Near-ties keep last step's contact so that its state and history persist.
    const Option* best = options.begin();
    for (const Option& o : options)
      if (o.clearance > best->clearance) best = &o;
    for (const Option& o : options) {
      const ContactKey k{o.vertexPoly->block, o.v, o.edgePoly->block, o.e};
      if (o.clearance >= best->clearance - 1e-3 && known(k)) {
        best = &o;
        break;
      }
    }
    // A contact the corners start, or switch to, takes the entrance the corner has penetrated
    // least (Shi: of the two entrances, the shortest distance), unless the one chosen above is
    // as open up to a tie. Another entrance may measure the vertex against the extension of an
    // edge it has already passed: a penetration the blocks do not have, whose spring would
    // start with energy no work has paid for (corners passing each other in the Vajont
    // run-out: 0.47 m, 4.4e10 J/m in one step). A contact kept from the last step goes on
    // with the spring it has.
    ContactCandidate chosen = candidate(*best);
    if (!known(chosen.key)) {
      ContactCandidate open = chosen;
      for (const Option& o : options) {
        // The chosen entrance's candidate is the one just made (makeCandidate is pure).
        const ContactCandidate c = &o == best ? chosen : candidate(o);
        if (c.gap > open.gap) open = c;
      }
      if (open.gap > chosen.gap + kGapTieFraction * s.searchDistance) chosen = open;
    }
    if (chosen.gap >= -0.5 * s.searchDistance) out.push_back(chosen);
  }
}

}  // namespace

void findContacts(int a, const std::vector<Vec2>& pa, int b, const std::vector<Vec2>& pb,
                  const NarrowPhaseSettings& s, const std::function<bool(const ContactKey&)>& known,
                  std::vector<ContactCandidate>& out) {
  const Poly A{a, pa}, B{b, pb};
  const Region region = contactRegion(pa, pb, s.searchDistance);
  if (region.box.lo.x() > region.box.hi.x() || region.box.lo.y() > region.box.hi.y()) return;
  vertexOnEdges(A, B, region, s, out);
  vertexOnEdges(B, A, region, s, out);
  vertexToVertex(A, B, region, s, known, out);
}

}  // namespace ddaslope::contact
