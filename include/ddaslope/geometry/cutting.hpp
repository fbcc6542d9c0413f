#pragma once
// Cutting polygons by straight lines (pure geometry for building blocks from a slope section).
#include <utility>
#include <vector>

#include "ddaslope/core/types.hpp"

namespace ddaslope::geometry {

/// The part of polygon `pts` on the left of the directed line through p along d (Sutherland-
/// Hodgman against one half-plane), with repeated and collinear vertices removed. Empty if the
/// polygon lies wholly on the right.
std::vector<Vec2> clipToLeft(const std::vector<Vec2>& pts, const Vec2& p, const Vec2& d);

/// How many times the polygon's boundary crosses the line (0 when it misses; 2 when the line cuts
/// it into two pieces; more when a non-convex polygon would fall into more than two).
int lineCrossings(const std::vector<Vec2>& pts, const Vec2& p, const Vec2& d);

/// Removes repeated vertices (closer than tol) and vertices on a straight line between their
/// neighbours.
std::vector<Vec2> cleanPolygon(std::vector<Vec2> pts, double tol);

}  // namespace ddaslope::geometry
