// Polygon moments and predicates against exact values.
#include <gtest/gtest.h>

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
