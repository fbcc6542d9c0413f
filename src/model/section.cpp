#include "ddaslope/model/section.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/geometry/cutting.hpp"
#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/model/input_limits.hpp"
#include "ddaslope/model/kinks.hpp"

namespace ddaslope::model {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& msg) { throw InputError("", path, msg); }

double groundAt(const std::vector<Vec2>& g, double x) {
  if (x <= g.front().x()) return g.front().y();
  for (size_t i = 1; i < g.size(); ++i)
    if (x <= g[i].x() && g[i].x() > g[i - 1].x())
      return g[i - 1].y() + (g[i].y() - g[i - 1].y()) * (x - g[i - 1].x()) / (g[i].x() - g[i - 1].x());
  return g.back().y();
}

/// Where p lies on the polyline g, as i + t for the first segment [g_i, g_i+1] within tol of p
/// (t in [0, 1]); -1 when p is not on it. Positions order ground vertices that share an x (a
/// vertical step at the toe or crown) where x alone cannot.
double positionOnPolyline(const std::vector<Vec2>& g, const Vec2& p, double tol) {
  for (size_t i = 0; i + 1 < g.size(); ++i) {
    const Vec2 d = g[i + 1] - g[i];
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - g[i]).dot(d) / len2, 0.0, 1.0) : 0.0;
    if ((g[i] + t * d - p).norm() <= tol) return static_cast<double>(i) + t;
  }
  return -1;
}

/// Ground vertex i lies before (upslope of) point p: by its position along the ground when p is
/// on the ground, by x otherwise (a sliding surface may end a little off a digitised ground).
bool groundVertexBefore(const std::vector<Vec2>& g, size_t i, const Vec2& p, double position, double tol) {
  if (position >= 0) return static_cast<double>(i) < position - 1e-12 && (g[i] - p).norm() > tol;
  return g[i].x() < p.x() - tol;
}

bool groundVertexAfter(const std::vector<Vec2>& g, size_t i, const Vec2& p, double position, double tol) {
  if (position >= 0) return static_cast<double>(i) > position + 1e-12 && (g[i] - p).norm() > tol;
  return g[i].x() > p.x() + tol;
}

Block makeBlock(std::string id, bool fixed, std::vector<Vec2> v) {
  Block b;
  b.id = std::move(id);
  b.fixed = fixed;
  geometry::orientCounterClockwise(v);
  b.vertices = std::move(v);
  b.moments = geometry::computeMoments(b.vertices);
  return b;
}

/// Splits every piece by the line; pieces it misses stay whole.
void cutAll(std::vector<std::vector<Vec2>>& pieces, const Vec2& p, const Vec2& d, const std::string& path,
            double minArea) {
  std::vector<std::vector<Vec2>> next;
  for (const auto& piece : pieces) {
    const int crossings = geometry::lineCrossings(piece, p, d);
    if (crossings <= 1) {
      next.push_back(piece);
      continue;
    }
    if (crossings > 2)
      fail(path, "this joint would cut a non-convex piece of the slide mass into more than two blocks; "
                 "split the mass with other joints first or shorten the section");
    for (const auto& part : {geometry::clipToLeft(piece, p, d), geometry::clipToLeft(piece, p, -d)})
      if (part.size() >= 3 && std::abs(geometry::signedArea(part)) > minArea) next.push_back(part);
  }
  pieces = std::move(next);
}


/// Distance from p to the nearest joint line of the section (explicit joints and joint sets).
double distanceToNearestJoint(const SectionSpec& s, const Vec2& p) {
  double nearest = INFINITY;
  for (const auto& [a, b] : s.joints) {
    const Vec2 d = (b - a).normalized();
    nearest = std::min(nearest, std::abs(cross(d, p - a)));
  }
  for (const JointSet& js : s.jointSets) {
    if (!(js.spacing > 0)) continue;
    const double ang = degToRad(js.angleDeg);
    const Vec2 n(-std::sin(ang), std::cos(ang));
    const double o = n.dot(p - js.origin);
    nearest = std::min(nearest, std::abs(o - js.spacing * std::round(o / js.spacing)));
  }
  return nearest;
}

/// Whether a joint line inclined by more than 10° from the vertical passes through p (within tol).
bool inclinedJointThrough(const SectionSpec& s, const Vec2& p, double tol) {
  const auto inclined = [](const Vec2& d) { return std::abs(d.normalized().x()) > std::sin(degToRad(10)); };
  for (const auto& [a, b] : s.joints) {
    const Vec2 d = (b - a).normalized();
    if (inclined(d) && std::abs(cross(d, p - a)) <= tol) return true;
  }
  for (const JointSet& js : s.jointSets) {
    if (!(js.spacing > 0)) continue;
    const double ang = degToRad(js.angleDeg);
    const Vec2 d(std::cos(ang), std::sin(ang)), n(-d.y(), d.x());
    const double o = n.dot(p - js.origin);
    if (inclined(d) && std::abs(o - js.spacing * std::round(o / js.spacing)) <= tol) return true;
  }
  return false;
}

/// Whether the piece a kink block's vertical cut at `at` would split reaches the crown: the cut
/// would leave the crown's piece bounded by nothing but the surface and the cut.
bool crownPieceAbove(const std::vector<std::vector<Vec2>>& pieces, const Vec2& at, const Vec2& crown, double tol) {
  for (const auto& piece : pieces) {
    const geometry::Aabb box = geometry::boundingBox(piece);
    if (at.x() <= box.lo.x() + tol || at.x() >= box.hi.x() - tol) continue;
    if (geometry::lineCrossings(piece, Vec2(at.x(), at.y()), Vec2(0, 1)) < 2) continue;
    // The piece just above the sliding surface at the cut.
    if (!geometry::containsPoint(piece, at, 1e3 * tol)) continue;
    return geometry::containsPoint(piece, crown, 1e3 * tol);
  }
  return false;
}

/// A section's lines from left to right as the slope facing +x would have them: x negated.
Vec2 flipped(const Vec2& p) { return {-p.x(), p.y()}; }
std::vector<Vec2> flippedLine(const std::vector<Vec2>& line) {
  std::vector<Vec2> out;
  for (auto it = line.rbegin(); it != line.rend(); ++it) out.push_back(flipped(*it));
  return out;
}

/// The section mirrored in x = 0: a slope facing −x becomes one facing +x, which is the way the
/// cut below reads a section (the crown first, "up the slope" towards −x).
SectionSpec mirroredSpec(const SectionSpec& s) {
  SectionSpec m = s;
  m.ground = flippedLine(s.ground);
  m.slidingSurface = flippedLine(s.slidingSurface);
  for (auto& [a, b] : m.joints) a = flipped(a), b = flipped(b);
  for (JointSet& js : m.jointSets) js.angleDeg = 180 - js.angleDeg, js.origin = flipped(js.origin);
  if (m.tensionCrack) m.tensionCrack->x = -m.tensionCrack->x;
  return m;
}

/// How large the section is, and the tolerance its points are compared with.
struct Extent {
  double size = 0, tol = 0, lowest = 0, highest = 0;
};

/// The section's lines checked (each message names its JSON path), and their extent.
Extent checkLines(const SectionSpec& s) {
  if (s.ground.size() < 2) fail("ground", "expected at least two points");
  if (s.joints.size() > static_cast<size_t>(limits::kMaxBlocks))
    fail("joints", "expected at most " + std::to_string(limits::kMaxBlocks) + " joints");
  for (size_t i = 1; i < s.ground.size(); ++i)
    if (s.ground[i].x() < s.ground[i - 1].x()) {
      std::ostringstream m;
      m << "expected x non-decreasing along the ground, found x = " << s.ground[i].x() << " after " << s.ground[i - 1].x();
      fail("ground[" + std::to_string(i) + "]", m.str());
    }
  if (s.slidingSurface.size() < 2) fail("sliding_surface", "expected at least two points");
  for (size_t i = 1; i < s.slidingSurface.size(); ++i)
    if (s.slidingSurface[i].x() <= s.slidingSurface[i - 1].x()) {
      std::ostringstream m;
      m << "expected x increasing along the sliding surface, found x = " << s.slidingSurface[i].x() << " after "
        << s.slidingSurface[i - 1].x();
      fail("sliding_surface[" + std::to_string(i) + "]", m.str());
    }
  const Vec2 crown = s.slidingSurface.front(), toe = s.slidingSurface.back();
  if (crown.x() < s.ground.front().x() || toe.x() > s.ground.back().x())
    fail("sliding_surface", "expected the sliding surface within the ground's x range");
  double size = 0, lowest = INFINITY, highest = -INFINITY;
  for (const Vec2& p : s.ground) lowest = std::min(lowest, p.y()), highest = std::max(highest, p.y());
  for (const Vec2& p : s.slidingSurface) lowest = std::min(lowest, p.y()), highest = std::max(highest, p.y());
  size = std::max(s.ground.back().x() - s.ground.front().x(), highest - lowest);
  const double tol = 1e-9 * size;
  // Crown and toe on the ground: a digitised section may miss it by a little, which the mass and
  // base absorb; farther off, they would invent or remove rock (a face redrawn through the toe).
  const double offGround = 1e-3 * size;
  for (const size_t i : {size_t{0}, s.slidingSurface.size() - 1}) {
    const Vec2 p = s.slidingSurface[i];
    double nearest = INFINITY;
    for (size_t k = 0; k + 1 < s.ground.size(); ++k)
      nearest = std::min(nearest, geometry::distanceToSegment(p, s.ground[k], s.ground[k + 1], nullptr));
    if (nearest > offGround) {
      std::ostringstream m;
      m << "expected the sliding surface's " << (i == 0 ? "first" : "last") << " point, an end of the slide, on the ground (within " << offGround
        << " m, 1e-3 of the section's size); (" << p.x() << ", " << p.y() << ") is " << nearest
        << " m from it, the ground at x = " << p.x() << " being at y = " << groundAt(s.ground, p.x())
        << " m. Draw the sliding surface's ends on the ground line";
      fail("sliding_surface[" + std::to_string(i) + "]", m.str());
    }
  }
  for (size_t i = 1; i + 1 < s.slidingSurface.size(); ++i)
    if (s.slidingSurface[i].y() >= groundAt(s.ground, s.slidingSurface[i].x()) - tol)
      fail("sliding_surface[" + std::to_string(i) + "]", "expected the sliding surface below the ground between crown and toe");
  // Everywhere between crown and toe (at every vertex of either line and midway between them) the
  // sliding surface runs below the ground; crown and toe may touch it.
  std::vector<double> xs;
  for (const Vec2& p : s.ground) xs.push_back(p.x());
  for (const Vec2& p : s.slidingSurface) xs.push_back(p.x());
  std::sort(xs.begin(), xs.end());
  const size_t vertexCount = xs.size();
  for (size_t i = 0; i + 1 < vertexCount; ++i) xs.push_back(0.5 * (xs[i] + xs[i + 1]));
  for (const double x : xs)
    if (x > crown.x() + tol && x < toe.x() - tol && groundAt(s.slidingSurface, x) >= groundAt(s.ground, x) - tol) {
      std::ostringstream m;
      m << "expected the sliding surface below the ground between crown and toe; at x = " << x << " m it is at "
        << groundAt(s.slidingSurface, x) << " m, the ground at " << groundAt(s.ground, x) << " m";
      fail("sliding_surface", m.str());
    }
  if (!(s.baseDepth > 0)) fail("base_depth", "expected a depth > 0 m");

  return {size, tol, lowest, highest};
}

/// The slide mass (ground from crown to toe, back along the slide's surface) and the base below
/// (the ground outside the slide, the base's surface). The two surfaces are the sliding surface,
/// or with a tension crack, each begins with its wall of the crack.
std::pair<std::vector<Vec2>, std::vector<Vec2>> massAndBase(const SectionSpec& s, const Extent& e,
                                                            const std::vector<Vec2>& slideSurface,
                                                            const std::vector<Vec2>& baseSurface) {
  const double tol = e.tol, lowest = e.lowest;
  const Vec2 crown = slideSurface.front(), toe = slideSurface.back(), baseCrown = baseSurface.front();
  const double crownAt = positionOnPolyline(s.ground, crown, tol), toeAt = positionOnPolyline(s.ground, toe, tol);
  const double baseCrownAt = positionOnPolyline(s.ground, baseCrown, tol);
  const auto betweenCrownAndToe = [&](size_t i) {
    return groundVertexAfter(s.ground, i, crown, crownAt, tol) && groundVertexBefore(s.ground, i, toe, toeAt, tol);
  };

  // Slide mass: the ground from crown to toe, back along the sliding surface.
  std::vector<Vec2> mass{crown};
  for (size_t i = 0; i < s.ground.size(); ++i)
    if (betweenCrownAndToe(i)) mass.push_back(s.ground[i]);
  for (size_t i = slideSurface.size(); i-- > 1;) mass.push_back(slideSurface[i]);
  mass = geometry::cleanPolygon(mass, tol);
  if (mass.size() < 3 || !geometry::isSimple(mass)) fail("sliding_surface", "the slide mass between ground and sliding surface is not a simple polygon");

  // Base: the ground outside the slide, the sliding surface, and a bottom baseDepth below.
  const double bottom = lowest - s.baseDepth;
  std::vector<Vec2> base;
  for (size_t i = 0; i < s.ground.size(); ++i)
    if (groundVertexBefore(s.ground, i, baseCrown, baseCrownAt, tol)) base.push_back(s.ground[i]);
  for (const Vec2& p : baseSurface) base.push_back(p);
  for (size_t i = 0; i < s.ground.size(); ++i)
    if (groundVertexAfter(s.ground, i, toe, toeAt, tol)) base.push_back(s.ground[i]);
  base.push_back({s.ground.back().x(), bottom});
  base.push_back({s.ground.front().x(), bottom});
  base = geometry::cleanPolygon(base, tol);
  if (base.size() < 3 || !geometry::isSimple(base)) fail("ground", "the base below the ground and sliding surface is not a simple polygon");

  return {mass, base};
}

/// Internal joints, single and in sets, cut the mass's pieces.
void cutByJoints(std::vector<std::vector<Vec2>>& pieces, const SectionSpec& s, const Extent& e,
                 const std::vector<Vec2>& mass) {
  const double tol = e.tol, size = e.size;
  const double minArea = 1e-9 * size * size;
  for (size_t i = 0; i < s.joints.size(); ++i) {
    const Vec2 d = s.joints[i].second - s.joints[i].first;
    if (d.norm() <= tol) fail("joints[" + std::to_string(i) + "]", "expected two distinct points");
    cutAll(pieces, s.joints[i].first, d, "joints[" + std::to_string(i) + "]", minArea);
  }
  const geometry::Aabb box = geometry::boundingBox(mass);
  // Each set's lines multiply the pieces at most by their number plus one: refuse before cutting
  // what would exceed the block limit (a spacing of 1 cm across a 500 m slide).
  double pieceBound = static_cast<double>(s.joints.size() + 1);
  for (size_t i = 0; i < s.jointSets.size(); ++i) {
    const JointSet& js = s.jointSets[i];
    const std::string path = "joint_sets[" + std::to_string(i) + "]";
    if (!(js.spacing > 0)) fail(path + ".spacing", "expected a spacing > 0 m");
    const double a = degToRad(js.angleDeg);
    const Vec2 d(std::cos(a), std::sin(a)), n(-d.y(), d.x());
    // Offsets (along n) of the lines that can cross the mass's bounding box.
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec2& c : {box.lo, box.hi, Vec2(box.lo.x(), box.hi.y()), Vec2(box.hi.x(), box.lo.y())}) {
      const double o = n.dot(c - js.origin);
      lo = std::min(lo, o), hi = std::max(hi, o);
    }
    const double lines = std::floor(hi / js.spacing) - std::ceil(lo / js.spacing) + 1;
    pieceBound *= std::max(lines, 0.0) + 1;
    if (pieceBound > limits::kMaxBlocks) {
      std::ostringstream m;
      m << "this spacing (" << js.spacing << " m) would cut the slide mass into up to " << pieceBound
        << " blocks; at most " << limits::kMaxBlocks << " are allowed";
      fail(path + ".spacing", m.str());
    }
    const long first = static_cast<long>(std::ceil(lo / js.spacing)), last = static_cast<long>(std::floor(hi / js.spacing));
    for (long k = first; k <= last; ++k) cutAll(pieces, js.origin + (k * js.spacing) * n, d, path, minArea);
  }
}

/// A thin block up the slope of each concave kink: a block whose corner sits on a kink leans on
/// it with a force its width sets, which slices do not have (docs/calibration.md).
void cutKinkBlocks(std::vector<std::vector<Vec2>>& pieces, const SectionSpec& s, const Extent& e) {
  const double tol = e.tol, lowest = e.lowest, highest = e.highest, minArea = 1e-9 * e.size * e.size;
  const Vec2 crown = s.slidingSurface.front();
  if (!s.kinkBlockAuto && s.kinkBlockWidth < 0) fail("kink_block_width", "expected a width >= 0 m");
  // Not given: a width chosen by measurement (docs/research/kink-blocks.md), at least twice the
  // failure displacement, or the slide squeezes the block out while it settles.
  const double w0 = 0.5 * std::max(s.ground.back().x() - s.ground.front().x(), highest - lowest + s.baseDepth);
  const double width = s.kinkBlockAuto ? std::max(5e-3 * w0, 2 * (s.failureDisplacement > 0 ? s.failureDisplacement : 1e-3 * w0))
                                       : s.kinkBlockWidth;
  if (width > 0)
    for (const Vec2& k : concaveKinks(s.slidingSurface)) {
      const Vec2 at(k.x() - width, groundAt(s.slidingSurface, k.x() - width));
      // A joint already within half the width of the cut makes a block about that wide there; a
      // second cut beside it would leave a sliver (and hold every step to a tenth of it).
      if (distanceToNearestJoint(s, at) < 0.5 * width) continue;
      if (s.kinkBlockAuto) {
        // An inclined joint ending on the kink is the slope's own geometry (a bilinear slab's
        // release, which the reader moves off the bend: model/kinks.hpp): a vertical kink block
        // there would make another block system.
        if (inclinedJointThrough(s, k, tol)) continue;
        // Nor at a head scarp: a crown piece with no other joint would decide the verdict alone.
        if (crownPieceAbove(pieces, at, crown, tol)) continue;
        // Nor where the surface rises beyond the bend (a basin's far side): that is a buttress of
        // the slope's own, not a corner the cut put there.
        const auto next = std::find_if(s.slidingSurface.begin(), s.slidingSurface.end(),
                                       [&](const Vec2& p) { return p.x() > k.x() + tol; });
        if (next != s.slidingSurface.end() && next->y() > k.y() + tol) continue;
      }
      cutAll(pieces, Vec2(at.x(), k.y()), Vec2(0, 1), "kink_block_width", minArea);
    }
}

}  // namespace

bool facesMinusX(const SectionSpec& s) {
  return s.slidingSurface.size() >= 2 && s.slidingSurface.front().y() < s.slidingSurface.back().y();
}

double crackPositionAtDepth(const SectionSpec& s, double depth) {
  if (facesMinusX(s)) return -crackPositionAtDepth(mirroredSpec(s), depth);
  const Vec2 crown = s.slidingSurface.front(), toe = s.slidingSurface.back();
  const auto excess = [&](double x) { return groundAt(s.ground, x) - groundAt(s.slidingSurface, x) - depth; };
  // The first sign change on a fine scan from the crown, then bisection.
  const int n = 2000;
  double a = crown.x();
  for (int k = 1; k <= n; ++k) {
    double b = crown.x() + (toe.x() - crown.x()) * k / n;
    if (excess(a) < 0 && excess(b) >= 0) {
      for (int i = 0; i < 100; ++i) {
        const double m = 0.5 * (a + b);
        if (excess(m) < 0) a = m;
        else b = m;
      }
      return 0.5 * (a + b);
    }
    a = b;
  }
  return NAN;
}

std::vector<Vec2> crackWaterLine(const CrackGeometry& c, const std::vector<Vec2>& ground) {
  if (c.toe.x() < c.x) {  // a slope facing −x: its line is the mirrored slope's, mirrored back
    CrackGeometry m = c;
    m.x = -c.x;
    m.toe = flipped(c.toe);
    return flippedLine(crackWaterLine(m, flippedLine(ground)));
  }
  const Vec2 from(c.x, c.bottom + c.waterDepth()), to = c.toe;
  std::vector<double> xs{from.x(), to.x()};
  for (const Vec2& p : ground)
    if (p.x() > from.x() && p.x() < to.x()) xs.push_back(p.x());
  std::sort(xs.begin(), xs.end());
  std::vector<Vec2> line;
  for (const double x : xs) {
    const double straight = from.y() + (to.y() - from.y()) * (x - from.x()) / (to.x() - from.x());
    if (line.empty() || x > line.back().x()) line.emplace_back(x, std::min(straight, groundAt(ground, x)));
  }
  return line;
}

namespace {

/// Open by a thousandth of the model's half size: far beyond the contacts' initial tolerance
/// (1e-6 of it), so the crack carries its water and nothing else.
double crackGap(const SectionSpec& s, const Extent& e) {
  return 1e-3 * 0.5 * std::max(s.ground.back().x() - s.ground.front().x(), e.highest - e.lowest + s.baseDepth);
}

/// The crack's walls: the slide's at x (the slide surface starts at its top and goes down it to
/// the sliding surface), the base's a gap behind. Checked against the section (paths relative to
/// the section object).
CrackGeometry cutCrack(const SectionSpec& s, const Extent& e, std::vector<Vec2>& slideSurface,
                       std::vector<Vec2>& baseSurface) {
  const TensionCrack& t = *s.tensionCrack;
  const Vec2 crown = s.slidingSurface.front(), toe = s.slidingSurface.back();
  CrackGeometry c;
  c.gap = crackGap(s, e);
  c.x = t.x;
  c.toe = toe;
  c.waterFraction = t.waterFraction;
  c.placedByDepth = t.placedByDepth;
  if (!(t.x > crown.x() + c.gap && t.x < toe.x())) {
    std::ostringstream m;
    m << "expected x between the crown (" << crown.x() << " m, plus the crack's width " << c.gap << " m) and the toe ("
      << toe.x() << " m), found " << t.x;
    fail("tension_crack.x", m.str());
  }
  c.top = groundAt(s.ground, t.x);
  c.bottom = groundAt(s.slidingSurface, t.x);
  if (!(c.depth() > e.tol)) fail("tension_crack.x", "the ground and the sliding surface meet there: no crack to cut");
  const double wall = t.x - c.gap;
  const auto after = [&](double x) {
    std::vector<Vec2> v;
    for (const Vec2& p : s.slidingSurface)
      if (p.x() > x + e.tol) v.push_back(p);
    return v;
  };
  slideSurface = {Vec2(t.x, c.top), Vec2(t.x, c.bottom)};
  for (const Vec2& p : after(t.x)) slideSurface.push_back(p);
  baseSurface = {Vec2(wall, groundAt(s.ground, wall)), Vec2(wall, groundAt(s.slidingSurface, wall))};
  for (const Vec2& p : after(wall)) baseSurface.push_back(p);
  return c;
}

}  // namespace

SectionBlocks cutSection(const SectionSpec& given) {
  const Extent e = checkLines(given);
  if (facesMinusX(given)) {
    // The crack's position is checked here, in the case's own coordinates.
    if (given.tensionCrack) {
      const double crown = given.slidingSurface.back().x(), toe = given.slidingSurface.front().x();
      const double gap = crackGap(given, e), x = given.tensionCrack->x;
      if (!(x < crown - gap && x > toe)) {
        std::ostringstream m;
        m << "expected x between the toe (" << toe << " m) and the crown (" << crown << " m, less the crack's width " << gap
          << " m), found " << x;
        fail("tension_crack.x", m.str());
      }
    }
    SectionBlocks m = cutSection(mirroredSpec(given));
    const auto back = [](const Block& b) { return makeBlock(b.id, b.fixed, flippedLine(b.vertices)); };
    SectionBlocks out;
    out.base = back(m.base);
    for (const Block& b : m.slide) out.slide.push_back(back(b));
    std::sort(out.slide.begin(), out.slide.end(),
              [](const Block& a, const Block& b) { return a.moments.centroid.x() < b.moments.centroid.x(); });
    for (size_t k = 0; k < out.slide.size(); ++k) out.slide[k].id = "slide_" + std::to_string(k + 1);
    if (m.crack) {
      out.crack = m.crack;
      out.crack->x = -m.crack->x;
      out.crack->toe = flipped(m.crack->toe);
    }
    return out;
  }
  SectionSpec s = given;
  std::vector<Vec2> slideSurface = s.slidingSurface, baseSurface = s.slidingSurface;
  std::optional<CrackGeometry> crack;
  if (s.tensionCrack) {
    crack = cutCrack(s, e, slideSurface, baseSurface);
    // The sliding surface the slide rests on: from the crack's bottom to the toe (its kinks).
    s.slidingSurface.assign(slideSurface.begin() + 1, slideSurface.end());
  }
  const auto [mass, base] = massAndBase(s, e, slideSurface, baseSurface);
  std::vector<std::vector<Vec2>> pieces{mass};
  cutByJoints(pieces, s, e, mass);
  cutKinkBlocks(pieces, s, e);
  std::sort(pieces.begin(), pieces.end(), [](const auto& p, const auto& q) {
    return geometry::computeMoments(p).centroid.x() < geometry::computeMoments(q).centroid.x();
  });
  SectionBlocks out;
  out.base = makeBlock("base", true, base);
  for (size_t k = 0; k < pieces.size(); ++k) out.slide.push_back(makeBlock("slide_" + std::to_string(k + 1), false, pieces[k]));
  out.crack = crack;
  return out;
}

}  // namespace ddaslope::model
