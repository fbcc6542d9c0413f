#include "scene_normalisation.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/model/kinks.hpp"

namespace ddaslope::io {
namespace {

/// Whether fixed blocks a and b meet every other block with the same joint (so that one block
/// standing for both changes no contact's strength).
bool sameJoints(const model::Scene& s, int a, int b) {
  for (size_t x = 0; x < s.blocks.size(); ++x)
    if (static_cast<int>(x) != a && static_cast<int>(x) != b &&
        s.jointBetween(static_cast<int>(x), a) != s.jointBetween(static_cast<int>(x), b))
      return false;
  return true;
}

}  // namespace

/// One ground, one contact: fixed blocks that share a stretch of boundary (a base split into
/// pieces, or drawn as several blocks) are merged, where they meet every other block with the same
/// joint. Fixed blocks have no unknowns and no contacts with one another, but a free block resting
/// across their seam would meet each piece as its own edge-to-edge contact and have its cohesion
/// judged in parts (docs/contact-model.md). Monitors, loads and fixed points on a merged block move
/// to the block it joined.
void mergeFixedBlocks(model::Scene& s) {
  const double tol = 1e-9 * 2 * s.modelHalfSize();
  // Each fixed block takes in the fixed blocks after it that it can, one at a time (its outline
  // grows with each), before the next is considered: no rescan of pairs already refused.
  for (size_t i = 0; i < s.blocks.size(); ++i) {
    if (!s.blocks[i].fixed) continue;
    for (bool merged = true; merged;) {
      merged = false;
      for (size_t j = i + 1; j < s.blocks.size() && !merged; ++j) {
        if (!s.blocks[j].fixed) continue;
        const geometry::Aabb bi = geometry::boundingBox(s.blocks[i].vertices), bj = geometry::boundingBox(s.blocks[j].vertices);
        if ((bi.lo.array() > bj.hi.array() + tol).any() || (bj.lo.array() > bi.hi.array() + tol).any()) continue;
        if (!sameJoints(s, static_cast<int>(i), static_cast<int>(j))) continue;
        // Each piece's corners on the other's edges become vertices, so shared stretches coincide
        // vertex for vertex.
        std::vector<Vec2> a = s.blocks[i].vertices, b = s.blocks[j].vertices;
        geometry::insertPointsOnEdges(a, s.blocks[j].vertices, tol);
        geometry::insertPointsOnEdges(b, s.blocks[i].vertices, tol);
        std::vector<Vec2> u = geometry::unionAlongSharedEdges(a, b, tol);
        if (u.empty()) continue;
        model::Block& keep = s.blocks[i];
        keep.vertices = std::move(u);
        keep.moments = geometry::computeMoments(keep.vertices);
        keep.mergedIds.push_back(s.blocks[j].id);
        keep.mergedIds.insert(keep.mergedIds.end(), s.blocks[j].mergedIds.begin(), s.blocks[j].mergedIds.end());
        // Block j goes: indices above it move down by one, and what was on it moves to i.
        const int gone = static_cast<int>(j);
        const auto renumber = [&](int k) { return k == gone ? static_cast<int>(i) : k > gone ? k - 1 : k; };
        s.forEachBlockPoint([&](model::BlockPoint& p) { p.block = renumber(p.block); });
        for (model::EdgeLoad& l : s.edgeLoads) l.block = renumber(l.block);
        std::map<std::pair<int, int>, int> pairs;
        for (const auto& [pair, joint] : s.pairJoints)
          if (pair.first != gone && pair.second != gone) {
            const int x = renumber(pair.first), y = renumber(pair.second);
            pairs[{std::min(x, y), std::max(x, y)}] = joint;
          }
        s.pairJoints = std::move(pairs);
        s.blocks.erase(s.blocks.begin() + gone);
        merged = true;
      }
    }
  }
}

/// One face, one contact: vertices on a straight edge (T-junctions of a block-cutting program or
/// a mesher, an edge split in CAD; within kCollinearTolerance of the chord, or within the gap that
/// counts as touching, Scene::touchingGap) are removed, so that the face meets its
/// neighbour as one edge-to-edge contact whatever vertices it was drawn with
/// (docs/contact-model.md).
void normaliseOutlines(model::Scene& s) {
  // A vertex as near the straight line as a gap that counts as touching at t = 0 is on it too:
  // coordinates rounded in the file make such vertices, and the contact that closes across the
  // rounding closes across the straightened edge as well.
  const double touching = s.touchingGap();
  for (model::Block& b : s.blocks) {
    // Never more than a hundredth of the block's own thickness (2·area/perimeter): a sliver
    // thinner than the gap keeps its corners.
    const double thickness = 2 * std::abs(geometry::signedArea(b.vertices)) / geometry::perimeter(b.vertices);
    const double within = std::min(touching, 0.01 * thickness);
    const int removed = geometry::removeCollinearVertices(b.vertices, model::kCollinearTolerance, within);
    b.removedCollinearVertices += removed;
    if (removed > 0) b.moments = geometry::computeMoments(b.vertices);
  }
}

/// A joint ending on a concave bend of a fixed block is moved off it (model/kinks.hpp): by
/// analysis.joint_end_offset, or by default by the automatic kink block's width, which measurement
/// chose so that a slide cannot squeeze the block out while it settles (docs/research/kink-blocks.md).
void moveJointEndsOffBends(model::Scene& s) {
  const double w0 = s.modelHalfSize();
  const double failure = s.settings.failureDisplacement > 0 ? s.settings.failureDisplacement : 1e-3 * w0;
  const double offset = s.settings.jointEndOffset >= 0 ? s.settings.jointEndOffset : std::max(5e-3 * w0, 2 * failure);
  s.movedJointEnds = model::moveJointEndsOffBends(s, offset);
}

/// A scene far from (0, 0) against its size (national-grid coordinates: 5e6 m for a 30 m slope)
/// is moved next to it (model::Scene::origin): there a coordinate's round-off, 1e-9 m, is a
/// sizeable part of a slow step's displacement (docs/calibration.md). The shift is
/// exact for the blocks (Sterbenz: every coordinate within a factor 2 of the origin's), so the
/// case's coordinates come back unchanged in outputs. A scene within 64 of its own size of (0, 0)
/// is left where it is.
void localiseOrigin(model::Scene& s) {
  geometry::Aabb box = geometry::boundingBox(s.blocks.front().vertices);
  for (const model::Block& b : s.blocks) {
    const geometry::Aabb bb = geometry::boundingBox(b.vertices);
    box.lo = box.lo.cwiseMin(bb.lo);
    box.hi = box.hi.cwiseMax(bb.hi);
  }
  const Vec2 centre = 0.5 * (box.lo + box.hi);
  const double half = 0.5 * (box.hi - box.lo).maxCoeff();
  Vec2 o(0, 0);
  for (int a = 0; a < 2; ++a)
    if (std::abs(centre[a]) > 64 * half) o[a] = centre[a];
  if (o.isZero()) return;
  s.origin = o;
  for (model::Block& b : s.blocks) {
    for (Vec2& v : b.vertices) v -= o;
    b.moments = geometry::computeMoments(b.vertices);  // now to the precision of a small scene
  }
  const auto shift = [&](model::BlockPoint& p) { p.initial -= o, p.current -= o; };
  s.forEachBlockPoint(shift);
  for (model::EdgeLoad& l : s.edgeLoads) l.from -= o, l.to -= o;
  for (Vec2& p : s.water.line) p -= o;
  if (s.water.grid) s.water.grid = std::make_shared<const model::PressureGrid>(s.water.grid->translated(-o));
  for (model::MovedJointEnd& m : s.movedJointEnds) m.kink -= o;
  for (double& level : s.water.seriesLevels) level -= o.y();
}

}  // namespace ddaslope::io
