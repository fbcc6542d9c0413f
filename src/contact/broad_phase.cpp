#include "ddaslope/contact/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "ddaslope/core/block_order.hpp"

namespace ddaslope::contact {

namespace {

/// The boxes grown by the margin: two blocks are candidates when these overlap (closed intervals).
/// The same floating-point operations as the sweep's tests, so both find the same pairs.
struct Grown {
  double xlo, xhi, ylo, yhi;
};

bool overlap(const Grown& p, const Grown& q) {
  return !(q.xlo > p.xhi) && !(p.xlo > q.xhi) && !(q.ylo > p.yhi) && !(p.ylo > q.yhi);
}

/// Uniform-grid broad phase: each grown box goes into the cells it covers, and a pair is tested
/// in the one cell where the lower-left corner of their common cells lies (no pair twice). A
/// sweep along x alone tests every block of a tall column of blocks against each other: in a
/// square wall of N bricks, N^1.5 tests; the grid tests each block against its neighbours.
/// Returns false (nothing found) where the grid cannot be built: boxes that are not finite, which
/// the sweep handles.
bool gridPairs(const std::vector<geometry::Aabb>& boxes, const std::vector<bool>& fixed, double margin,
               std::vector<BlockPair>& found) {
  const size_t n = boxes.size();
  if (n < 2) return true;
  std::vector<Grown> g(n);
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  std::vector<double> extent(n);
  for (size_t i = 0; i < n; ++i) {
    const geometry::Aabb& b = boxes[i];
    // As the sweep: the other box's lo − margin against this one's hi + margin.
    g[i] = {b.lo.x() - margin, b.hi.x() + margin, b.lo.y() - margin, b.hi.y() + margin};
    if (!std::isfinite(g[i].xlo) || !std::isfinite(g[i].xhi) || !std::isfinite(g[i].ylo) || !std::isfinite(g[i].yhi))
      return false;
    x0 = std::min(x0, g[i].xlo), x1 = std::max(x1, g[i].xhi);
    y0 = std::min(y0, g[i].ylo), y1 = std::max(y1, g[i].yhi);
    extent[i] = std::max(g[i].xhi - g[i].xlo, g[i].yhi - g[i].ylo);
  }
  // Cells the size of a typical block (the median, so that one large base block does not set
  // it), but no more cells than 4 per block: a scene spread thin keeps a small grid.
  std::nth_element(extent.begin(), extent.begin() + static_cast<long>(n / 2), extent.end());
  const double width = x1 - x0, height = y1 - y0;
  double h = std::max(extent[n / 2], std::sqrt(width * height / (4.0 * static_cast<double>(n))));
  if (!(h > 0) || !std::isfinite(h)) return false;
  const auto cells = [&](double span) { return std::max(1, static_cast<int>(std::min(span / h, 4.0 * n)) + 1); };
  const int nx = cells(width), ny = cells(height);
  // Clamped before the conversion (a monotone map, so overlapping boxes share a cell).
  const auto cellX = [&](double x) { return static_cast<int>(std::clamp((x - x0) / h, 0.0, nx - 1.0)); };
  const auto cellY = [&](double y) { return static_cast<int>(std::clamp((y - y0) / h, 0.0, ny - 1.0)); };
  struct Span {
    int cx0, cx1, cy0, cy1;
  };
  std::vector<Span> span(n);
  std::vector<size_t> start(static_cast<size_t>(nx) * static_cast<size_t>(ny) + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    span[i] = {cellX(g[i].xlo), cellX(g[i].xhi), cellY(g[i].ylo), cellY(g[i].yhi)};
    for (int cy = span[i].cy0; cy <= span[i].cy1; ++cy)
      for (int cx = span[i].cx0; cx <= span[i].cx1; ++cx) ++start[static_cast<size_t>(cy) * nx + cx + 1];
  }
  for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<int> members(start.back());
  std::vector<size_t> next(start.begin(), start.end() - 1);
  for (size_t i = 0; i < n; ++i)
    for (int cy = span[i].cy0; cy <= span[i].cy1; ++cy)
      for (int cx = span[i].cx0; cx <= span[i].cx1; ++cx)
        members[next[static_cast<size_t>(cy) * nx + cx]++] = static_cast<int>(i);
  for (int cy = 0; cy < ny; ++cy)
    for (int cx = 0; cx < nx; ++cx) {
      const size_t c = static_cast<size_t>(cy) * nx + cx;
      for (size_t u = start[c]; u < start[c + 1]; ++u) {
        const int i = members[u];
        for (size_t v = u + 1; v < start[c + 1]; ++v) {
          const int j = members[v];
          if (fixed[i] && fixed[j]) continue;
          // The pair belongs to the first cell both cover.
          if (std::max(span[i].cx0, span[j].cx0) != cx || std::max(span[i].cy0, span[j].cy0) != cy) continue;
          if (overlap(g[i], g[j])) found.push_back({std::min(i, j), std::max(i, j)});
        }
      }
    }
  return true;
}

}  // namespace

std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin,
                                          std::vector<int>& order) {
  std::vector<BlockPair> found;
  if (gridPairs(boxes, fixed, margin, found))
    return sortedByBlock(found, static_cast<int>(boxes.size()), [](const BlockPair& p) { return p.a; },
                         [](const BlockPair& p, const BlockPair& q) { return p.b < q.b; });
  return sweepPairs(boxes, fixed, margin, order);
}

std::vector<BlockPair> sweepPairs(const std::vector<geometry::Aabb>& boxes, const std::vector<bool>& fixed,
                                  double margin, std::vector<int>& order) {
  const int n = static_cast<int>(boxes.size());
  // A strict total order (left edge, then index), so any sorting method gives the same sweep.
  const auto before = [&](int i, int j) {
    return boxes[i].lo.x() < boxes[j].lo.x() || (boxes[i].lo.x() == boxes[j].lo.x() && i < j);
  };
  if (static_cast<int>(order.size()) != n) {
    order.resize(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), before);
  } else {
    for (int k = 1; k < n; ++k) {  // insertion: last step's order is nearly right
      const int i = order[static_cast<size_t>(k)];
      int m = k;
      while (m > 0 && before(i, order[static_cast<size_t>(m - 1)])) {
        order[static_cast<size_t>(m)] = order[static_cast<size_t>(m - 1)];
        --m;
      }
      order[static_cast<size_t>(m)] = i;
    }
  }
  std::vector<BlockPair> found;
  for (int k = 0; k < n; ++k) {
    const int i = order[static_cast<size_t>(k)];
    const double reach = boxes[i].hi.x() + margin;
    for (int m = k + 1; m < n; ++m) {
      const int j = order[static_cast<size_t>(m)];
      if (boxes[j].lo.x() - margin > reach) break;
      if (fixed[i] && fixed[j]) continue;
      if (boxes[i].lo.y() - margin > boxes[j].hi.y() + margin) continue;
      if (boxes[j].lo.y() - margin > boxes[i].hi.y() + margin) continue;
      found.push_back({std::min(i, j), std::max(i, j)});
    }
  }
  // (a, b) order, counted into place by a.
  const std::vector<BlockPair> pairs = sortedByBlock(found, n, [](const BlockPair& p) { return p.a; },
                                                     [](const BlockPair& p, const BlockPair& q) { return p.b < q.b; });
  return pairs;
}

std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin) {
  std::vector<int> order;
  return findCandidatePairs(boxes, fixed, margin, order);
}

}  // namespace ddaslope::contact
