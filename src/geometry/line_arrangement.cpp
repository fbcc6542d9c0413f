#include "ddaslope/geometry/line_arrangement.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>
#include <utility>

#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::geometry {
namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  // The smaller index stays the root, so a cluster keeps the position of its first node: a line's
  // end as written rather than a computed crossing.
  void join(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

struct Edge {
  int u, v, type;
  bool alive = true;
};

/// Node ids on each segment, with their parameter along it.
using Splits = std::vector<std::vector<std::pair<double, int>>>;

void splitAtCrossings(const std::vector<TypedSegment>& lines, double tol, std::vector<Vec2>& nodes, Splits& splits) {
  const size_t n = lines.size();
  for (size_t i = 0; i < n; ++i) {
    splits[i].push_back({0.0, static_cast<int>(nodes.size())});
    nodes.push_back(lines[i].a);
    splits[i].push_back({1.0, static_cast<int>(nodes.size())});
    nodes.push_back(lines[i].b);
  }
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  const auto lo = [&](size_t i) { return std::min(lines[i].a.x(), lines[i].b.x()); };
  const auto hi = [&](size_t i) { return std::max(lines[i].a.x(), lines[i].b.x()); };
  std::sort(order.begin(), order.end(), [&](size_t p, size_t q) { return lo(p) < lo(q); });
  // An end of j within tol of segment i, away from i's own ends, splits i there (a T-junction,
  // or one end of a collinear overlap).
  const auto endOn = [&](size_t i, size_t j, int endIndex) {
    const Vec2& p = endIndex == 0 ? lines[j].a : lines[j].b;
    const double len = (lines[i].b - lines[i].a).norm();
    double t = 0;
    if (distanceToSegment(p, lines[i].a, lines[i].b, &t) <= tol && t * len > tol && (1 - t) * len > tol)
      splits[i].push_back({t, static_cast<int>(2 * j + endIndex)});
  };
  for (size_t oi = 0; oi < n; ++oi) {
    const size_t i = order[oi];
    const double yLoI = std::min(lines[i].a.y(), lines[i].b.y()), yHiI = std::max(lines[i].a.y(), lines[i].b.y());
    for (size_t oj = oi + 1; oj < n && lo(order[oj]) <= hi(i) + tol; ++oj) {
      const size_t j = order[oj];
      if (std::min(lines[j].a.y(), lines[j].b.y()) > yHiI + tol || std::max(lines[j].a.y(), lines[j].b.y()) < yLoI - tol)
        continue;
      endOn(i, j, 0), endOn(i, j, 1), endOn(j, i, 0), endOn(j, i, 1);
      const Vec2 r = lines[i].b - lines[i].a, s = lines[j].b - lines[j].a;
      const double denom = cross(r, s), li = r.norm(), lj = s.norm();
      if (std::abs(denom) <= 1e-12 * li * lj) continue;  // parallel: overlaps are split by their ends
      const Vec2 d = lines[j].a - lines[i].a;
      const double t = cross(d, s) / denom, u = cross(d, r) / denom;
      // A crossing within tol of an end is that end's T-junction (above) or a node merge (below).
      if (t * li > tol && (1 - t) * li > tol && u * lj > tol && (1 - u) * lj > tol) {
        const int id = static_cast<int>(nodes.size());
        nodes.push_back(lines[i].a + t * r);
        splits[i].push_back({t, id});
        splits[j].push_back({u, id});
      }
    }
  }
}

/// Merges nodes within tol of each other (transitively), through a grid of cells of size tol.
int mergeNodes(const std::vector<Vec2>& nodes, double tol, UnionFind& uf) {
  std::unordered_map<long long, std::vector<int>> grid;
  const auto key = [](long long cx, long long cy) { return cx * 73856093LL ^ cy * 19349663LL; };
  const auto cell = [&](double v) { return static_cast<long long>(std::floor(v / tol)); };
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
    const long long cx = cell(nodes[i].x()), cy = cell(nodes[i].y());
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = grid.find(key(cx + dx, cy + dy));
        if (it == grid.end()) continue;
        for (int j : it->second)
          if ((nodes[i] - nodes[j]).norm() <= tol) uf.join(i, j);
      }
    grid[key(cx, cy)].push_back(i);
  }
  int merged = 0;
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) merged += uf.find(i) != i;
  return merged;
}

/// Removes edges with an end of degree one until there is none.
int dropDangling(std::vector<Edge>& edges, size_t nodeCount) {
  std::vector<int> degree(nodeCount, 0);
  std::vector<std::vector<int>> at(nodeCount);
  for (int e = 0; e < static_cast<int>(edges.size()); ++e)
    if (edges[e].alive) ++degree[edges[e].u], ++degree[edges[e].v], at[edges[e].u].push_back(e), at[edges[e].v].push_back(e);
  std::vector<int> queue;
  for (size_t i = 0; i < nodeCount; ++i)
    if (degree[i] == 1) queue.push_back(static_cast<int>(i));
  int dropped = 0;
  while (!queue.empty()) {
    const int node = queue.back();
    queue.pop_back();
    for (int e : at[node]) {
      if (!edges[e].alive) continue;
      edges[e].alive = false;
      ++dropped;
      for (int end : {edges[e].u, edges[e].v})
        if (--degree[end] == 1) queue.push_back(end);
    }
  }
  return dropped;
}

struct Faces {
  std::vector<int> faceOf;                 ///< per half-edge 2e (u→v) and 2e+1 (v→u)
  std::vector<std::vector<int>> halfEdges; ///< per face, in order
};

/// Traces the faces of the embedded graph: each half-edge continues with the edge next clockwise
/// about its head, so every face lies on the left of its half-edges, bounded faces run
/// counter-clockwise and each piece's outer boundary clockwise.
Faces traceFaces(const std::vector<Edge>& edges, const std::vector<Vec2>& pos) {
  const auto head = [&](int h) { return h % 2 == 0 ? edges[h / 2].v : edges[h / 2].u; };
  const auto tail = [&](int h) { return h % 2 == 0 ? edges[h / 2].u : edges[h / 2].v; };
  std::vector<std::vector<int>> out(pos.size());
  for (int e = 0; e < static_cast<int>(edges.size()); ++e)
    if (edges[e].alive) out[edges[e].u].push_back(2 * e), out[edges[e].v].push_back(2 * e + 1);
  std::vector<int> slot(2 * edges.size(), -1);
  for (auto& list : out) {
    std::sort(list.begin(), list.end(), [&](int p, int q) {
      const Vec2 dp = pos[head(p)] - pos[tail(p)], dq = pos[head(q)] - pos[tail(q)];
      return std::atan2(dp.y(), dp.x()) < std::atan2(dq.y(), dq.x());
    });
    for (size_t k = 0; k < list.size(); ++k) slot[list[k]] = static_cast<int>(k);
  }
  Faces f;
  f.faceOf.assign(2 * edges.size(), -1);
  for (int h0 = 0; h0 < static_cast<int>(2 * edges.size()); ++h0) {
    if (!edges[h0 / 2].alive || f.faceOf[h0] >= 0) continue;
    const int face = static_cast<int>(f.halfEdges.size());
    f.halfEdges.emplace_back();
    for (int h = h0; f.faceOf[h] < 0;) {
      f.faceOf[h] = face;
      f.halfEdges[face].push_back(h);
      const auto& list = out[head(h)];
      const int twin = h ^ 1;
      h = list[(slot[twin] + list.size() - 1) % list.size()];
    }
  }
  return f;
}

std::vector<Vec2> startAtLowest(std::vector<Vec2> pts) {
  const auto lowest = std::min_element(pts.begin(), pts.end(), [](const Vec2& p, const Vec2& q) {
    return p.y() < q.y() || (p.y() == q.y() && p.x() < q.x());
  });
  std::rotate(pts.begin(), lowest, pts.end());
  return pts;
}

}  // namespace

LineArrangement arrangeLines(const std::vector<TypedSegment>& lines, double mergeDistance) {
  LineArrangement result;
  if (lines.empty()) return result;
  double scale = 0;
  for (const auto& l : lines) scale = std::max({scale, l.a.cwiseAbs().maxCoeff(), l.b.cwiseAbs().maxCoeff()});
  // Exact duplicates must merge even at distance 0; the grid needs a positive cell.
  const double tol = std::max(mergeDistance, 1e-12 * std::max(scale, 1.0));

  std::vector<Vec2> nodes;
  Splits splits(lines.size());
  splitAtCrossings(lines, tol, nodes, splits);
  UnionFind uf(nodes.size());
  result.mergedNodes = mergeNodes(nodes, tol, uf);

  std::vector<Edge> edges;
  std::map<std::pair<int, int>, int> edgeIndex;
  for (size_t i = 0; i < lines.size(); ++i) {
    auto& s = splits[i];
    std::sort(s.begin(), s.end());
    int prev = -1;
    for (const auto& [t, id] : s) {
      const int node = uf.find(id);
      if (prev >= 0 && node != prev) {
        const std::pair<int, int> k{std::min(prev, node), std::max(prev, node)};
        if (const auto it = edgeIndex.find(k); it != edgeIndex.end())
          result.typeConflicts += edges[it->second].type != lines[i].type;
        else
          edgeIndex[k] = static_cast<int>(edges.size()), edges.push_back({k.first, k.second, lines[i].type});
      }
      prev = node;
    }
  }

  result.danglingEdges = dropDangling(edges, nodes.size());
  Faces f;
  for (;;) {
    f = traceFaces(edges, nodes);
    int bridges = 0;
    for (size_t e = 0; e < edges.size(); ++e)
      if (edges[e].alive && f.faceOf[2 * e] == f.faceOf[2 * e + 1]) edges[e].alive = false, ++bridges;
    if (bridges == 0) break;
    result.bridgeEdges += bridges;
    result.danglingEdges += dropDangling(edges, nodes.size());
  }

  const auto tailPos = [&](int h) { return nodes[h % 2 == 0 ? edges[h / 2].u : edges[h / 2].v]; };
  std::vector<std::vector<Vec2>> polygons(f.halfEdges.size());
  std::vector<double> areas(f.halfEdges.size());
  for (size_t k = 0; k < f.halfEdges.size(); ++k) {
    for (int h : f.halfEdges[k]) polygons[k].push_back(tailPos(h));
    areas[k] = signedArea(polygons[k]);
  }
  // A piece's outer boundary (clockwise) inside a bounded face of another piece leaves a hole
  // in that face: a block cannot have one.
  std::vector<bool> keep(polygons.size());
  for (size_t k = 0; k < polygons.size(); ++k) keep[k] = areas[k] > 0;
  for (size_t outer = 0; outer < polygons.size(); ++outer) {
    if (areas[outer] > 0) continue;
    const Vec2 p = polygons[outer].front();
    for (size_t k = 0; k < polygons.size(); ++k)
      if (keep[k] && containsPoint(polygons[k], p, 0) &&
          std::none_of(polygons[k].begin(), polygons[k].end(), [&](const Vec2& q) { return q == p; }))
        keep[k] = false, ++result.holedFaces;
  }
  for (size_t k = 0; k < polygons.size(); ++k)
    if (keep[k] && !isSimple(polygons[k])) keep[k] = false, ++result.pinchedFaces;

  std::vector<size_t> kept;
  for (size_t k = 0; k < polygons.size(); ++k)
    if (keep[k]) kept.push_back(k);
  std::vector<Vec2> centroids(polygons.size());
  for (size_t k : kept) centroids[k] = computeMoments(polygons[k]).centroid;
  const double rowTol = 1e-9 * std::max(scale, 1.0);
  std::sort(kept.begin(), kept.end(), [&](size_t p, size_t q) {
    if (std::abs(centroids[p].y() - centroids[q].y()) > rowTol) return centroids[p].y() < centroids[q].y();
    return centroids[p].x() < centroids[q].x();
  });
  std::vector<int> faceIndex(polygons.size(), -1);
  for (size_t i = 0; i < kept.size(); ++i) {
    faceIndex[kept[i]] = static_cast<int>(i);
    std::vector<Vec2> pts = polygons[kept[i]];
    removeCollinearVertices(pts, 1e-12, 1e-12 * std::max(scale, 1.0));
    result.faces.push_back(startAtLowest(std::move(pts)));
  }
  for (size_t e = 0; e < edges.size(); ++e) {
    if (!edges[e].alive) continue;
    const int left = faceIndex[f.faceOf[2 * e]], right = faceIndex[f.faceOf[2 * e + 1]];
    if (left < 0 && right < 0) continue;
    result.edges.push_back({left, right, edges[e].type, (nodes[edges[e].v] - nodes[edges[e].u]).norm()});
  }
  return result;
}

}  // namespace ddaslope::geometry
