#pragma once
// Pure polygon geometry: moments by simplex integration, orientation, simplicity.
#include <optional>
#include <vector>

#include "ddaslope/core/types.hpp"

namespace ddaslope::geometry {

/// Area moments of a polygon. Second moments are taken about the centroid, so the
/// first moments vanish (Shi 1988, simplex integration over a triangle fan: exact).
struct PolygonMoments {
  double area = 0;   ///< S = ∫ dA (m²), positive for counter-clockwise vertices
  Vec2 centroid{0, 0};
  double sxx = 0;    ///< ∫ (x − x0)² dA
  double syy = 0;    ///< ∫ (y − y0)² dA
  double sxy = 0;    ///< ∫ (x − x0)(y − y0) dA
};

struct Aabb {
  Vec2 lo{0, 0};
  Vec2 hi{0, 0};
};

/// Signed area: positive for counter-clockwise order.
double signedArea(const std::vector<Vec2>& pts);
/// Moments of a counter-clockwise polygon (area positive).
PolygonMoments computeMoments(const std::vector<Vec2>& pts);
/// True when no two non-adjacent edges touch and no two consecutive vertices coincide.
bool isSimple(const std::vector<Vec2>& pts);
/// Why an outline is not simple, at the first place isSimple finds: vertices `first` and `second`
/// repeated, the edges from them crossing, or the outline folded back at vertex `first`.
struct SimplicityDefect {
  enum class Kind { RepeatedVertex, CrossingEdges, Fold } kind;
  size_t first = 0, second = 0;
};
std::optional<SimplicityDefect> simplicityDefect(const std::vector<Vec2>& pts);
/// Removes every vertex that lies on the straight line between the vertices kept on either side
/// of it, within `relativeTolerance` of that chord's length or within `absoluteTolerance` (m),
/// whichever is larger (a run of such vertices is tested against the one chord that replaces it,
/// so a gentle curve is not flattened piece by piece). Returns how many were removed. The polygon
/// must be simple, with at least three corners.
int removeCollinearVertices(std::vector<Vec2>& pts, double relativeTolerance, double absoluteTolerance = 0);
/// Inserts, in order along each edge, every point of `points` that lies on the edge (within `tol`
/// of it, not within `tol` of its ends): the vertices a neighbour's corners make on it. Returns
/// how many were inserted.
int insertPointsOnEdges(std::vector<Vec2>& pts, const std::vector<Vec2>& points, double tol);
/// The union of two counter-clockwise polygons that share a stretch of boundary (edges that
/// coincide vertex for vertex, within `tol`, run in opposite directions) and do not overlap: one
/// simple polygon of area a + b, or empty if they share no edge or the union is not such a polygon
/// (it would have a hole, or they touch elsewhere).
std::vector<Vec2> unionAlongSharedEdges(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tol);
/// Reverses the order if needed so that the signed area is positive.
void orientCounterClockwise(std::vector<Vec2>& pts);
/// Point in polygon (boundary counts as inside within tol).
bool containsPoint(const std::vector<Vec2>& pts, const Vec2& p, double tol);
Aabb boundingBox(const std::vector<Vec2>& pts);
/// Sum of the edge lengths of the closed polygon.
double perimeter(const std::vector<Vec2>& pts);
/// Distance from p to segment ab and the parameter t ∈ [0,1] of the closest point.
double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b, double* t);
/// The region two polygons share.
struct Overlap {
  double area = 0;       ///< m²; 0 when they meet only along their boundaries
  double perimeter = 0;  ///< m, of the shared region
  Vec2 point{0, 0};      ///< a point on the shared region's boundary (where to look)
};
/// The region two counter-clockwise simple polygons share, by Green's theorem over the parts of
/// each boundary inside the other. A boundary point within `tol` (m) of the other's boundary lies
/// on it: neighbours along a common edge share nothing.
Overlap overlapOf(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tol);
/// True when segments ab and cd share a point.
bool segmentsIntersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

}  // namespace ddaslope::geometry
