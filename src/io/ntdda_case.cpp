// An ntdda model as a ddaslope case: blocks cut from the joint lines, the points and properties
// mapped onto the case's keys, and every element that has no counterpart named in a note.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/io/ntdda_model.hpp"

namespace ddaslope::io {
namespace {

using Json = nlohmann::ordered_json;

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string at(const std::string& file, const NtddaSource& s) { return file + ":" + std::to_string(s.line) + ": <" + s.element + ">"; }

/// Top-level keys one to a line and the items of arrays of objects one to a line: a case a
/// person can read and diff.
std::string caseText(const Json& c) {
  std::string out = "{\n";
  size_t k = 0;
  for (const auto& [key, value] : c.items()) {
    out += "  " + Json(key).dump() + ": ";
    if (value.is_array() && !value.empty() && value.front().is_object()) {
      out += "[\n";
      for (size_t i = 0; i < value.size(); ++i) out += "    " + value[i].dump() + (i + 1 < value.size() ? ",\n" : "\n");
      out += "  ]";
    } else if (value.is_object() && !value.empty() && value.begin()->is_object()) {
      out += "{\n";
      size_t i = 0;
      for (const auto& [name, item] : value.items())
        out += "    " + Json(name).dump() + ": " + item.dump() + (++i < value.size() ? ",\n" : "\n");
      out += "  }";
    } else {
      out += value.dump();
    }
    out += ++k < c.size() ? ",\n" : "\n";
  }
  return out + "}\n";
}

/// The first block holding p (inside or on its boundary), or else the first within tol of it
/// (a point drawn on a line that the node merge moved); −1 for none.
int blockHolding(const std::vector<std::vector<Vec2>>& blocks, const Vec2& p, double tol) {
  for (double t : {0.0, tol})
    for (size_t b = 0; b < blocks.size(); ++b)
      if (geometry::containsPoint(blocks[b], p, t)) return static_cast<int>(b);
  return -1;
}

/// Blocks the segment ab passes through or runs along (within tol of their boundary).
std::set<int> blocksCrossed(const std::vector<std::vector<Vec2>>& blocks, const Vec2& a, const Vec2& b, double tol) {
  std::vector<double> ts{0.0, 1.0};
  const Vec2 r = b - a;
  for (const auto& poly : blocks)
    for (size_t i = 0; i < poly.size(); ++i) {
      const Vec2 &c = poly[i], &d = poly[(i + 1) % poly.size()];
      const Vec2 s = d - c;
      const double den = cross(r, s);
      if (std::abs(den) < 1e-15 * r.norm() * s.norm()) continue;
      const double t = cross(c - a, s) / den, u = cross(c - a, r) / den;
      if (t > 0 && t < 1 && u >= 0 && u <= 1) ts.push_back(t);
    }
  std::sort(ts.begin(), ts.end());
  std::set<int> crossed;
  for (size_t i = 0; i + 1 < ts.size(); ++i) {
    if (ts[i + 1] - ts[i] < 1e-12) continue;
    const Vec2 mid = a + 0.5 * (ts[i] + ts[i + 1]) * r;
    for (size_t k = 0; k < blocks.size(); ++k)
      if (geometry::containsPoint(blocks[k], mid, tol)) crossed.insert(static_cast<int>(k));
  }
  return crossed;
}

/// Does segment ab cross (or touch) the block's boundary?
bool crossesBoundary(const std::vector<Vec2>& poly, const Vec2& a, const Vec2& b) {
  for (size_t i = 0; i < poly.size(); ++i)
    if (geometry::segmentsIntersect(a, b, poly[i], poly[(i + 1) % poly.size()])) return true;
  return false;
}

}  // namespace

ConvertedModel convertNtddaModel(const NtddaGeometry& g, const NtddaAnalysis* a) {
  ConvertedModel out;
  auto& notes = out.notes;
  const std::string& gf = g.file;

  int jointTypes = 0;
  for (const NtddaLine& l : g.joints) jointTypes = std::max(jointTypes, l.type);
  if (a) {
    for (const NtddaLine& l : g.joints)
      if (l.type > static_cast<int>(a->joints.size()))
        throw InputError(gf, l.source.where(), "expected a joint type from 1 to " + std::to_string(a->joints.size()) +
                                                    " (the joint properties of " + a->file + "), found " + std::to_string(l.type));
    jointTypes = static_cast<int>(a->joints.size());
  }
  const int materialCount = a ? static_cast<int>(a->materials.size()) : [&] {
    int m = 1;
    for (const NtddaLine& l : g.materialLines) m = std::max(m, l.type);
    return m;
  }();
  for (const NtddaLine& l : g.materialLines)
    if (l.type > materialCount)
      throw InputError(gf, l.source.where(), "expected a material from 1 to " + std::to_string(materialCount) +
                                                  " (the block materials of " + (a ? a->file : "the model") + "), found " + std::to_string(l.type));

  // Blocks: the bounded faces of the joint lines, nodes merged as ntdda merges them (dc02: within
  // 1.25 e00 w0).
  const double w0 = ntddaScale(g.joints);
  const double merge = 1.25 * g.edgeNodeDistance * w0;
  std::vector<geometry::TypedSegment> segments;
  for (const NtddaLine& l : g.joints) segments.push_back({l.a, l.b, l.type});
  out.arrangement = geometry::arrangeLines(segments, merge);
  const auto& arr = out.arrangement;
  const auto& blocks = arr.faces;
  if (blocks.empty())
    throw InputError(gf, "", "expected joint lines that close at least one block, found " + std::to_string(g.joints.size()) +
                                 " lines closing none (lines meet where an end lies within the edge-node distance " +
                                 fmt(merge) + " m of another line)");
  if (arr.danglingEdges > 0)
    notes.push_back(gf + ": " + std::to_string(arr.danglingEdges) + " piece(s) of joint lines bound no block (ends past the last crossing, lines closing nothing): dropped, as Shi's block cutting drops them");
  if (arr.bridgeEdges > 0)
    notes.push_back(gf + ": " + std::to_string(arr.bridgeEdges) + " piece(s) of joint lines join two closed groups of blocks and bound none: dropped");
  if (arr.typeConflicts > 0)
    notes.push_back(gf + ": " + std::to_string(arr.typeConflicts) + " piece(s) where joint lines of different types overlap: the first line's type is kept");
  if (arr.holedFaces > 0)
    notes.push_back(gf + ": " + std::to_string(arr.holedFaces) + " region(s) with other blocks inside them, untouched (a block with a hole): not made blocks");
  if (arr.pinchedFaces > 0)
    notes.push_back(gf + ": " + std::to_string(arr.pinchedFaces) + " region(s) whose boundary touches itself: not made blocks");

  double scale = 0;
  for (const auto& b : blocks)
    for (const Vec2& p : b) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  const double tol = std::max(merge, 1e-9 * std::max(scale, 1.0));

  // Materials (ntdda's dc13): a material line gives its material to every block whose boundary
  // it crosses, or else to the block holding its first point; later lines win; others get 1.
  std::vector<int> material(blocks.size(), 1);
  for (const NtddaLine& l : g.materialLines) {
    bool any = false;
    for (size_t b = 0; b < blocks.size(); ++b)
      if (crossesBoundary(blocks[b], l.a, l.b)) material[b] = l.type, any = true;
    if (any) continue;
    const int b = blockHolding(blocks, l.a, 0);
    if (b >= 0) material[b] = l.type;
    else notes.push_back(at(gf, l.source) + ": material line in no block and crossing none: not used");
  }

  // Fixed points: two or more in a block hold it (ntdda's springs then take all its rigid
  // motion): a fixed block; a single one pins it at that point: a fixed point of the case.
  std::vector<std::vector<Vec2>> fixedIn(blocks.size());
  for (const NtddaPoint& p : g.fixedPoints) {
    const int b = blockHolding(blocks, p.p, tol);
    if (b < 0) notes.push_back(at(gf, p.source) + ": fixed point (" + fmt(p.p.x()) + ", " + fmt(p.p.y()) + ") in no block: not used");
    else fixedIn[b].push_back(p.p);
  }
  std::vector<bool> fixed(blocks.size(), false);
  for (const NtddaLine& l : g.fixedLines) {
    const std::set<int> crossed = blocksCrossed(blocks, l.a, l.b, tol);
    if (crossed.empty()) notes.push_back(at(gf, l.source) + ": fixed line through no block: not used");
    for (int b : crossed) fixed[b] = true;
  }
  Json fixedPoints = Json::array();
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (fixedIn[b].size() >= 2) fixed[b] = true;
    if (!fixed[b] && fixedIn[b].size() == 1)
      fixedPoints.push_back({{"block", "b" + std::to_string(b + 1)}, {"point", {fixedIn[b][0].x(), fixedIn[b][0].y()}}});
  }

  // Joints between blocks: the type of the lines along their shared boundary; the type with
  // the most shared length is the default.
  std::map<std::pair<int, int>, std::map<int, double>> pairTypes;
  std::map<int, double> typeLength;
  for (const auto& e : arr.edges)
    if (e.left >= 0 && e.right >= 0) {
      pairTypes[{std::min(e.left, e.right), std::max(e.left, e.right)}][e.type] += e.length;
      typeLength[e.type] += e.length;
    }
  int defaultType = 1;
  for (const auto& [t, len] : typeLength)
    if (!typeLength.count(defaultType) || len > typeLength.at(defaultType)) defaultType = t;
  Json jointPairs = Json::array();
  for (const auto& [pair, types] : pairTypes) {
    auto best = std::max_element(types.begin(), types.end(), [](const auto& p, const auto& q) { return p.second < q.second; });
    if (types.size() > 1)
      notes.push_back(gf + ": blocks b" + std::to_string(pair.first + 1) + " and b" + std::to_string(pair.second + 1) +
                      " meet along joint lines of " + std::to_string(types.size()) + " types: joint j" + std::to_string(best->first) +
                      " (the longest) taken for the whole contact");
    if (best->first != defaultType)
      jointPairs.push_back({{"blocks", {"b" + std::to_string(pair.first + 1), "b" + std::to_string(pair.second + 1)}},
                            {"joint", "j" + std::to_string(best->first)}});
  }

  Json c;
  c["description"] = "converted by ddaslope convert from Shi's DDA model " + gf + (a ? " and " + a->file : std::string()) +
                     ": " + std::to_string(g.joints.size()) + " joint lines cut into " + std::to_string(blocks.size()) + " blocks";
  const double gacc = a ? a->gravity : 9.81;
  c["gravity"] = {0.0, -gacc};
  Json materials = Json::object();
  for (int m = 0; m < materialCount; ++m) {
    if (!a) {
      materials["m" + std::to_string(m + 1)] = {{"density", 2600.0}, {"young_modulus", 1e10}, {"poisson_ratio", 0.25}};
      continue;
    }
    const NtddaMaterial& mat = a->materials[m];
    materials["m" + std::to_string(m + 1)] = {{"density", mat.unitMass}, {"young_modulus", mat.youngModulus}, {"poisson_ratio", mat.poissonRatio}};
    const std::string where = at(a->file, mat.source);
    if (mat.unitMass > 0 && std::abs(mat.unitWeight - mat.unitMass * gacc) > 1e-6 * std::abs(mat.unitMass * gacc))
      notes.push_back(where + ": unit weight " + fmt(mat.unitWeight) + " is not unit mass × gravity (" + fmt(mat.unitMass * gacc) +
                      "): the case takes the unit mass as density and the weight from gravity");
    if (mat.damping != 0) notes.push_back(where + ": damping " + fmt(mat.damping) + " not mapped (ddaslope damps strain modes by analysis.strain_damping)");
    if (mat.stress[0] != 0 || mat.stress[1] != 0 || mat.stress[2] != 0)
      notes.push_back(where + ": initial stress not mapped (blocks start unstressed)");
    if (mat.strain[0] != 0 || mat.strain[1] != 0 || mat.strain[2] != 0)
      notes.push_back(where + ": initial strain not mapped (blocks start unstrained)");
  }
  if (!a) notes.push_back(gf + ": no analysis file: materials m1-m" + std::to_string(materialCount) +
                          " are a placeholder rock (2600 kg/m³, 10 GPa, ν 0.25), joints j1-j" + std::to_string(jointTypes) +
                          " φ 30°, and the analysis runs 1 s; set them before running");
  c["materials"] = materials;
  Json joints = Json::object();
  for (int j = 0; j < jointTypes; ++j) {
    if (!a) {
      joints["j" + std::to_string(j + 1)] = {{"friction_angle", 30.0}, {"cohesion", 0.0}, {"tensile_strength", 0.0}};
      continue;
    }
    const NtddaJointType& jt = a->joints[j];
    joints["j" + std::to_string(j + 1)] = {{"friction_angle", jt.friction}, {"cohesion", jt.cohesion}, {"tensile_strength", jt.tensile}};
  }
  c["joints"] = joints;
  c["default_joint"] = "j" + std::to_string(defaultType);
  if (!jointPairs.empty()) c["joint_pairs"] = jointPairs;

  Json blockList = Json::array();
  for (size_t b = 0; b < blocks.size(); ++b) {
    Json v = Json::array();
    for (const Vec2& p : blocks[b]) v.push_back({p.x(), p.y()});
    Json block = {{"id", "b" + std::to_string(b + 1)}, {"material", "m" + std::to_string(material[b])}};
    if (fixed[b]) block["fixed"] = true;
    block["vertices"] = v;
    if (a && !fixed[b]) {
      const double* vel = a->materials[material[b] - 1].velocity;
      if (vel[0] != 0 || vel[1] != 0) block["velocity"] = {vel[0], vel[1]};
      if (vel[2] != 0) block["angular_velocity"] = vel[2];
    }
    blockList.push_back(block);
    out.fixedBlocks += fixed[b];
  }
  out.blocks = static_cast<int>(blocks.size());
  c["blocks"] = blockList;

  Json monitors = Json::array();
  for (const NtddaPoint& p : g.measuredPoints) {
    const int b = blockHolding(blocks, p.p, tol);
    if (b < 0) {
      notes.push_back(at(gf, p.source) + ": measured point (" + fmt(p.p.x()) + ", " + fmt(p.p.y()) + ") in no block: not mapped");
      continue;
    }
    monitors.push_back({{"id", "p" + std::to_string(monitors.size() + 1)}, {"block", "b" + std::to_string(b + 1)}, {"point", {p.p.x(), p.p.y()}}});
  }
  if (!monitors.empty()) c["monitors"] = monitors;

  // Load points, each with its force history of the analysis (in order): a history linear in
  // time is a point load's force + rate·t.
  Json loads = Json::array();
  const double duration = a ? a->steps * a->timeStep : 1.0;
  for (size_t k = 0; k < g.loadPoints.size(); ++k) {
    const NtddaPoint& p = g.loadPoints[k];
    const int b = blockHolding(blocks, p.p, tol);
    if (b < 0) {
      notes.push_back(at(gf, p.source) + ": load point in no block: not mapped");
      continue;
    }
    if (!a || k >= a->loads.size()) {
      notes.push_back(at(gf, p.source) + ": load point without a force history in the analysis: not mapped");
      continue;
    }
    const auto& rec = a->loads[k].records;
    Vec2 force(rec[0].y(), rec[0].z()), rate(0, 0);
    if (rec.size() >= 2 && rec[1].x() != rec[0].x()) {
      rate = Vec2(rec[1].y() - rec[0].y(), rec[1].z() - rec[0].z()) / (rec[1].x() - rec[0].x());
      force -= rate * rec[0].x();
    }
    bool linear = true;
    for (const Vec3& r : rec) {
      const Vec2 f(r.y(), r.z()), fit = force + rate * r.x();
      linear = linear && (f - fit).norm() <= 1e-9 * std::max(f.norm(), fit.norm()) + 1e-300;
    }
    if (!linear)
      notes.push_back(at(a->file, a->loads[k].source) + ": force history not linear in time: taken as the line through its first two records");
    Json load = {{"id", "load" + std::to_string(loads.size() + 1)}, {"block", "b" + std::to_string(b + 1)},
                 {"point", {p.p.x(), p.p.y()}}, {"force", {force.x(), force.y()}}};
    if (rate.x() != 0 || rate.y() != 0) load["rate"] = {rate.x(), rate.y()};
    loads.push_back(load);
  }
  if (a && a->loads.size() > g.loadPoints.size())
    notes.push_back(a->file + ": " + std::to_string(a->loads.size() - g.loadPoints.size()) + " force histories without a load point: not used");
  if (!loads.empty()) c["point_loads"] = loads;

  // Bolts: every bolt takes the first bolt properties, as ntdda gives them.
  Json supports = Json::array();
  for (const NtddaLine& l : g.bolts) {
    const int h = blockHolding(blocks, l.a, tol), e = blockHolding(blocks, l.b, tol);
    if (h < 0 || e < 0 || h == e || (fixed[h] && fixed[e])) {
      notes.push_back(at(gf, l.source) + ": bolt not mapped: its ends must lie in two different blocks, not both fixed");
      continue;
    }
    Json s = {{"id", "bolt" + std::to_string(supports.size() + 1)}, {"head", {l.a.x(), l.a.y()}}, {"end", {l.b.x(), l.b.y()}}};
    if (a && !a->bolts.empty()) {
      const auto& bp = a->bolts.front();
      s["stiffness"] = bp.stiffness;
      if (bp.strength > 0) s["capacity"] = bp.strength;
      s["pretension"] = bp.pretension;
    } else {
      notes.push_back(at(gf, l.source) + ": bolt without <Boltproperties> in the analysis: a spring of no stiffness");
    }
    supports.push_back(s);
  }
  if (a && a->bolts.size() > 1) notes.push_back(at(a->file, a->bolts[1].source) + ": bolt properties after the first are unused (ntdda gives every bolt the first)");
  if (!supports.empty()) c["supports"] = supports;
  if (!fixedPoints.empty()) c["fixed_points"] = fixedPoints;

  for (const NtddaPoint& p : g.holePoints) notes.push_back(at(gf, p.source) + ": hole point not mapped (ddaslope has no holes in blocks)");
  for (const NtddaPoint& p : g.seismicPoints) notes.push_back(at(gf, p.source) + ": seismic point not mapped (use the case's seismic section)");
  for (const NtddaLine& l : g.boundaryLines) notes.push_back(at(gf, l.source) + ": boundary line not mapped (the blocks' outline is their boundary)");
  for (const NtddaSource& s : g.unmapped) notes.push_back(at(gf, s) + ": not mapped");
  for (const std::string& n : g.notes) notes.push_back(gf + ": " + n);

  Json analysis;
  if (a) {
    analysis["duration"] = duration;
    analysis["time_step"] = a->timeStep;
    if (!a->dynamic) analysis["mode"] = "static";
    if (!a->planeStrain) analysis["plane"] = "stress";
    double maxE = 0;
    for (const auto& m : a->materials) maxE = std::max(maxE, m.youngModulus);
    analysis["penalty"] = a->penaltyFactor * maxE;
    if (a->maxDisplacement > 0) {
      const double g2 = std::clamp(a->maxDisplacement, 1e-5, 0.1);
      if (g2 != a->maxDisplacement)
        notes.push_back(a->file + ": maximum displacement ratio " + fmt(a->maxDisplacement) + " outside ddaslope's [1e-5, 0.1]: " + fmt(g2));
      analysis["max_displacement_ratio"] = g2;
    }
    if (a->autoPenalty)
      notes.push_back(a->file + ": automatic penalty: ntdda adapts it during the run; the case holds pfactor × largest E = " +
                      fmt(a->penaltyFactor * maxE) + " N/m fixed");
    if (a->xml && !a->gravityPhase)
      notes.push_back(a->file + ": <Gravity flag=\"no\">: ntdda applies gravity at once from the first step; the case keeps ddaslope's start at rest under gravity (set analysis.initial_equilibrium false for ntdda's start)");
    for (const NtddaSource& s : a->unmapped) notes.push_back(at(a->file, s) + ": not mapped");
    for (const std::string& n : a->notes) notes.push_back(a->file + ": " + n);
  } else {
    analysis["duration"] = 1.0;
  }
  c["analysis"] = analysis;
  // A product of the model's numbers may overflow (pfactor × E, a force history's rate); the case
  // must hold finite numbers only (JSON has no others).
  const std::function<void(const Json&, const std::string&)> finite = [&](const Json& j, const std::string& path) {
    if (j.is_number_float() && !std::isfinite(j.get<double>()))
      throw InputError(a ? a->file : gf, "", "the model's values overflow in the case's " + path + "; check the values it is made of");
    if (j.is_structured())
      for (const auto& [k, v] : j.items()) finite(v, path.empty() ? k : path + "." + k);
  };
  finite(c, "");
  out.caseJson = caseText(c);
  return out;
}

}  // namespace ddaslope::io
