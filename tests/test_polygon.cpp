#include <gtest/gtest.h>
#include "ddaslope/geometry/polygon.hpp"
using namespace ddaslope;
TEST(Polygon, UnitSquareMoments) {
  const auto m = geometry::computeMoments({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_NEAR(m.area, 1.0, 1e-14);
}
