// A scene as ntdda's DDAML geometry and analysis files (the C++ form of
// ../shared/ntdda/json2ntdda.py). ntdda reads no block polygons: Shi's block cutting rebuilds
// them from joint lines, so every block edge is written as part of one.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/io/ntdda_model.hpp"

namespace ddaslope::io {
namespace {

/// The shortest text that reads back as the same double.
std::string num(double v) {
  char b[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(b, sizeof b, "%.*g", digits, v);
    if (std::strtod(b, nullptr) == v) break;
  }
  return b;
}

/// An angle converted from radians, without the conversion's last-bit noise (29.999999999999996).
std::string degrees(double radians) {
  char b[32];
  std::snprintf(b, sizeof b, "%.12g", radians * 180 / M_PI);
  return b;
}

struct JointSegment {
  Vec2 a, b;
  int type;  ///< 1-based joint index
};

/// Every block edge merged into maximal collinear segments, split where the joint changes:
/// overlapping collinear joint lines would confuse Shi's block cutting, and a shared face must
/// be one line. T-junctions need no overshoot (ntdda counts an end on another line as a crossing).
std::vector<JointSegment> jointSegments(const std::vector<std::vector<Vec2>>& blocks, const model::Scene& scene, double size) {
  const double tol = 1e-9 * size;
  struct Edge {
    double theta, offset;
    Vec2 a, c;
    int block;
  };
  std::vector<Edge> edges;
  for (int bi = 0; bi < static_cast<int>(blocks.size()); ++bi) {
    const auto& v = blocks[bi];
    for (size_t i = 0; i < v.size(); ++i) {
      const Vec2 &a = v[i], &c = v[(i + 1) % v.size()];
      const double len = (c - a).norm();
      if (len <= tol) continue;
      Vec2 u = (c - a) / len;
      if (u.x() < -1e-12 || (std::abs(u.x()) <= 1e-12 && u.y() < 0)) u = -u;
      // Directions bucketed to 1e-9 rad, so that a shared face's two edges group together.
      const double theta = std::round(std::atan2(u.y(), u.x()) * 1e9) / 1e9;
      edges.push_back({theta, -u.y() * a.x() + u.x() * a.y(), a, c, bi});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& p, const Edge& q) {
    return p.theta < q.theta || (p.theta == q.theta && p.offset < q.offset);
  });
  std::vector<JointSegment> out;
  const auto jointOf = [&](const std::vector<int>& owners) {
    return (owners.size() == 2 ? scene.jointBetween(owners[0], owners[1]) : scene.defaultJoint) + 1;
  };
  for (size_t g0 = 0; g0 < edges.size();) {
    size_t g1 = g0 + 1;
    while (g1 < edges.size() && std::abs(edges[g1].theta - edges[g0].theta) <= 1e-9 &&
           std::abs(edges[g1].offset - edges[g1 - 1].offset) <= tol)
      ++g1;
    const Vec2 u(std::cos(edges[g0].theta), std::sin(edges[g0].theta));
    const Vec2 p0 = edges[g0].a;
    const auto s = [&](const Vec2& p) { return (p - p0).dot(u); };
    std::vector<double> pts;
    for (size_t k = g0; k < g1; ++k) pts.push_back(s(edges[k].a)), pts.push_back(s(edges[k].c));
    std::sort(pts.begin(), pts.end());
    std::vector<double> brk{pts.front()};
    for (double x : pts)
      if (x - brk.back() > 1e3 * tol) brk.push_back(x);
    // The pieces' ends at the blocks' own vertices, exactly as the case gives them.
    std::map<size_t, Vec2> coord;
    for (size_t k = g0; k < g1; ++k)
      for (const Vec2& p : {edges[k].a, edges[k].c}) {
        const double sp = s(p);
        size_t best = 0;
        for (size_t i = 1; i < brk.size(); ++i)
          if (std::abs(brk[i] - sp) < std::abs(brk[best] - sp)) best = i;
        coord.emplace(best, p);
      }
    const auto at = [&](size_t k) { return coord.count(k) ? coord.at(k) : Vec2(p0 + brk[k] * u); };
    int open = -1;
    size_t from = 0;
    for (size_t k = 0; k + 1 < brk.size(); ++k) {
      const double mid = 0.5 * (brk[k] + brk[k + 1]);
      std::set<int> owners;
      for (size_t e = g0; e < g1; ++e) {
        const double lo = std::min(s(edges[e].a), s(edges[e].c)), hi = std::max(s(edges[e].a), s(edges[e].c));
        if (lo - 1e3 * tol <= mid && mid <= hi + 1e3 * tol) owners.insert(edges[e].block);
      }
      const int type = owners.empty() ? -1 : jointOf(std::vector<int>(owners.begin(), owners.end()));
      if (type != open) {
        if (open > 0) out.push_back({at(from), at(k), open});
        open = type, from = k;
      }
    }
    if (open > 0) out.push_back({at(from), at(brk.size() - 1), open});
    g0 = g1;
  }
  return out;
}

/// A point well inside a simple polygon: the middle of the widest chord on a horizontal line
/// halfway between two vertex heights (so never through a vertex).
Vec2 interiorPoint(const std::vector<Vec2>& poly) {
  std::vector<double> ys;
  for (const Vec2& p : poly) ys.push_back(p.y());
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  double bestWidth = -1;
  Vec2 best = poly.front();
  for (size_t i = 0; i + 1 < ys.size(); ++i) {
    const double y = 0.5 * (ys[i] + ys[i + 1]);
    std::vector<double> xs;
    for (size_t k = 0; k < poly.size(); ++k) {
      const Vec2 &a = poly[k], &b = poly[(k + 1) % poly.size()];
      if ((a.y() > y) != (b.y() > y)) xs.push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
    std::sort(xs.begin(), xs.end());
    for (size_t k = 0; k + 1 < xs.size(); k += 2)
      if (xs[k + 1] - xs[k] > bestWidth) bestWidth = xs[k + 1] - xs[k], best = Vec2(0.5 * (xs[k] + xs[k + 1]), y);
  }
  return best;
}

std::string pointElement(const Vec2& p) { return "<Point> " + num(p.x()) + " " + num(p.y()) + " </Point>"; }

}  // namespace

NtddaFiles writeNtddaModel(const model::Scene& scene, const std::string& caseName) {
  NtddaFiles files;
  auto& notes = files.notes;
  std::vector<std::vector<Vec2>> blocks;
  for (const auto& b : scene.blocks) {
    std::vector<Vec2> v;
    for (const Vec2& p : b.vertices) v.push_back(p + scene.origin);
    blocks.push_back(v);
  }
  Vec2 lo = blocks.front().front(), hi = lo;
  for (const auto& b : blocks)
    for (const Vec2& p : b) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double W = hi.x() - lo.x(), H = hi.y() - lo.y(), w0 = std::max(W, H) / 2;
  const std::vector<JointSegment> segs = jointSegments(blocks, scene, std::max(W, H));
  files.jointLines = static_cast<int>(segs.size());

  // e00 against ntdda's own scale: 1 % of the shortest line or edge, so that no two real nodes merge.
  std::vector<NtddaLine> asLines;
  for (const auto& s : segs) asLines.push_back({s.a, s.b, s.type, {}});
  double minLen = INFINITY;
  for (const auto& s : segs) minLen = std::min(minLen, (s.b - s.a).norm());
  for (const auto& b : blocks)
    for (size_t i = 0; i < b.size(); ++i) minLen = std::min(minLen, (b[i] - b[(i + 1) % b.size()]).norm());
  const double e00 = 0.01 * minLen / ntddaScale(asLines);

  const double gacc = -scene.gravity.y();
  if (std::abs(scene.gravity.x()) > 1e-12 * scene.gravity.norm() || gacc <= 0)
    notes.push_back("gravity (" + num(scene.gravity.x()) + ", " + num(scene.gravity.y()) +
                    ") not written as it is: ntdda's gravity points down −y; written as " + num(scene.gravity.norm()) + " m/s² down");
  const double g = gacc > 0 && std::abs(scene.gravity.x()) <= 1e-12 * scene.gravity.norm() ? gacc : scene.gravity.norm();

  double maxE = 0;
  for (const auto& m : scene.materials) maxE = std::max(maxE, m.youngModulus);
  const double penalty = scene.normalPenalty();
  double thinnest = INFINITY;
  for (size_t b = 0; b < blocks.size(); ++b)
    if (!scene.blocks[b].fixed)
      thinnest = std::min(thinnest, 2 * std::abs(geometry::signedArea(blocks[b])) / geometry::perimeter(blocks[b]));
  // ntdda has no cap of its own: the step limit written is the one ddaslope would use.
  const double g2 = std::min(scene.settings.maxDisplacementRatio, 0.1 * thinnest / w0);
  const auto& st = scene.settings;
  const int steps = std::max(1, static_cast<int>(std::lround(st.duration / st.timeStep)));

  std::vector<Vec2> fixedPoints;
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (!scene.blocks[b].fixed) continue;
    // Points just inside the corners (at most 8): ntdda's springs at them hold the block, and
    // ddaslope reads two or more in a block as a fixed block.
    const Vec2 c = interiorPoint(blocks[b]);
    const auto& v = blocks[b];
    const size_t n = std::min<size_t>(v.size(), 8);
    for (size_t i = 0; i < n; ++i) {
      const Vec2 corner = v[v.size() <= 8 ? i : static_cast<size_t>(std::lround(static_cast<double>(i) * v.size() / 8)) % v.size()];
      const Vec2 p = corner + 0.15 * (c - corner);
      fixedPoints.push_back(geometry::containsPoint(v, p, 0) ? p : c);
    }
  }
  std::map<int, int> pinsPerBlock;
  for (const auto& fp : scene.fixedPoints) {
    fixedPoints.push_back(fp.point.initial + scene.origin);
    ++pinsPerBlock[fp.point.block];
  }
  for (const auto& [b, n] : pinsPerBlock)
    if (n >= 2 && !scene.blocks[b].fixed)
      notes.push_back("block " + scene.blocks[b].id + ": " + std::to_string(n) + " fixed points; ntdda holds them by springs, and read back the block becomes a fixed block");

  std::ostringstream geo;
  geo << "<?xml version=\"1.0\" standalone=\"no\"?>\n<!DOCTYPE DDA SYSTEM \"geometry.dtd\">\n"
      << "<Berkeley:DDA xmlns:Berkeley=\"http://www.tsoft.com/~bdoolin/dda\">\n"
      << "<!-- from " << caseName << " by ddaslope convert: " << blocks.size() << " blocks, " << segs.size() << " joint lines -->\n"
      << "<Berkeley:Geometry>\n<Berkeley:Edgenodedist distance=\"" << num(e00) << "\"/>\n<Jointlist>\n";
  for (const auto& s : segs)
    geo << "<Joint type=\"" << s.type << "\"> " << num(s.a.x()) << " " << num(s.a.y()) << " " << num(s.b.x()) << " " << num(s.b.y()) << " </Joint>\n";
  geo << "</Jointlist>\n";
  // No white space between list items: ntdda takes text nodes there for validation failures.
  if (!fixedPoints.empty()) {
    geo << "<Fixedpointlist>";
    for (const Vec2& p : fixedPoints) geo << pointElement(p);
    geo << "</Fixedpointlist>\n";
  }
  std::vector<const model::PointLoad*> loads;
  for (const auto& l : scene.pointLoads) loads.push_back(&l);
  if (!loads.empty()) {
    geo << "<Loadpointlist>";
    for (const auto* l : loads) geo << pointElement(l->point.initial + scene.origin);
    geo << "</Loadpointlist>\n";
  }
  if (!scene.monitors.empty()) {
    geo << "<Measuredpointlist>";
    for (const auto& m : scene.monitors) geo << pointElement(m.point.initial + scene.origin);
    geo << "</Measuredpointlist>\n";
  }
  if (!scene.supports.empty()) {
    geo << "<Boltlist>";
    for (const auto& s : scene.supports) {
      const Vec2 h = s.head.initial + scene.origin, e = s.end.initial + scene.origin;
      geo << "<Bolt type=\"1\"> " << num(h.x()) << " " << num(h.y()) << " " << num(e.x()) << " " << num(e.y()) << " </Bolt>";
    }
    geo << "</Boltlist>\n";
  }
  std::vector<std::string> matLines;
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (scene.blocks[b].material == 0) continue;
    // A short line inside the block: Shi's material assignment finds its block by position.
    const Vec2 p = interiorPoint(blocks[b]);
    const Vec2 q = p + Vec2(1e-3 * minLen, 0);
    matLines.push_back("<Line type=\"" + std::to_string(scene.blocks[b].material + 1) + "\"> " + num(p.x()) + " " + num(p.y()) + " " +
                       num(q.x()) + " " + num(q.y()) + " </Line>");
  }
  if (!matLines.empty()) {
    geo << "<Matlinelist>";
    for (const auto& l : matLines) geo << l;
    geo << "</Matlinelist>\n";
  }
  geo << "</Berkeley:Geometry>\n</Berkeley:DDA>\n";
  files.geometry = geo.str();

  const char* kind = st.mode == model::AnalysisMode::Static ? "static" : "dynamic";
  std::ostringstream ana;
  ana << "<?xml version=\"1.0\" standalone=\"no\"?>\n<!DOCTYPE DDA SYSTEM \"analysis.dtd\">\n"
      << "<Berkeley:DDA xmlns:Berkeley=\"http://www.tsoft.com/~bdoolin/dda\">\n"
      << "<!-- from " << caseName << " by ddaslope convert; penalty " << num(penalty) << " N/m -->\n"
      << "<Analysis type=\"" << kind << "\">\n"
      << "  <Analysistype type=\"" << kind << "\"/>\n  <Rotation type=\"linear\"/>\n  <Gravity flag=\"no\"/>\n"
      << "  <Gravaccel value=\"" << num(g) << "\"/>\n  <Autotimestep flag=\"no\"/>\n"
      << "  <Autopenalty flag=\"no\" pfactor=\"" << num(penalty / maxE) << "\"/>\n"
      << "  <Planestrain flag=\"" << (st.plane == model::PlaneMode::Strain ? "yes" : "no") << "\"/>\n"
      << "  <Numtimesteps timesteps=\"" << steps << "\"/>\n  <Maxtimestep maxtimestep=\"" << num(st.timeStep) << "\"/>\n"
      << "  <Maxdisplacement maxdisplacement=\"" << num(g2) << "\"/>\n  <Saveinterval step=\"" << steps << "\"/>\n";
  for (const auto& m : scene.materials)
    ana << "  <Blockmaterial type=\"" << (&m - scene.materials.data()) + 1 << "\">\n"
        << "    <Unitmass> " << num(m.density) << " </Unitmass>\n    <Unitweight> " << num(m.density * g) << " </Unitweight>\n"
        << "    <Youngsmod> " << num(m.youngModulus) << " </Youngsmod>\n    <Poissonratio> " << num(m.poissonRatio) << " </Poissonratio>\n"
        << "    <Damping> 0.0 </Damping>\n    <Istress> 0 0 0 </Istress>\n    <Ivelocity> 0 0 0 </Ivelocity>\n"
        << "    <Istrain> 0 0 0 </Istrain>\n  </Blockmaterial>\n";
  for (const auto& j : scene.joints) {
    ana << "  <Jointproperties type=\"" << (&j - scene.joints.data()) + 1 << "\">\n"
        << "    <Friction> " << degrees(j.frictionAngle) << " </Friction>\n    <Cohesion> " << num(j.cohesion) << " </Cohesion>\n"
        << "    <Tensile> " << num(j.tensileStrength) << " </Tensile>\n  </Jointproperties>\n";
    if (j.bartonBandis) notes.push_back("joint " + j.name + ": Barton–Bandis law written as its residual friction angle only");
    if (j.residualFrictionAngle || j.residualCohesion > 0 || (j.weakeningDistance && *j.weakeningDistance > 0))
      notes.push_back("joint " + j.name + ": softening to residual strength not written (ntdda's bond is brittle)");
    if (j.normalStiffness > 0 || j.shearStiffness > 0) notes.push_back("joint " + j.name + ": joint stiffness not written (ntdda uses its penalty)");
  }
  if (!loads.empty()) {
    ana << "  <Loadpointlist>\n";
    for (const auto* l : loads) {
      const Vec2 f1 = l->at(st.duration);
      ana << "    <Loadpoint numpoints=\"2\"> 0 " << num(l->force.x()) << " " << num(l->force.y()) << "; " << num(st.duration) << " "
          << num(f1.x()) << " " << num(f1.y()) << "; </Loadpoint>\n";
    }
    ana << "  </Loadpointlist>\n";
  }
  if (!scene.supports.empty()) {
    const auto& s = scene.supports.front();
    ana << "  <Boltproperties> " << num(s.stiffness) << " " << num(std::isfinite(s.capacity) ? s.capacity : 0) << " " << num(s.pretension)
        << " </Boltproperties>\n";
    for (const auto& o : scene.supports)
      if (o.stiffness != s.stiffness || o.capacity != s.capacity || o.pretension != s.pretension)
        notes.push_back("support " + o.id + ": ntdda gives every bolt the first bolt's properties (" + s.id + ")");
    notes.push_back("supports: written per metre of slope, as ntdda's bolts; spacing, bond, failure and compression are not held by ntdda's bolt");
  }
  ana << "</Analysis>\n</Berkeley:DDA>\n";
  files.analysis = ana.str();

  if (!scene.edgeLoads.empty()) notes.push_back("edge loads: written as the load points of their Gauss points");
  if (scene.water.active() || scene.water.ru > 0) notes.push_back("water: not written (ntdda has no water pressure)");
  if (scene.seismic.active()) notes.push_back("seismic loading: not written");
  for (const auto& b : scene.blocks)
    if (b.velocity.head<3>().norm() > 0) {
      notes.push_back("initial block velocities: not written (ntdda sets them per material)");
      break;
    }
  if (st.rigidBlocks) notes.push_back("analysis.blocks rigid: not written (ntdda's blocks deform)");
  notes.push_back("analysis.initial_equilibrium: ntdda starts with gravity at once (<Gravity flag=\"no\">), not at rest under it");
  return files;
}

}  // namespace ddaslope::io
