// Polygon moments and predicates against exact values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "ddaslope/geometry/polygon.hpp"

using namespace ddaslope;
using geometry::computeMoments;

// Unit square: area 1, centroid (0.5, 0.5), Sxx = Syy = 1/12, Sxy = 0 (exact; STYLE.md).
TEST(Polygon, UnitSquareMoments) {
  const auto m = computeMoments({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_NEAR(m.area, 1.0, 1e-14);
  EXPECT_NEAR(m.centroid.x(), 0.5, 1e-14);
  EXPECT_NEAR(m.centroid.y(), 0.5, 1e-14);
  EXPECT_NEAR(m.sxx, 1.0 / 12, 1e-14);
  EXPECT_NEAR(m.syy, 1.0 / 12, 1e-14);
  EXPECT_NEAR(m.sxy, 0.0, 1e-14);
}

// Right triangle (0,0),(b,0),(0,h): about its centroid Sxx = b³h/36, Syy = bh³/36,
// Sxy = −b²h²/72 (standard section properties).
TEST(Polygon, RightTriangleCentralMoments) {
  const double b = 3, h = 2;
  const auto m = computeMoments({{0, 0}, {b, 0}, {0, h}});
  EXPECT_NEAR(m.area, b * h / 2, 1e-13);
  EXPECT_NEAR(m.centroid.x(), b / 3, 1e-13);
  EXPECT_NEAR(m.centroid.y(), h / 3, 1e-13);
  EXPECT_NEAR(m.sxx, b * b * b * h / 36, 1e-12);
  EXPECT_NEAR(m.syy, b * h * h * h / 36, 1e-12);
  EXPECT_NEAR(m.sxy, -b * b * h * h / 72, 1e-12);
}

// Moments about the centroid do not depend on where the polygon is: a kilometre-scale offset
// must not cost more than ~1e-9 relative (cancellation guard).
TEST(Polygon, MomentsTranslationInvariant) {
  const auto a = computeMoments({{0, 0}, {2, 0}, {2, 1}, {0, 1}});
  const auto b = computeMoments({{1e5, 2e5}, {1e5 + 2, 2e5}, {1e5 + 2, 2e5 + 1}, {1e5, 2e5 + 1}});
  EXPECT_NEAR(a.sxx, b.sxx, 1e-9 * a.sxx);
  EXPECT_NEAR(a.syy, b.syy, 1e-9 * a.syy);
  EXPECT_NEAR(a.area, b.area, 1e-9);
}

TEST(Polygon, OrientationAndSimplicity) {
  std::vector<Vec2> cw{{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  EXPECT_LT(geometry::signedArea(cw), 0);
  geometry::orientCounterClockwise(cw);
  EXPECT_NEAR(geometry::signedArea(cw), 1.0, 1e-15);
  EXPECT_TRUE(geometry::isSimple(cw));
  EXPECT_FALSE(geometry::isSimple({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));    // bow tie
  EXPECT_FALSE(geometry::isSimple({{0, 0}, {1, 0}, {1, 0}, {0, 1}}));    // repeated vertex
  EXPECT_FALSE(geometry::isSimple({{0, 0}, {1, 0}}));                    // too few vertices
}

TEST(Polygon, ContainsPoint) {
  const std::vector<Vec2> sq{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_TRUE(geometry::containsPoint(sq, {0.5, 0.5}, 0));
  EXPECT_TRUE(geometry::containsPoint(sq, {1.0, 0.5}, 1e-12));  // on the boundary
  EXPECT_FALSE(geometry::containsPoint(sq, {1.5, 0.5}, 1e-12));
}

// An outline with vertices on its straight edges (T-junctions, edges split in CAD) is the same
// polygon as its corners alone: they are removed, the corners kept in their order from the first.
TEST(Outline, VerticesOnStraightEdgesAreRemoved) {
  const std::vector<Vec2> corners{{0, 0}, {4, 0}, {4, 2}, {0, 2}};
  std::vector<Vec2> drawn{{0, 0}, {1, 0}, {2.5, 0}, {4, 0}, {4, 1}, {4, 2}, {3, 2}, {0, 2}, {0, 1.2}};
  EXPECT_EQ(geometry::removeCollinearVertices(drawn, 1e-6), 5);
  EXPECT_EQ(drawn, corners);
  // Starting on a vertex of an edge: the outline starts at the first corner kept.
  std::vector<Vec2> fromMid{{2, 0}, {4, 0}, {4, 2}, {0, 2}, {0, 0}};
  EXPECT_EQ(geometry::removeCollinearVertices(fromMid, 1e-6), 1);
  EXPECT_EQ(fromMid, (std::vector<Vec2>{{4, 0}, {4, 2}, {0, 2}, {0, 0}}));
  std::vector<Vec2> plain = corners;
  EXPECT_EQ(geometry::removeCollinearVertices(plain, 1e-6), 0);
  EXPECT_EQ(plain, corners);
}

// The tolerance is against the chord that replaces a run, and far from the origin the test is made
// on differences: a vertex 1e-7 of its 10 m chord off the line goes at 1e-6, one 1e-5 off stays.
TEST(Outline, ToleranceIsRelativeToTheChord) {
  const Vec2 o(5e5, 5e6);
  std::vector<Vec2> slight{o + Vec2(0, 0), o + Vec2(5, -1e-6), o + Vec2(10, 0), o + Vec2(10, 4), o + Vec2(0, 4)};
  EXPECT_EQ(geometry::removeCollinearVertices(slight, 1e-6), 1);
  EXPECT_EQ(slight.size(), 4u);
  std::vector<Vec2> bent{o + Vec2(0, 0), o + Vec2(5, -1e-4), o + Vec2(10, 0), o + Vec2(10, 4), o + Vec2(0, 4)};
  EXPECT_EQ(geometry::removeCollinearVertices(bent, 1e-6), 0);
}

// A gentle arc of 40 segments of 0.2 m, each bending by 2e-6 rad, is not flattened piece by piece:
// one vertex lies 2.5e-7 of its neighbours' chord off it (removable), but a run of m segments sags
// by about m·θ/8 of its chord, so each run is tested against the one chord that replaces it and
// stops at four segments; the whole arc (sag 1e-5 of it) keeps about ten chords.
TEST(Outline, GentleCurveIsNotFlattenedPieceByPiece) {
  std::vector<Vec2> arc;
  const double theta = 2e-6, radius = 1e5;
  for (int k = 0; k <= 40; ++k)
    arc.push_back({radius * std::sin(k * theta), 2 * radius * std::pow(std::sin(k * theta / 2), 2)});
  std::vector<Vec2> outline{{0, -5}, {arc.back().x(), -5}};
  outline.insert(outline.end(), arc.rbegin(), arc.rend());  // the top from right to left
  ASSERT_GT(geometry::signedArea(outline), 0);
  const int removed = geometry::removeCollinearVertices(outline, 1e-6);
  EXPECT_GT(removed, 20);
  EXPECT_GE(outline.size(), 2u + 9u) << "the arc flattened into too few chords";
  // Every vertex of the arc lies within 1e-6 of the chord (at most 0.8 m) that replaced it.
  for (const Vec2& p : arc) {
    double nearest = INFINITY;
    for (size_t k = 0; k < outline.size(); ++k)
      nearest = std::min(nearest, geometry::distanceToSegment(p, outline[k], outline[(k + 1) % outline.size()], nullptr));
    EXPECT_LE(nearest, 1e-6 * 0.8) << "m from the simplified outline";
  }
}

// The region two blocks share, against its area and perimeter drawn by hand.
namespace {
std::vector<Vec2> rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }
}  // namespace

TEST(Overlap, AreaAndPerimeterOfTheSharedRegion) {
  const auto unit = rect(0, 0, 1, 1);
  // Shifted by half a side: a 0.5 × 0.5 square.
  geometry::Overlap o = geometry::overlapOf(unit, rect(0.5, 0.5, 1.5, 1.5), 1e-12);
  EXPECT_NEAR(o.area, 0.25, 1e-12);
  EXPECT_NEAR(o.perimeter, 2.0, 1e-12);
  // Crossed bars, neither with a corner inside the other: the 1 × 1 middle.
  o = geometry::overlapOf(rect(0, 1, 3, 2), rect(1, 0, 2, 3), 1e-12);
  EXPECT_NEAR(o.area, 1.0, 1e-12);
  EXPECT_NEAR(o.perimeter, 4.0, 1e-12);
  // One inside the other, and one drawn twice (coinciding boundaries counted once).
  EXPECT_NEAR(geometry::overlapOf(unit, rect(0.25, 0.25, 0.75, 0.75), 1e-12).area, 0.25, 1e-12);
  EXPECT_NEAR(geometry::overlapOf(rect(0.25, 0.25, 0.75, 0.75), unit, 1e-12).area, 0.25, 1e-12);
  o = geometry::overlapOf(unit, unit, 1e-12);
  EXPECT_NEAR(o.area, 1.0, 1e-12);
  EXPECT_NEAR(o.perimeter, 4.0, 1e-12);
  // A triangle on three of the square's corners, its hypotenuse through the square.
  EXPECT_NEAR(geometry::overlapOf(unit, {{0, 0}, {1, 0}, {1, 1}}, 1e-12).area, 0.5, 1e-12);
}

TEST(Overlap, NeighboursShareNothing) {
  // Along a whole edge, along part of one (a T-junction: two blocks on one), at a corner.
  EXPECT_EQ(geometry::overlapOf(rect(0, 0, 1, 1), rect(1, 0, 2, 1), 1e-12).area, 0);
  EXPECT_EQ(geometry::overlapOf(rect(0, 0, 2, 1), rect(0, 1, 1, 2), 1e-12).area, 0);
  EXPECT_EQ(geometry::overlapOf(rect(0, 0, 2, 1), rect(1, 1, 2, 2), 1e-12).area, 0);
  EXPECT_EQ(geometry::overlapOf(rect(0, 0, 1, 1), rect(1, 1, 2, 2), 1e-12).area, 0);
  // A square in the notch of an L, and a neighbour with an extra vertex on the shared edge.
  const std::vector<Vec2> ell{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  EXPECT_EQ(geometry::overlapOf(ell, rect(1, 1, 2, 2), 1e-12).area, 0);
  EXPECT_EQ(geometry::overlapOf(rect(0, 0, 1, 1), {{1, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 0.5}}, 1e-12).area, 0);
  // Within the tolerance of touching: nothing.
  EXPECT_EQ(geometry::overlapOf(rect(0, 0, 1, 1), rect(1 - 1e-13, 0, 2, 1), 1e-12).area, 0);
}

TEST(Overlap, FarFromTheOriginAsNearIt) {
  const double x = 1e12;
  const geometry::Overlap o = geometry::overlapOf(rect(x, x, x + 1, x + 1), rect(x + 0.5, x + 0.5, x + 1.5, x + 1.5), 1e-9);
  EXPECT_NEAR(o.area, 0.25, 1e-3);  // coordinates resolve 1.2e-4 m at 1e12
  EXPECT_NEAR(o.perimeter, 2.0, 1e-3);
}

// A column on a 20° ground line, as a CAD export writes it: its base split at a vertex, each base
// vertex within 5e-7 m of the line on either side (coordinates to the micrometre), the ground a
// non-convex outline. They share at most slivers of that thickness along the 3.4 m base; the
// same column sunk 5 cm into the ground shares the 5 cm strip (3.4 m × 0.05 m, to the sliver).
TEST(Overlap, ABaseWithinRoundOffOfTheGroundSharesOnlySlivers) {
  const std::vector<Vec2> ground{{-10, -15}, {90, -15}, {90, 23.941409999999905}, {65.77848300000187, 23.941409999999905},
                                 {0, 0}, {-10, 0}};
  std::vector<Vec2> column{{28.190778999996837, 10.260604000000058}, {29.130471333337482, 10.602624333333324},
                           {31.009855999960564, 11.286665000000085}, {27.58965499995975, 20.68359099999998},
                           {24.770576999988407, 19.657531000000063}};
  const double base = (column[2] - column[0]).norm();
  for (const Vec2& shift : {Vec2(0, 0), Vec2(512345.678, 5123456.789)}) {
    std::vector<Vec2> g = ground, c = column;
    for (Vec2& v : g) v += shift;
    for (Vec2& v : c) v += shift;
    const double tol = 1e-9 * 100;  // the case reader's: 1e-9 of the scene
    EXPECT_LT(geometry::overlapOf(g, c, tol).area, base * 1e-6) << shift.transpose();
    EXPECT_LT(geometry::overlapOf(c, g, tol).area, base * 1e-6) << shift.transpose();
    // Sunk 5 cm normal to the 20° line.
    const Vec2 down = 0.05 * Vec2(std::sin(degToRad(20)), -std::cos(degToRad(20)));
    std::vector<Vec2> sunk = c;
    for (Vec2& v : sunk) v += down;
    EXPECT_NEAR(geometry::overlapOf(g, sunk, tol).area, base * 0.05, base * 1e-5) << shift.transpose();
  }
}
