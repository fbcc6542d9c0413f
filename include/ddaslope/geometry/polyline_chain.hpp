#pragma once
// Joining drawn pieces (lines, open polylines) end to end into one polyline: a ground surface
// drawn in CAD as a run of separate LINEs is one line to the section.
#include <vector>

#include "ddaslope/core/types.hpp"

namespace ddaslope::geometry {

struct Chain {
  std::vector<Vec2> points;     ///< the joined polyline, in the first piece's direction
  std::vector<int> pieceOf;     ///< for each point, the piece it came from (a joint: the earlier one)
  int stray = -1;               ///< a piece that meets no end of the others (the first such), or -1
  bool closed = false;          ///< the chain's two ends meet: a loop, not a line
};

/// Joins `pieces` (each at least two points) end to end, reversing pieces as needed. Two ends
/// within `tol` meet; the point already in the chain is kept. A piece that touches the chain
/// only inside (a branch) or not at all is `stray`.
Chain joinEndToEnd(const std::vector<std::vector<Vec2>>& pieces, double tol);

}  // namespace ddaslope::geometry
