#include "ddaslope/contact/narrow_phase.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "ddaslope/geometry/polygon.hpp"
#include "narrow_phase_certifier.hpp"

namespace ddaslope::contact {
namespace {

using detail::Certifier;
using detail::Poly;
using detail::SkipChain;
using detail::allNonNegativeSlack;
using detail::convexSlack;
using detail::gapRate;
using detail::nearestSlack;

/// Entrances of a corner-to-corner contact whose gaps differ by less than this fraction of the
/// search distance count as equally open.
constexpr double kGapTieFraction = 1e-3;

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
  // The region's bounds and the points each move by at most δ: rate 2.
  double containsSlack(const Vec2& p) const {
    return allNonNegativeSlack({p.x() - box.lo.x(), box.hi.x() - p.x(), p.y() - box.lo.y(), box.hi.y() - p.y()}, 2);
  }
  double meetsSlack(const Vec2& a, const Vec2& b) const {
    return allNonNegativeSlack({std::max(a.x(), b.x()) - box.lo.x(), box.hi.x() - std::min(a.x(), b.x()),
                                std::max(a.y(), b.y()) - box.lo.y(), box.hi.y() - std::min(a.y(), b.y())},
                               2);
  }
  double nonEmptySlack() const { return allNonNegativeSlack({box.hi.x() - box.lo.x(), box.hi.y() - box.lo.y()}, 2); }
};

Region contactRegion(const geometry::Aabb& a, const geometry::Aabb& b, double d) {
  const Vec2 margin(d, d);
  return {{a.lo.cwiseMax(b.lo) - margin, a.hi.cwiseMin(b.hi) + margin}};
}

void vertexOnEdges(const Poly& V, const Poly& E, const Region& region, const NarrowPhaseSettings& s,
                   Certifier& cert, std::vector<ContactCandidate>& out) {
  const double minClearance = -s.sinParallelTolerance;
  const double sd = s.searchDistance;
  // The edges of E that cross the region, found once: a block on a long stepped base meets a few
  // of its edges. An edge outside is skipped on the same test for every vertex, so its slack is
  // held once, when the first vertex reaches the edges. An edge that crosses it and gives a
  // contact no longer holds its crossing's slack, which never binds: with the exact boxes, a
  // vertex of V within distance δ ≤ sd of the edge puts the edge at least sd − δ inside each side
  // of the region, a slack of (sd − δ)/2, the distance test's own.
  thread_local std::vector<int> crossing;
  crossing.clear();
  double outsideSlack = INFINITY;
  for (int e = 0; e < E.n(); ++e) {
    const Vec2 a = E.at(e), b = E.at(e + 1);
    if (region.meets(a, b))
      crossing.push_back(e);
    else if (cert.on())
      outsideSlack = std::min(outsideSlack, region.meetsSlack(a, b));
  }
  bool outsideHeld = false;
  for (int v = 0; v < V.n(); ++v) {
    const Vec2& p = V.at(v);
    SkipChain vertex(cert);
    if (vertex.skipIf(!region.contains(p), [&] { return region.containsSlack(p); })) continue;
    // A reflex vertex cannot touch an edge from outside.
    if (vertex.skipIf(!V.convex(v), [&] { return convexSlack(V, v, cert); })) continue;
    if (!outsideHeld) cert.hold(outsideSlack), outsideHeld = true;
    for (const int e : crossing) {
      if (E.internalEdge(e)) continue;  // inside the base: no face (a flag of the scene's)
      const Vec2 a = E.at(e), b = E.at(e + 1);
      SkipChain edge(cert);
      double t;
      const double distance = geometry::distanceToSegment(p, a, b, &t);
      if (edge.skipIf(distance > sd, [&] { return std::abs(distance - sd) / 2; })) continue;
      // Near an end of the edge: the vertex-to-vertex rule decides.
      const double toA = (p - a).norm();
      if (edge.skipIf(toA < sd, [&] { return std::abs(toA - sd) / 2; })) continue;
      const double toB = (p - b).norm();
      if (edge.skipIf(toB < sd, [&] { return std::abs(toB - sd) / 2; })) continue;
      const double clear = clearance(V, v, E, e);
      if (edge.skipIf(clear < minClearance, [&] { return std::abs(clear - minClearance) / (2 * cert.unitRate); }))
        continue;
      ContactCandidate c = makeCandidate(V, v, E, e, s.sinParallelTolerance);
      // Deeper than a step can carry a vertex (0.4 of the search distance): behind the edge, not
      // this edge's contact.
      if (edge.skipIf(c.gap < -0.5 * sd, [&] { return std::abs(c.gap + 0.5 * sd) / gapRate(p, a, cert); }))
        continue;
      edge.passed();
      vertex.passed();
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
                    const std::function<bool(const ContactKey&)>& known, Certifier& cert,
                    std::vector<ContactCandidate>& out) {
  const double minClearance = -s.sinParallelTolerance;
  const double sd = s.searchDistance;
  const auto candidate = [&](const Option& o) {
    return makeCandidate(*o.vertexPoly, o.v, *o.edgePoly, o.e, s.sinParallelTolerance);
  };
  const auto keyOf = [](const Option& o) { return ContactKey{o.vertexPoly->block, o.v, o.edgePoly->block, o.e}; };
  const auto gapRateOf = [&](const Option& o) { return gapRate(o.vertexPoly->at(o.v), o.edgePoly->at(o.e), cert); };
  // Rate of a clearance: two unit directions (the corner's edge and the entrance's normal).
  const double clearanceRate = 2 * cert.unitRate;
  for (int p = 0; p < A.n(); ++p) {
    SkipChain corner(cert);
    if (corner.skipIf(!region.contains(A.at(p)), [&] { return region.containsSlack(A.at(p)); })) continue;
    // Only the nearest vertex of B can be the corner P touches: with blocks not much larger than
    // the search distance, farther corners are within reach too and would give false contacts.
    // (Skipped, the test holds on the distance alone, whichever vertex is nearest.)
    const int q = nearestVertex(A.at(p), B);
    const double apart = (A.at(p) - B.at(q)).norm();
    if (corner.skipIf(apart >= sd, [&] { return std::abs(apart - sd) / 2; })) continue;
    // From here on every decision is held: the corner's nearest vertex, its convexity, the
    // entrances allowed, the choice among them.
    if (cert.on()) {
      corner.passed();
      cert.hold(nearestSlack(A.at(p), B, q));
      cert.hold(convexSlack(A, p, cert));
      cert.hold(convexSlack(B, q, cert));
    }
    const bool pConvex = A.convex(p), qConvex = B.convex(q);
    if (!pConvex && !qConvex) continue;
    Options options;
    const auto add = [&](const Option& o) {
      if (cert.on()) cert.hold(std::abs(o.clearance - minClearance) / clearanceRate);
      options.add(o, minClearance);
    };
    if (pConvex)
      for (int e : {q - 1, q})
        if (!B.internalEdge(e)) add({&A, p, &B, B.wrap(e), clearance(A, p, B, B.wrap(e))});
    if (qConvex)
      for (int e : {p - 1, p})
        if (!A.internalEdge(e)) add({&B, q, &A, A.wrap(e), clearance(B, q, A, A.wrap(e))});
    if (options.count == 0) continue;
    if (!qConvex || !pConvex) {
      // A convex corner in a reflex corner touches both of its edges.
      for (const Option& o : options) {
        const ContactCandidate c = candidate(o);
        if (cert.on()) cert.hold(std::abs(c.gap + 0.5 * sd) / gapRateOf(o));
        if (c.gap >= -0.5 * sd) out.push_back(c);
      }
      continue;
    }
    // Two convex corners: one contact, on the entrance edge that best separates them.
    // Near-ties keep last step's contact so that its state and history persist.
    const Option* best = options.begin();
    for (const Option& o : options)
      if (o.clearance > best->clearance) best = &o;
    const Option* tied = nullptr;
    for (const Option& o : options) {
      // A search that certifies asks about every entrance, so that the answers it records cover
      // whichever entrance a slightly moved corner would ask about.
      if (cert.on()) {
        cert.hold(std::abs(o.clearance - (best->clearance - 1e-3)) / (2 * clearanceRate));
        if (cert.ask(known, keyOf(o)) && o.clearance >= best->clearance - 1e-3 && !tied) tied = &o;
      } else if (o.clearance >= best->clearance - 1e-3 && known(keyOf(o))) {
        tied = &o;
        break;
      }
    }
    if (cert.on() && !tied)  // the best entrance itself decides
      for (const Option& o : options)
        if (&o != best) cert.hold(std::abs(o.clearance - best->clearance) / (2 * clearanceRate));
    if (tied) best = tied;
    // A contact the corners start, or switch to, takes the entrance the corner has penetrated
    // least (Shi: of the two entrances, the shortest distance), unless the one chosen above is
    // as open up to a tie. Another entrance may measure the vertex against the extension of an
    // edge it has already passed: a penetration the blocks do not have, whose spring would
    // start with energy no work has paid for (corners passing each other in the Vajont
    // run-out: 0.47 m, 4.4e10 J/m in one step). A contact kept from the last step goes on
    // with the spring it has.
    ContactCandidate chosen = candidate(*best);
    const Option* chosenOption = best;
    if (!cert.ask(known, chosen.key)) {
      ContactCandidate open = chosen;
      const Option* openOption = best;
      for (const Option& o : options) {
        // The chosen entrance's candidate is the one just made (makeCandidate is pure).
        const ContactCandidate c = &o == best ? chosen : candidate(o);
        if (cert.on()) cert.hold(std::abs(c.gap - open.gap) / (gapRateOf(o) + gapRateOf(*openOption)));
        if (c.gap > open.gap) open = c, openOption = &o;
      }
      const double tie = kGapTieFraction * sd;
      if (cert.on())
        cert.hold(std::abs(open.gap - (chosen.gap + tie)) / (gapRateOf(*openOption) + gapRateOf(*best)));
      if (open.gap > chosen.gap + tie) chosen = open, chosenOption = openOption;
    }
    if (cert.on()) cert.hold(std::abs(chosen.gap + 0.5 * sd) / gapRateOf(*chosenOption));
    if (chosen.gap >= -0.5 * sd) out.push_back(chosen);
  }
}

}  // namespace

void findContacts(int a, const std::vector<Vec2>& pa, int b, const std::vector<Vec2>& pb,
                  const NarrowPhaseSettings& s, const std::function<bool(const ContactKey&)>& known,
                  std::vector<ContactCandidate>& out, SearchMargin* margin,
                  const std::array<geometry::Aabb, 2>* boxes) {
  const auto flatOf = [&](int block, const std::vector<Vec2>& p) -> const std::vector<char>* {
    if (!s.flatCorners || block >= static_cast<int>(s.flatCorners->size())) return nullptr;
    const std::vector<char>& f = (*s.flatCorners)[static_cast<size_t>(block)];
    return f.size() == p.size() ? &f : nullptr;
  };
  const Poly A{a, pa, flatOf(a, pa)}, B{b, pb, flatOf(b, pb)};
  Certifier cert(margin, A, B);
  const Region region = boxes ? contactRegion((*boxes)[0], (*boxes)[1], s.searchDistance)
                              : contactRegion(geometry::boundingBox(pa), geometry::boundingBox(pb), s.searchDistance);
  const bool empty = region.box.lo.x() > region.box.hi.x() || region.box.lo.y() > region.box.hi.y();
  if (cert.on()) cert.hold(region.nonEmptySlack());
  if (empty) return;
  vertexOnEdges(A, B, region, s, cert, out);
  vertexOnEdges(B, A, region, s, cert, out);
  vertexToVertex(A, B, region, s, known, cert, out);
}

ContactCandidate contactCandidate(int a, const std::vector<Vec2>& pa, int v, int b, const std::vector<Vec2>& pb,
                                  int e, const NarrowPhaseSettings& s) {
  return makeCandidate(Poly{a, pa}, v, Poly{b, pb}, e, s.sinParallelTolerance);
}

}  // namespace ddaslope::contact
