#include "ddaslope/model/kinks.hpp"

#include <algorithm>
#include <cmath>

#include "ddaslope/geometry/polygon.hpp"

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

namespace {

/// Index of the vertex of v within tol of p, or −1.
int vertexAt(const std::vector<Vec2>& v, const Vec2& p, double tol) {
  for (size_t k = 0; k < v.size(); ++k)
    if ((v[k] - p).norm() <= tol) return static_cast<int>(k);
  return -1;
}

/// Whether unit directions a and b are the same within 1e-6 rad.
bool along(const Vec2& a, const Vec2& b) { return a.dot(b) > 0 && std::abs(cross(a, b)) <= 1e-6; }

struct JointOnBend {
  int upper = -1, lower = -1;  // block indices
  Vec2 other{0, 0};            // the joint's other end
};

/// The two free blocks that meet at `kink` across a joint, the one on the upper face first; none
/// unless exactly two free blocks have a vertex there, share an edge from it, and lie one along
/// each face.
JointOnBend jointOnBend(const Scene& scene, const Vec2& kink, const Vec2& upFace, const Vec2& lowFace, double tol) {
  std::vector<int> here;
  for (size_t b = 0; b < scene.blocks.size(); ++b)
    if (!scene.blocks[b].fixed && vertexAt(scene.blocks[b].vertices, kink, tol) >= 0) here.push_back(static_cast<int>(b));
  if (here.size() != 2) return {};
  const auto neighbours = [&](int b) {
    const std::vector<Vec2>& v = scene.blocks[static_cast<size_t>(b)].vertices;
    const size_t n = v.size(), k = static_cast<size_t>(vertexAt(v, kink, tol));
    return std::pair{v[(k + n - 1) % n], v[(k + 1) % n]};
  };
  const auto [a0, a1] = neighbours(here[0]);
  const auto [b0, b1] = neighbours(here[1]);
  // The shared edge: a neighbour of the kink in both blocks; each block's other edge along a face.
  for (const auto& [q, aFace] : {std::pair{a0, a1}, std::pair{a1, a0}})
    for (const auto& [r, bFace] : {std::pair{b0, b1}, std::pair{b1, b0}}) {
      if ((q - r).norm() > tol) continue;
      const Vec2 da = (aFace - kink).normalized(), db = (bFace - kink).normalized();
      if (along(da, upFace) && along(db, lowFace)) return {here[0], here[1], q};
      if (along(db, upFace) && along(da, lowFace)) return {here[1], here[0], q};
    }
  return {};
}

/// Replaces the vertex at `from` by `to`.
void moveVertex(std::vector<Vec2>& v, const Vec2& from, const Vec2& to, double tol) {
  const int k = vertexAt(v, from, tol);
  if (k >= 0) v[static_cast<size_t>(k)] = to;
}

/// Inserts p on the edge between the vertices at a and b (cyclically: before the later one).
void insertBetween(std::vector<Vec2>& v, const Vec2& a, const Vec2& b, const Vec2& p, double tol) {
  const size_t n = v.size();
  const int ka = vertexAt(v, a, tol), kb = vertexAt(v, b, tol);
  if (ka < 0 || kb < 0) return;
  if (static_cast<size_t>(kb) == (static_cast<size_t>(ka) + 1) % n) v.insert(v.begin() + kb, p);
  else if (static_cast<size_t>(ka) == (static_cast<size_t>(kb) + 1) % n) v.insert(v.begin() + ka, p);
}

}  // namespace

std::vector<MovedJointEnd> moveJointEndsOffBends(Scene& scene, double offset) {
  std::vector<MovedJointEnd> moved;
  if (!(offset > 0)) return moved;
  const double tol = 1e-6 * scene.modelHalfSize();
  const Vec2 down = scene.gravity.norm() > 0 ? Vec2(scene.gravity.normalized()) : Vec2(0, -1);
  for (const ConcaveKink& k : concaveKinksUnderBlocks(scene)) {
    if (k.blocksWithCorner != 2) continue;
    const std::vector<Vec2>& f = scene.blocks[static_cast<size_t>(k.fixedBlock)].vertices;
    const size_t n = f.size(), i = static_cast<size_t>(vertexAt(f, k.point, tol));
    const Vec2 prev = f[(i + n - 1) % n], next = f[(i + 1) % n];
    // The upper face rises more steeply from the kink (against gravity).
    const bool prevUp = (prev - k.point).normalized().dot(-down) > (next - k.point).normalized().dot(-down);
    const Vec2 upEnd = prevUp ? prev : next, lowEnd = prevUp ? next : prev;
    const Vec2 up = (upEnd - k.point).normalized(), low = (lowEnd - k.point).normalized();
    const JointOnBend j = jointOnBend(scene, k.point, up, low, tol);
    if (j.upper < 0) continue;
    const Vec2 joint = j.other - k.point;
    if (std::abs(cross(joint.normalized(), down)) <= std::sin(degToRad(10))) continue;  // a kink block's cut
    Block& A = scene.blocks[static_cast<size_t>(j.upper)];
    Block& B = scene.blocks[static_cast<size_t>(j.lower)];
    // How far along the upper face A's edge and the fixed block's edge run from the kink.
    const std::vector<Vec2>& av = A.vertices;
    const size_t an = av.size(), ak = static_cast<size_t>(vertexAt(av, k.point, tol));
    const Vec2 aPrev = av[(ak + an - 1) % an], aNext = av[(ak + 1) % an];
    const Vec2 aFaceEnd = (aPrev - j.other).norm() <= tol ? aNext : aPrev;
    double delta = std::min({offset, 0.25 * (aFaceEnd - k.point).norm(), 0.25 * (upEnd - k.point).norm(),
                             0.25 * joint.norm()});
    // The joint's other end slides along the straight outline it lies on, if only A and B meet
    // there; else the joint turns about it.
    Vec2 otherMoved = j.other;
    bool parallel = false;
    int blocksAtOther = 0;
    for (const Block& b : scene.blocks) blocksAtOther += vertexAt(b.vertices, j.other, tol) >= 0;
    const int qa = vertexAt(av, j.other, tol);
    const int qb = vertexAt(B.vertices, j.other, tol);
    if (blocksAtOther == 2 && qa >= 0 && qb >= 0) {
      const size_t bn = B.vertices.size();
      const auto beyond = [&](const std::vector<Vec2>& v, size_t q, size_t m) {
        const Vec2 p0 = v[(q + m - 1) % m], p1 = v[(q + 1) % m];
        return (p0 - k.point).norm() <= tol || (p0 - j.other).norm() <= tol ? p1 : p0;
      };
      const Vec2 aBeyond = beyond(av, static_cast<size_t>(qa), an);
      const Vec2 bBeyond = beyond(B.vertices, static_cast<size_t>(qb), bn);
      const Vec2 ta = (aBeyond - j.other).normalized(), tb = (bBeyond - j.other).normalized();
      const Vec2 dj = joint.normalized();
      if (along(ta, -tb) && std::abs(cross(dj, ta)) > 0.1) {
        // K' + s dj = Q + r ta
        const Vec2 kMoved = k.point + delta * up;
        const double r = cross(kMoved - j.other, dj) / cross(ta, dj);
        if (r > 0 && r < 0.25 * (aBeyond - j.other).norm()) otherMoved = j.other + r * ta, parallel = true;
      }
    }
    if (!parallel) delta = std::min(delta, 0.05 * joint.norm());
    const Vec2 kMoved = k.point + delta * up;
    std::vector<Vec2> a = A.vertices, b = B.vertices;
    moveVertex(a, j.other, otherMoved, tol);
    moveVertex(a, k.point, kMoved, tol);
    moveVertex(b, j.other, otherMoved, tol);
    insertBetween(b, k.point, otherMoved, kMoved, tol);
    if (b.size() != B.vertices.size() + 1 || !geometry::isSimple(a) || !geometry::isSimple(b) ||
        !(geometry::signedArea(a) > 0) || !(geometry::signedArea(b) > 0))
      continue;
    A.vertices = std::move(a);
    B.vertices = std::move(b);
    A.moments = geometry::computeMoments(A.vertices);
    B.moments = geometry::computeMoments(B.vertices);
    moved.push_back({k.fixedBlock, j.upper, j.lower, k.point, delta * up, parallel});
  }
  return moved;
}

}  // namespace ddaslope::model
