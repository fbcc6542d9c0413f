#pragma once
// Blocks cut out of joint lines: the bounded faces of the planar arrangement of line segments,
// as Shi's block-cutting (DC) phase makes them. A model of Shi's DDA (ntdda) stores its joint
// lines, never its blocks, so reading one means cutting the blocks again.
#include <vector>

#include "ddaslope/core/types.hpp"

namespace ddaslope::geometry {

/// A joint line and its joint type (ntdda's 1-based type number).
struct TypedSegment {
  Vec2 a{0, 0}, b{0, 0};
  int type = 1;
};

/// One edge of the arrangement that bounds a kept face, with the faces on either side.
struct ArrangementEdge {
  int left = -1, right = -1;  ///< indices into LineArrangement::faces; −1 outside every kept face
  int type = 1;               ///< the joint type of the line it lies on
  double length = 0;
};

struct LineArrangement {
  /// The blocks: simple polygons, counter-clockwise, starting at their lowest (then leftmost)
  /// vertex, vertices on a straight edge removed; ordered by centroid, bottom row first.
  std::vector<std::vector<Vec2>> faces;
  std::vector<ArrangementEdge> edges;
  int mergedNodes = 0;      ///< nodes merged into a neighbour within the merge distance
  int danglingEdges = 0;    ///< edges that bounded no face (line ends past the last crossing, lone lines)
  int bridgeEdges = 0;      ///< edges with the same face on both sides (a line joining two closed loops)
  int typeConflicts = 0;    ///< edges where lines of different types overlap (the first line's type is kept)
  int holedFaces = 0;       ///< faces dropped because other lines lie inside them, untouched
  int pinchedFaces = 0;     ///< faces dropped because their boundary touches itself
};

/// Splits the segments at every crossing and at every end lying on another segment (a
/// T-junction), merges nodes closer than `mergeDistance` (m), drops dangling edges until none
/// is left, and traces the bounded faces. Empty faces when the lines close no region.
LineArrangement arrangeLines(const std::vector<TypedSegment>& lines, double mergeDistance);

}  // namespace ddaslope::geometry
