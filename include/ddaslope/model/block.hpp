#pragma once
// A DDA block: a simple polygon with six unknowns about its centroid (Shi 1988).
#include <string>
#include <vector>

#include "ddaslope/core/types.hpp"
#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::model {

/// T(x, y) of Shi (1988): displacement of point p of a block with centroid c is T · D.
Mat26 displacementMatrix(const Vec2& centroid, const Vec2& p);
/// New position of p after displacement D, with the rigid rotation applied exactly
/// (cos r0, sin r0) so that rotating blocks do not grow (dda-method.md §3).
Vec2 displacedPoint(const Vec2& centroid, const Vec2& p, const Vec6& d);

/// A vertex within this fraction of its chord's length of the straight line between its neighbours
/// is not a corner: the reader removes it (geometry::removeCollinearVertices). A block's
/// displacement is affine (first-order DDA), so such a vertex stays on that line, carries no
/// unknown, mass or load of its own, and would only split one face into two contacts.
constexpr double kCollinearTolerance = 1e-6;

struct Block {
  std::string id;
  int material = 0;
  bool fixed = false;
  std::vector<Vec2> vertices;           ///< current, counter-clockwise
  geometry::PolygonMoments moments;     ///< current
  Vec6 velocity = Vec6::Zero();         ///< dD/dt at the end of the last step
  Vec3 stress = Vec3::Zero();           ///< σx, σy, τxy accumulated (Pa)
  /// r0 summed over every displacement applied (rad, counter-clockwise): the rotation from the
  /// case's geometry, which the vertices alone cannot tell past a half turn (outputs only).
  double rotation = 0;
  /// Vertices on a straight edge that the reader removed (kCollinearTolerance), for `check`.
  int removedCollinearVertices = 0;
  /// Fixed blocks of the case that the reader merged into this one (their ids), for `check`.
  std::vector<std::string> mergedIds;

  Mat26 tAt(const Vec2& p) const { return displacementMatrix(moments.centroid, p); }
  /// Moves the vertices by D (exact rotation), recomputes the moments and adds r0 to rotation.
  void applyDisplacement(const Vec6& d);
  /// Largest vertex displacement |T D| over the block's vertices (linearised).
  double maxVertexDisplacement(const Vec6& d) const;
  /// A bound never below maxVertexDisplacement(d), its round-off included, from the vertices'
  /// largest offsets from the centroid along x and y: a few operations per vertex instead of a
  /// 2 × 6 product and a square root, so that a step limit is checked exactly only where the
  /// bound does not clear it.
  double vertexDisplacementBound(const Vec6& d) const;
};

}  // namespace ddaslope::model
