#include "ddaslope/geometry/polyline_chain.hpp"

#include <deque>

namespace ddaslope::geometry {

Chain joinEndToEnd(const std::vector<std::vector<Vec2>>& pieces, double tol) {
  Chain out;
  if (pieces.empty()) return out;
  std::deque<Vec2> points(pieces[0].begin(), pieces[0].end());
  std::deque<int> from(pieces[0].size(), 0);
  std::vector<bool> used(pieces.size(), false);
  used[0] = true;
  const auto meets = [&](const Vec2& a, const Vec2& b) { return (a - b).norm() <= tol; };
  // Each pass attaches one piece at either end of the chain; a run of n pieces needs n − 1 passes
  // whatever their order in the drawing.
  for (bool grew = true; grew;) {
    grew = false;
    for (size_t k = 1; k < pieces.size() && !grew; ++k) {
      if (used[k]) continue;
      const std::vector<Vec2>& p = pieces[k];
      const int id = static_cast<int>(k);
      if (meets(p.front(), points.back()) || meets(p.back(), points.back())) {
        const bool forward = meets(p.front(), points.back());
        for (size_t i = 1; i < p.size(); ++i) {
          points.push_back(forward ? p[i] : p[p.size() - 1 - i]);
          from.push_back(id);
        }
      } else if (meets(p.back(), points.front()) || meets(p.front(), points.front())) {
        const bool forward = meets(p.back(), points.front());
        for (size_t i = 1; i < p.size(); ++i) {
          points.push_front(forward ? p[p.size() - 1 - i] : p[i]);
          from.push_front(id);
        }
      } else {
        continue;
      }
      used[k] = grew = true;
    }
  }
  for (size_t k = 0; k < pieces.size() && out.stray < 0; ++k)
    if (!used[k]) out.stray = static_cast<int>(k);
  out.points.assign(points.begin(), points.end());
  out.pieceOf.assign(from.begin(), from.end());
  out.closed = out.points.size() > 2 && meets(out.points.front(), out.points.back());
  return out;
}

}  // namespace ddaslope::geometry
