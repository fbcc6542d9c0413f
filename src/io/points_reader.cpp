#include "points_reader.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>
#include <sstream>

#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::io {
namespace {

using case_json::json;
using case_json::Reader;
using case_json::typeName;

/// The block holding point `at`: the one named by `blockKey` of j if given (the point checked to
/// lie inside it), else the block that contains it, a free one before a fixed one. A point on the
/// joint between two free blocks is the user's to assign when it carries a force (an anchor's
/// head on one block or the other changes F by a third): refused unless `highest`, for a monitor,
/// which follows the block whose centroid lies highest (up the slope, whichever way it faces; a
/// monitor reports and does not decide). Either way the blocks' order in the file does not decide.
int blockHolding(const Reader& r, const json& j, const std::string& p, const std::string& blockKey, const Vec2& at,
                 const std::string& pointPath, const model::Scene& s, bool highest = false) {
  const auto inside = [&](size_t b) {
    const geometry::Aabb box = geometry::boundingBox(s.blocks[b].vertices);
    return geometry::containsPoint(s.blocks[b].vertices, at, 1e-9 * (box.hi - box.lo).maxCoeff());
  };
  if (!j.contains(blockKey)) {
    int found = -1;
    std::vector<int> free;
    for (size_t b = 0; b < s.blocks.size(); ++b) {
      if (!inside(b)) continue;
      if (!s.blocks[b].fixed) free.push_back(static_cast<int>(b));
      if (found < 0 || (s.blocks[found].fixed && !s.blocks[b].fixed)) found = static_cast<int>(b);
    }
    std::ostringstream m;
    m << "(" << at.x() << ", " << at.y() << ")";
    if (found < 0) r.fail(pointPath, "point lies in no block: expected a point inside (or on) a block, found " + m.str());
    if (free.size() > 1 && highest) {
      const auto key = [&](int b) { return std::make_pair(s.blocks[b].moments.centroid.y(), s.blocks[b].moments.centroid.x()); };
      return *std::max_element(free.begin(), free.end(), [&](int a, int b) { return key(a) < key(b); });
    }
    if (free.size() > 1) {
      std::string names;
      for (size_t k = 0; k < free.size(); ++k)
        names += (k == 0 ? "" : k + 1 == free.size() ? " and " : ", ") + ("\"" + s.blocks[free[k]].id + "\"");
      r.fail(pointPath, "the point " + m.str() + " lies on the boundary of the free blocks " + names +
                            ": say which carries it with \"" + blockKey + "\" (" + Reader::join(p, blockKey) + ")");
    }
    return found;
  }
  const std::string id = r.string(j.at(blockKey), Reader::join(p, blockKey));
  const int b = s.blockIndex(id);
  if (b < 0) r.fail(Reader::join(p, blockKey), "unknown block \"" + id + "\"");
  if (!inside(static_cast<size_t>(b))) r.fail(pointPath, "point lies outside block \"" + id + "\"");
  return b;
}

/// A point ("point", on "block" if named) carried by a block.
model::BlockPoint blockPoint(const Reader& r, const json& j, const std::string& p, const model::Scene& s,
                             const std::string& pointKey = "point", const std::string& blockKey = "block",
                             bool highest = false) {
  model::BlockPoint bp;
  bp.initial = bp.current = r.point(r.required(j, p, pointKey), Reader::join(p, pointKey));
  bp.block = blockHolding(r, j, p, blockKey, bp.initial, Reader::join(p, pointKey), s, highest);
  return bp;
}

/// The length of segment a–b inside polygon `poly` (m): the bolt's embedment in a block.
double lengthInside(const std::vector<Vec2>& poly, const Vec2& a, const Vec2& b) {
  std::vector<double> t{0.0, 1.0};
  const Vec2 d = b - a;
  for (size_t k = 0; k < poly.size(); ++k) {
    const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
    const Vec2 e = q - p;
    const double den = cross(d, e);
    if (std::abs(den) < 1e-300) continue;
    const double s = cross(p - a, e) / den, u = cross(p - a, d) / den;
    if (s > 0 && s < 1 && u >= 0 && u <= 1) t.push_back(s);
  }
  std::sort(t.begin(), t.end());
  const geometry::Aabb box = geometry::boundingBox(poly);
  const double tol = 1e-9 * (box.hi - box.lo).maxCoeff();
  double inside = 0;
  for (size_t k = 0; k + 1 < t.size(); ++k)
    if (geometry::containsPoint(poly, a + 0.5 * (t[k] + t[k + 1]) * d, tol)) inside += (t[k + 1] - t[k]) * d.norm();
  return inside;
}

/// A load's or a support's id: a name unique among them (critical --support finds it by name).
std::string namedOnce(const Reader& r, const json& j, const std::string& p, std::set<std::string>& names,
                      bool required) {
  if (!j.contains("id")) {
    if (required) r.required(j, p, "id");
    return {};
  }
  const std::string id = r.identifier(r.string(j.at("id"), p + ".id"), p + ".id");
  if (!names.insert(id).second)
    r.fail(p + ".id", "duplicate id \"" + id + "\" (supports, point loads and edge loads share their names)");
  return id;
}

/// A traction along an edge load: a constant vector [qx, qy] or, varying linearly, [[qx, qy] at
/// from, [qx, qy] at to].
std::pair<Vec2, Vec2> traction(const Reader& r, const json& j, const std::string& p) {
  if (j.is_array() && j.size() == 2 && j[0].is_array()) return {r.point(j[0], p + "[0]"), r.point(j[1], p + "[1]")};
  const Vec2 q = r.point(j, p);
  return {q, q};
}

void readEdgeLoads(const Reader& r, const json& list, model::Scene& s, std::set<std::string>& names) {
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string p = Reader::index("edge_loads", i);
    const json& j = list[i];
    r.onlyKeys(j, p, {"id", "block", "from", "to", "load", "pressure"});
    model::EdgeLoad l;
    l.id = namedOnce(r, j, p, names, false);
    l.from = r.point(r.required(j, p, "from"), p + ".from");
    l.to = r.point(r.required(j, p, "to"), p + ".to");
    const Vec2 mid = 0.5 * (l.from + l.to);
    l.block = blockHolding(r, j, p, "block", mid, p, s);
    const std::vector<Vec2>& poly = s.blocks[l.block].vertices;
    const geometry::Aabb box = geometry::boundingBox(poly);
    const double size = (box.hi - box.lo).maxCoeff();
    if ((l.to - l.from).norm() <= 1e-9 * size) r.fail(p + ".to", "expected a segment of non-zero length");
    // The segment must lie on the block's boundary: its ends and its middle on an edge.
    for (const auto& [point, key] : {std::pair{l.from, ".from"}, std::pair{l.to, ".to"}, std::pair{mid, ""}}) {
      double nearest = INFINITY, t;
      for (size_t k = 0; k < poly.size(); ++k)
        nearest = std::min(nearest, geometry::distanceToSegment(point, poly[k], poly[(k + 1) % poly.size()], &t));
      if (nearest > 1e-6 * size)
        r.fail(p + key, std::string("expected the loaded segment on the boundary of block \"") + s.blocks[l.block].id +
                            "\", found " + (*key ? "its end" : "its middle") + " " + std::to_string(nearest) + " m from it");
    }
    if (j.contains("load") == j.contains("pressure"))
      r.fail(p, "expected exactly one of load (a traction [qx, qy] in N/m²) and pressure (normal, into the block, Pa)");
    if (j.contains("load")) {
      std::tie(l.q0, l.q1) = traction(r, j.at("load"), p + ".load");
    } else {
      const json& pj = j.at("pressure");
      if (pj.is_array() && pj.size() != 2)
        r.fail(p + ".pressure", "expected a pressure (Pa) or [at from, at to], found " + typeName(pj));
      const double p0 = pj.is_array() ? r.number(pj[0], p + ".pressure[0]") : r.number(pj, p + ".pressure");
      const double p1 = pj.is_array() ? r.number(pj[1], p + ".pressure[1]") : p0;
      // Into the block: the side of the segment where its middle, nudged, lies inside.
      const Vec2 d = (l.to - l.from).normalized();
      Vec2 n(-d.y(), d.x());
      if (!geometry::containsPoint(poly, mid + 1e-6 * size * n, 0)) n = -n;
      l.q0 = p0 * n, l.q1 = p1 * n;
    }
    s.edgeLoads.push_back(l);
    for (const model::PointLoad& g : model::equivalentPointLoads(l)) s.pointLoads.push_back(g);
  }
}

void readSupports(const Reader& r, const json& list, model::Scene& s, std::set<std::string>& names) {
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string p = Reader::index("supports", i);
    const json& j = list[i];
    r.onlyKeys(j, p, {"id", "head", "head_block", "end", "end_block", "spacing", "stiffness", "pretension", "capacity",
                      "bond_strength", "failure", "compression"});
    model::Support b;
    b.id = namedOnce(r, j, p, names, true);
    b.head = blockPoint(r, j, p, s, "head", "head_block");
    b.end = blockPoint(r, j, p, s, "end", "end_block");
    if (b.head.block == b.end.block)
      r.fail(p + ".end", "expected the end in another block than the head (block \"" + s.blocks[b.head.block].id +
                             "\"): a support joins two blocks");
    if (s.blocks[b.head.block].fixed && s.blocks[b.end.block].fixed)
      r.fail(p + ".head", "both ends lie in fixed blocks: the support would carry nothing");
    b.initialLength = (b.end.initial - b.head.initial).norm();
    const geometry::Aabb box = geometry::boundingBox(s.blocks[b.head.block].vertices);
    if (!(b.initialLength > 1e-6 * (box.hi - box.lo).maxCoeff()))
      r.fail(p + ".end", "expected the end apart from the head: a support needs a length and a direction");
    const double spacing = r.optionalIn(j, p, "spacing", 1.0, 0, 1e3, true, false, "an out-of-plane spacing in (0, 1000] m");
    const double big = 1e15;
    b.stiffness = r.optionalIn(j, p, "stiffness", 0.0, 0, big, false, false, "a stiffness in [0, 1e15] N/m") / spacing;
    b.pretension = r.optionalIn(j, p, "pretension", 0.0, 0, big, false, false, "a force in [0, 1e15] N") / spacing;
    b.capacity = r.optionalIn(j, p, "capacity", INFINITY, 0, INFINITY, true, true, "a capacity > 0 N") / spacing;
    if (j.contains("bond_strength")) {
      b.bondStrength = r.numberIn(j.at("bond_strength"), p + ".bond_strength", 0, big, true, false,
                                  "a bond strength in (0, 1e15] N per metre of bolt") /
                       spacing;
      b.headEmbedment = lengthInside(s.blocks[b.head.block].vertices, b.head.initial, b.end.initial);
      b.endEmbedment = lengthInside(s.blocks[b.end.block].vertices, b.head.initial, b.end.initial);
      b.bondCapacity = b.bondStrength * std::min(b.headEmbedment, b.endEmbedment);
      b.capacity = std::min(b.capacity, b.bondCapacity);
      // A bolt with no length inside one of its blocks (its head on the block's face, pointing
      // out of it across an open crack) is bonded over nothing and carries nothing.
      if (!(b.bondCapacity > 0)) {
        std::ostringstream m;
        m << "expected the support to run inside both its blocks, to be bonded there (bond_strength): it runs "
          << b.headEmbedment << " m inside its head's block \"" << s.blocks[b.head.block].id << "\" and " << b.endEmbedment
          << " m inside its end's block \"" << s.blocks[b.end.block].id << "\", so its bond holds nothing";
        r.fail(p + (b.headEmbedment > 0 ? ".end" : ".head"), m.str());
      }
    }
    if (b.pretension > b.capacity) {
      std::ostringstream m;
      m << "expected a pretension of at most the capacity (" << b.capacity * spacing << " N per support";
      if (j.contains("bond_strength")) m << ", with the bond over the embedded lengths";
      m << "), found " << b.pretension * spacing << " N";
      r.fail(p + ".pretension", m.str());
    }
    b.failure = r.choice(j, p, "failure", "yield", {"yield", "rupture"}) == "rupture" ? model::SupportFailure::Rupture
                                                                                        : model::SupportFailure::Yield;
    b.carriesCompression = r.boolean(j, p, "compression", false);
    b.spacing = spacing;
    b.force = b.pretension;
    s.supports.push_back(b);
  }
}

}  // namespace

void readPointsAndLoads(const Reader& r, const json& doc, model::Scene& s) {
  const auto list = [&](const char* key) -> const json* {
    if (!doc.contains(key)) return nullptr;
    if (!doc.at(key).is_array()) r.fail(key, "expected an array, found " + typeName(doc.at(key)));
    return &doc.at(key);
  };
  std::set<std::string> names;
  if (const json* mons = list("monitors")) {
    std::set<std::string> seen;
    for (size_t i = 0; i < mons->size(); ++i) {
      const std::string p = Reader::index("monitors", i);
      r.onlyKeys((*mons)[i], p, {"id", "block", "point"});
      model::Monitor m;
      m.id = r.identifier(r.string(r.required((*mons)[i], p, "id"), p + ".id"), p + ".id");
      if (!seen.insert(m.id).second) r.fail(p + ".id", "duplicate monitor id \"" + m.id + "\"");
      m.point = blockPoint(r, (*mons)[i], p, s, "point", "block", true);
      s.monitors.push_back(m);
    }
  }
  if (const json* loads = list("point_loads")) {
    for (size_t i = 0; i < loads->size(); ++i) {
      const std::string p = Reader::index("point_loads", i);
      r.onlyKeys((*loads)[i], p, {"id", "block", "point", "force", "rate"});
      model::PointLoad l;
      l.id = namedOnce(r, (*loads)[i], p, names, false);
      l.point = blockPoint(r, (*loads)[i], p, s);
      l.force = r.point(r.required((*loads)[i], p, "force"), p + ".force");
      if ((*loads)[i].contains("rate")) l.rate = r.point((*loads)[i].at("rate"), p + ".rate");
      s.pointLoads.push_back(l);
    }
  }
  if (const json* fps = list("fixed_points")) {
    for (size_t i = 0; i < fps->size(); ++i) {
      const std::string p = Reader::index("fixed_points", i);
      r.onlyKeys((*fps)[i], p, {"block", "point"});
      s.fixedPoints.push_back({blockPoint(r, (*fps)[i], p, s)});
    }
  }
  if (const json* loads = list("edge_loads")) readEdgeLoads(r, *loads, s, names);
  if (const json* supports = list("supports")) readSupports(r, *supports, s, names);
}

}  // namespace ddaslope::io
