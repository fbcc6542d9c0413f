#include "ddaslope/io/case_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/io/csv_series.hpp"
#include "ddaslope/io/ground_motion.hpp"
#include "json_input.hpp"
#include "ddaslope/model/input_limits.hpp"
#include "ddaslope/model/kinks.hpp"
#include "ddaslope/model/presets.hpp"
#include "points_reader.hpp"
#include "scene_normalisation.hpp"
#include "section_reader.hpp"

namespace ddaslope::io {
namespace {

namespace limits = model::limits;

using case_json::json;
using case_json::Reader;
using case_json::typeName;

void readMaterials(const Reader& r, const json& doc, model::Scene& s, std::map<std::string, int>& ids) {
  const json& mats = r.required(doc, "", "materials");
  r.object(mats, "materials");
  if (mats.empty()) r.fail("materials", "expected at least one material");
  for (const auto& [name, m] : mats.items()) {
    const std::string p = "materials." + name;
    r.onlyKeys(m, p, {"density", "unit_weight", "young_modulus", "poisson_ratio"});
    model::Material mat;
    mat.name = r.identifier(name, p);
    if (m.contains("density") == m.contains("unit_weight"))
      r.fail(p, "expected one of density (kg/m³) and unit_weight (kN/m³, as RS2 and Slide2 take it; density = "
                "1000·γ/g), " + std::string(m.contains("density") ? "found both" : "found neither"));
    if (m.contains("unit_weight")) {
      // γ in kN/m³ under the case's own gravity (9.81 m/s² unless it says otherwise).
      if (!(s.gravity.norm() > 0))
        r.fail(p + ".unit_weight", "a unit weight is a density under gravity, and the case has none: give density");
      const double g = s.gravity.norm();
      const double gamma = r.numberIn(m.at("unit_weight"), p + ".unit_weight", limits::kMinDensity * g / 1e3,
                                      limits::kMaxDensity * g / 1e3, false, false,
                                      "a unit weight in kN/m³ (a density of 1 to 1e5 kg/m³)");
      mat.density = gamma * 1e3 / g;
    } else {
      mat.density = r.numberIn(m.at("density"), p + ".density", limits::kMinDensity, limits::kMaxDensity, false,
                               false, "a density in [1, 1e5] kg/m³ (or give unit_weight in kN/m³)");
    }
    mat.youngModulus = r.numberIn(r.required(m, p, "young_modulus"), p + ".young_modulus", limits::kMinYoungModulus,
                                  limits::kMaxYoungModulus, false, false, "a Young's modulus in [1e3, 1e15] Pa");
    mat.poissonRatio = r.numberIn(r.required(m, p, "poisson_ratio"), p + ".poisson_ratio", 0, 0.5,
                                  false, true, "a Poisson's ratio in [0, 0.5)");
    ids[name] = static_cast<int>(s.materials.size());
    s.materials.push_back(mat);
  }
}

/// Peak-to-residual softening of a joint (docs/case-format.md, "Joint").
void readWeakening(const Reader& r, const json& jn, const std::string& p, model::JointProperties& jp) {
  if (jn.contains("residual_friction_angle"))
    jp.residualFrictionAngle = degToRad(r.numberIn(jn.at("residual_friction_angle"), p + ".residual_friction_angle",
                                                   0, 90, false, true, "a friction angle in [0, 90) degrees"));
  jp.residualCohesion = r.optionalIn(jn, p, "residual_cohesion", 0, 0, 1e12, false, false, "a cohesion ≥ 0 Pa");
  if (jn.contains("weakening_distance"))
    jp.weakeningDistance = r.numberIn(jn.at("weakening_distance"), p + ".weakening_distance", 0, 1e6, false, false,
                                      "a slip distance ≥ 0 m (0: brittle)");
  jp.weakeningLaw = r.choice(jn, p, "weakening_law", "linear", {"linear", "exponential"}) == "exponential"
                        ? model::WeakeningLaw::Exponential
                        : model::WeakeningLaw::Linear;
  if (jp.residualFrictionAngle && *jp.residualFrictionAngle > jp.frictionAngle)
    r.fail(p + ".residual_friction_angle", "expected a residual friction angle ≤ the peak friction_angle (" +
                                               std::to_string(radToDeg(jp.frictionAngle)) + "°)");
  if (jp.residualCohesion > jp.cohesion)
    r.fail(p + ".residual_cohesion", "expected a residual cohesion ≤ the peak cohesion (" +
                                         std::to_string(jp.cohesion) + " Pa)");
}

/// A Barton–Bandis joint: φr (residual_friction_angle), JRC and JCS, with Barton & Bandis's (1982)
/// scale correction from the laboratory sample's length to the field block's when `scale` gives
/// them: JRC_n = JRC_0 (L_n/L_0)^(−0.02 JRC_0), JCS_n = JCS_0 (L_n/L_0)^(−0.03 JRC_0).
void readBartonBandis(const Reader& r, const json& jn, const std::string& p, model::JointProperties& jp) {
  for (const char* key : {"friction_angle", "cohesion", "residual_cohesion"})
    if (jn.contains(key))
      r.fail(Reader::join(p, key), "a Barton–Bandis joint's strength is σn tan(φr + JRC log10(JCS/σn)): give "
                                   "residual_friction_angle (φr), jrc and jcs, without friction_angle or cohesion");
  jp.frictionAngle = degToRad(r.numberIn(r.required(jn, p, "residual_friction_angle"), p + ".residual_friction_angle",
                                         0, 90, false, true, "a residual friction angle φr in [0, 90) degrees"));
  model::JointProperties::BartonBandis bb;
  bb.jrc = r.numberIn(r.required(jn, p, "jrc"), p + ".jrc", 0, 20, false, false, "a JRC in [0, 20]");
  bb.jcs = r.numberIn(r.required(jn, p, "jcs"), p + ".jcs", 1e5, 1e9, false, false,
                      "a JCS in [1e5, 1e9] Pa (0.1 to 1000 MPa)");
  if (jn.contains("scale")) {
    const json& sc = jn.at("scale");
    const std::string q = p + ".scale";
    r.onlyKeys(sc, q, {"lab_length", "field_length"});
    const double lab = r.optionalIn(sc, q, "lab_length", 0.1, 0, 1e3, true, false, "a sample length in (0, 1000] m");
    const double field = r.numberIn(r.required(sc, q, "field_length"), q + ".field_length", 0, 1e4, true, false,
                                    "a block length in (0, 1e4] m");
    const double jrc0 = bb.jrc;
    bb.jrc = jrc0 * std::pow(field / lab, -0.02 * jrc0);
    bb.jcs = bb.jcs * std::pow(field / lab, -0.03 * jrc0);
  }
  jp.bartonBandis = bb;
}

void readJoints(const Reader& r, const json& doc, model::Scene& s, std::map<std::string, int>& ids) {
  const json& joints = r.required(doc, "", "joints");
  r.object(joints, "joints");
  if (joints.empty()) r.fail("joints", "expected at least one joint");
  for (const auto& [name, jn] : joints.items()) {
    const std::string p = "joints." + name;
    r.onlyKeys(jn, p, {"law", "friction_angle", "cohesion", "tensile_strength", "bond", "residual_friction_angle",
                       "residual_cohesion", "weakening_distance", "weakening_law", "jrc", "jcs", "scale",
                       "normal_stiffness", "shear_stiffness"});
    model::JointProperties jp;
    jp.name = r.identifier(name, p);
    if (r.choice(jn, p, "law", "mohr_coulomb", {"mohr_coulomb", "barton_bandis"}) == "barton_bandis") {
      readBartonBandis(r, jn, p, jp);
    } else {
      for (const char* key : {"jrc", "jcs", "scale"})
        if (jn.contains(key)) r.fail(Reader::join(p, key), "used only by a Barton–Bandis joint (\"law\": \"barton_bandis\")");
      jp.frictionAngle = degToRad(r.numberIn(r.required(jn, p, "friction_angle"), p + ".friction_angle",
                                             0, 90, false, true, "a friction angle in [0, 90) degrees"));
    }
    jp.cohesion = r.optionalIn(jn, p, "cohesion", 0, 0, 1e12, false, false, "a cohesion ≥ 0 Pa");
    jp.tensileStrength = r.optionalIn(jn, p, "tensile_strength", 0, 0, 1e12, false, false,
                                      "a tensile strength ≥ 0 Pa");
    const std::string bond = r.choice(jn, p, "bond", "initial", {"initial", "none", "always"});
    jp.bond = bond == "none" ? model::BondPolicy::None
                             : (bond == "always" ? model::BondPolicy::Always : model::BondPolicy::Initial);
    readWeakening(r, jn, p, jp);
    if (jp.bartonBandis) jp.bartonBandis->wears = jn.contains("weakening_distance");
    // From a soft infilled joint (1e7 Pa/m) to a rigid stand-in (RS2's 1e14, UDEC's up to 1e15).
    const std::string range = "a stiffness in [1e6, 1e15] Pa/m (stress per metre of closure or slip)";
    jp.normalStiffness = r.optionalIn(jn, p, "normal_stiffness", 0, 1e6, 1e15, false, false, range);
    jp.shearStiffness = r.optionalIn(jn, p, "shear_stiffness", 0, 1e6, 1e15, false, false, range);
    ids[name] = static_cast<int>(s.joints.size());
    s.joints.push_back(jp);
  }
  if (doc.contains("default_joint")) {
    const std::string name = r.string(doc.at("default_joint"), "default_joint");
    if (!ids.count(name)) r.fail("default_joint", "unknown joint \"" + name + "\" (not in joints)");
    s.defaultJoint = ids.at(name);
  } else if (s.joints.size() > 1) {
    r.fail("default_joint", "required key is missing (the case has several joints)");
  }
}

/// Where an outline stops being a simple polygon, by the vertices' indices as the case numbers them.
std::string whereNotSimple(const std::vector<Vec2>& v, const geometry::SimplicityDefect& d) {
  const auto at = [&](size_t k) {
    std::ostringstream p;
    p << "vertex " << k << " (" << v[k].x() << ", " << v[k].y() << ")";
    return p.str();
  };
  switch (d.kind) {
    case geometry::SimplicityDefect::Kind::RepeatedVertex:
      return "vertices " + std::to_string(d.first) + " and " + std::to_string(d.second) + " repeated at " + at(d.first);
    case geometry::SimplicityDefect::Kind::CrossingEdges:
      return "a self-intersecting outline: the edge from " + at(d.first) + " meets the edge from " + at(d.second);
    case geometry::SimplicityDefect::Kind::Fold:
      return "an outline folded back on itself at " + at(d.first);
  }
  return "one that is self-intersecting, folded or has repeated vertices";
}

/// Blocks may touch but not overlap: at the first step the contacts would thrust an overlap
/// apart with the penalty times its depth, and a search would read the explosion as failure at
/// every strength. Overlaps thinner than 1e-4 of the scene (rounded coordinates) are the initial
/// contacts' business. Two fixed blocks never meet in contact and may overlap.
void checkOverlaps(const Reader& r, const model::Scene& s, double size) {
  const size_t n = s.blocks.size();
  std::vector<geometry::Aabb> boxes(n);
  std::vector<size_t> order(n);
  for (size_t b = 0; b < n; ++b) boxes[b] = geometry::boundingBox(s.blocks[b].vertices), order[b] = b;
  std::sort(order.begin(), order.end(), [&](size_t x, size_t y) { return boxes[x].lo.x() < boxes[y].lo.x(); });
  const double tol = 1e-9 * size;
  for (size_t i = 0; i < n; ++i) {
    const size_t a = order[i];
    for (size_t k = i + 1; k < n && boxes[order[k]].lo.x() < boxes[a].hi.x(); ++k) {
      const size_t b = order[k];
      if (s.blocks[a].fixed && s.blocks[b].fixed) continue;
      if (boxes[b].lo.y() >= boxes[a].hi.y() || boxes[a].lo.y() >= boxes[b].hi.y()) continue;
      const geometry::Overlap o = geometry::overlapOf(s.blocks[a].vertices, s.blocks[b].vertices, tol);
      const double depth = o.perimeter > 0 ? 2 * o.area / o.perimeter : 0;
      if (depth <= 1e-4 * size) continue;
      const size_t first = std::min(a, b), second = std::max(a, b);
      std::ostringstream m;
      m << "block \"" << s.blocks[second].id << "\" overlaps block \"" << s.blocks[first].id << "\" (blocks["
        << first << "]): " << o.area << " m² in common, about " << depth << " m deep (2·area/perimeter), near ("
        << o.point.x() << ", " << o.point.y() << "). Blocks may touch along edges but not overlap";
      r.fail(Reader::index("blocks", second) + ".vertices", m.str());
    }
  }
}

/// Sizes the numbers can resolve: the scene from a laboratory sample to a mountain range, each
/// block at least 1e-6 of it thick, and a bounded number of blocks.
void checkGeometry(const Reader& r, const model::Scene& s) {
  if (s.blocks.size() > static_cast<size_t>(limits::kMaxBlocks))
    r.fail("blocks", "expected at most " + std::to_string(limits::kMaxBlocks) + " blocks, found " +
                         std::to_string(s.blocks.size()));
  geometry::Aabb box = geometry::boundingBox(s.blocks.front().vertices);
  for (const model::Block& b : s.blocks) {
    const geometry::Aabb bb = geometry::boundingBox(b.vertices);
    box.lo = box.lo.cwiseMin(bb.lo);
    box.hi = box.hi.cwiseMax(bb.hi);
  }
  const double size = (box.hi - box.lo).maxCoeff();
  std::ostringstream m;
  if (!(size >= limits::kMinSceneSize && size <= limits::kMaxSceneSize)) {
    m << "expected a scene between 1 mm and 1000 km across, found " << size << " m";
    r.fail("blocks", m.str());
  }
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    const model::Block& blk = s.blocks[b];
    double perimeter = 0;
    for (size_t k = 0; k < blk.vertices.size(); ++k)
      perimeter += (blk.vertices[(k + 1) % blk.vertices.size()] - blk.vertices[k]).norm();
    const double thickness = 2 * std::abs(blk.moments.area) / perimeter;
    if (thickness < limits::kMinRelativeThickness * size) {
      m << "block \"" << blk.id << "\" is " << thickness << " m thick (2·area/perimeter) in a scene " << size
        << " m across: below the 1e-6 of it that the numbers resolve; merge it with a neighbour or remove it";
      r.fail(Reader::index("blocks", b) + ".vertices", m.str());
    }
  }
  checkOverlaps(r, s, size);
}

void readBlocks(const Reader& r, const json& doc, model::Scene& s,
                const std::map<std::string, int>& materialIds) {
  if (!doc.contains("blocks") && !s.blocks.empty()) return;  // all blocks come from the section
  const json& blocks = r.required(doc, "", "blocks");
  if (!blocks.is_array() || (blocks.empty() && s.blocks.empty()))
    r.fail("blocks", "expected a non-empty array of blocks, found " + typeName(blocks));
  std::set<std::string> seen;
  for (const auto& b : s.blocks) seen.insert(b.id);
  for (size_t b = 0; b < blocks.size(); ++b) {
    const std::string p = Reader::index("blocks", b);
    const json& jb = blocks[b];
    r.onlyKeys(jb, p, {"id", "material", "fixed", "vertices", "velocity", "angular_velocity"});
    model::Block blk;
    blk.id = r.identifier(r.string(r.required(jb, p, "id"), p + ".id"), p + ".id");
    if (!seen.insert(blk.id).second) r.fail(p + ".id", "duplicate block id \"" + blk.id + "\"");
    const std::string mat = r.string(r.required(jb, p, "material"), p + ".material");
    if (!materialIds.count(mat)) r.fail(p + ".material", "unknown material \"" + mat + "\" (not in materials)");
    blk.material = materialIds.at(mat);
    blk.fixed = r.boolean(jb, p, "fixed", false);
    const json& verts = r.required(jb, p, "vertices");
    if (!verts.is_array() || verts.size() < 3 || verts.size() > static_cast<size_t>(limits::kMaxBlockVertices))
      r.fail(p + ".vertices", "expected an array of 3 to " + std::to_string(limits::kMaxBlockVertices) +
                                  " points, found " + typeName(verts));
    for (size_t k = 0; k < verts.size(); ++k) blk.vertices.push_back(r.point(verts[k], Reader::index(p + ".vertices", k)));
    if (const auto defect = geometry::simplicityDefect(blk.vertices))
      r.fail(p + ".vertices", "expected a simple polygon, found " + whereNotSimple(blk.vertices, *defect));
    const geometry::Aabb box = geometry::boundingBox(blk.vertices);
    const double size = (box.hi - box.lo).maxCoeff();
    if (std::abs(geometry::signedArea(blk.vertices)) <= 1e-9 * size * size)
      r.fail(p + ".vertices", "expected a polygon with non-zero area, found a degenerate one");
    geometry::orientCounterClockwise(blk.vertices);
    blk.moments = geometry::computeMoments(blk.vertices);
    if (jb.contains("velocity")) {
      const Vec2 v = r.point(jb.at("velocity"), p + ".velocity");
      blk.velocity[0] = v.x();
      blk.velocity[1] = v.y();
    }
    if (jb.contains("angular_velocity")) blk.velocity[2] = r.number(jb.at("angular_velocity"), p + ".angular_velocity");
    // The fastest point of the block: |v| + |ω| · (its farthest vertex from the centroid).
    double reach = 0;
    for (const Vec2& v : blk.vertices) reach = std::max(reach, (v - blk.moments.centroid).norm());
    if (blk.velocity.head<2>().norm() + std::abs(blk.velocity[2]) * reach > limits::kMaxInitialSpeed)
      r.fail(p + (jb.contains("angular_velocity") ? ".angular_velocity" : ".velocity"),
             "expected an initial speed of at most 1000 m/s at every point of the block (|v| + |ω|·r)");
    if (blk.fixed && !blk.velocity.isZero()) r.fail(p + ".velocity", "a fixed block cannot have an initial velocity");
    s.blocks.push_back(blk);
  }
}

void readJointPairs(const Reader& r, const json& doc, model::Scene& s, const std::map<std::string, int>& jointIds) {
  if (!doc.contains("joint_pairs")) return;
  const json& pairs = doc.at("joint_pairs");
  if (!pairs.is_array()) r.fail("joint_pairs", "expected an array, found " + typeName(pairs));
  std::map<std::pair<int, int>, size_t> first;  // each pair's entry
  for (size_t i = 0; i < pairs.size(); ++i) {
    const std::string p = Reader::index("joint_pairs", i);
    r.onlyKeys(pairs[i], p, {"blocks", "joint"});
    const json& bl = r.required(pairs[i], p, "blocks");
    if (!bl.is_array() || bl.size() != 2) r.fail(p + ".blocks", "expected two block ids, found " + typeName(bl));
    int ids[2];
    for (int k = 0; k < 2; ++k) {
      const std::string id = r.string(bl[k], Reader::index(p + ".blocks", k));
      ids[k] = s.blockIndex(id);
      if (ids[k] < 0) r.fail(Reader::index(p + ".blocks", k), "unknown block \"" + id + "\"");
    }
    if (ids[0] == ids[1]) r.fail(p + ".blocks", "expected two different blocks");
    const std::string jn = r.string(r.required(pairs[i], p, "joint"), p + ".joint");
    if (!jointIds.count(jn)) r.fail(p + ".joint", "unknown joint \"" + jn + "\" (not in joints)");
    const std::pair<int, int> key{std::min(ids[0], ids[1]), std::max(ids[0], ids[1])};
    if (const auto seen = first.find(key); seen != first.end())
      r.fail(p + ".blocks", "the pair of blocks \"" + s.blocks[key.first].id + "\" and \"" + s.blocks[key.second].id +
                                "\" is already given a joint by joint_pairs[" + std::to_string(seen->second) +
                                "]: expected one joint per pair of blocks");
    first[key] = i;
    s.pairJoints[key] = jointIds.at(jn);
  }
}

/// water.pressure_grid: points [x, y, p] given in the case or as three columns of a CSV file.
std::shared_ptr<const model::PressureGrid> readPressureGrid(const Reader& r, const json& g, const std::string& p) {
  r.onlyKeys(g, p, {"points", "csv", "x_column", "y_column", "pressure_column"});
  if (g.contains("points") == g.contains("csv"))
    r.fail(p, "expected exactly one of points ([[x, y, p], …] in m and Pa) or csv (a file with x, y and pressure columns)");
  std::vector<Vec2> points;
  std::vector<double> pressures;
  std::string where = p + ".points";
  if (g.contains("points")) {
    const json& a = g.at("points");
    if (!a.is_array()) r.fail(where, "expected an array of points [x, y, p]");
    for (size_t i = 0; i < a.size(); ++i) {
      const std::string q = Reader::index(where, i);
      if (!a[i].is_array() || a[i].size() != 3) r.fail(q, "expected [x, y, p] (m, m, Pa)");
      points.emplace_back(r.number(a[i][0], q + "[0]"), r.number(a[i][1], q + "[1]"));
      pressures.push_back(r.number(a[i][2], q + "[2]"));
    }
  } else {
    where = p + ".csv";
    const std::string csv = r.string(g.at("csv"), where);
    const auto column = [&](const char* key, const char* def) {
      return g.contains(key) ? r.string(g.at(key), p + "." + key) : std::string(def);
    };
    const std::string file = (std::filesystem::path(r.file()).parent_path() / csv).string();
    const io::Series xp = readCsvColumns(file, column("x_column", "x"), column("pressure_column", "pressure"), r.file(), where);
    const io::Series yp = readCsvColumns(file, column("y_column", "y"), column("pressure_column", "pressure"), r.file(), where);
    for (size_t i = 0; i < xp.x.size(); ++i) points.emplace_back(xp.x[i], yp.x[i]), pressures.push_back(xp.y[i]);
  }
  if (points.size() < 3) r.fail(where, "expected at least three points");
  if (points.size() > 1000) r.fail(where, "expected at most 1000 points (the spline's system grows as their cube)");
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& q : points) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double tol = 1e-9 * std::max((hi - lo).maxCoeff(), 1e-300);
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if ((points[i] - points[j]).norm() <= tol)
        r.fail(Reader::index(where, i), "this point repeats point " + std::to_string(j) + ": give each place once");
  try {
    return std::make_shared<const model::PressureGrid>(points, pressures);
  } catch (const std::invalid_argument&) {
    r.fail(where, "expected points that span an area: these lie on one line");
  }
}

void readWater(const Reader& r, const json& doc, model::Scene& s) {
  const bool crackWater = s.tensionCrack && s.tensionCrack->waterFraction > 0;
  const bool drawn = s.water.active() && !crackWater;  // the section's drawing gave the water line
  if (!doc.contains("water")) return;
  if (crackWater)
    r.fail("water", "the tension crack's water (section.tension_crack.water_fraction) is the case's water: remove "
                    "water, or give the crack no water_fraction");
  const json& w = doc.at("water");
  r.onlyKeys(w, "water", {"level", "phreatic_line", "level_series", "unit_weight", "ru", "ground_unit_weight", "pressure_grid"});
  s.water.unitWeight = r.optionalIn(w, "water", "unit_weight", 9810, 10, 1e6, false, false, "a unit weight in [10, 1e6] N/m³");
  const int given = w.contains("level") + w.contains("phreatic_line") + w.contains("level_series") + w.contains("ru") +
                    w.contains("pressure_grid");
  if (drawn && given > 0)
    r.fail("water", "the water line is drawn (section.dxf.layers.water_line): remove level, phreatic_line and "
                    "level_series here, or the water_line layer from the section");
  if (drawn) return;
  if (given != 1)
    r.fail("water", "expected exactly one of level (a horizontal water surface), phreatic_line, level_series, ru "
                    "(a pore-pressure ratio) or pressure_grid");
  if (w.contains("ru")) {
    const double ru = r.numberIn(w.at("ru"), "water.ru", 0, 1, false, false, "a pore-pressure ratio r_u in [0, 1]");
    // γ of the ground above: the material's, if the case has one; else the user's.
    double gamma = 0;
    if (w.contains("ground_unit_weight"))
      gamma = 1e3 * r.numberIn(w.at("ground_unit_weight"), "water.ground_unit_weight", 1, 100, false, false,
                               "a unit weight in [1, 100] kN/m³ (as materials' unit_weight)");
    else if (s.materials.size() == 1)
      gamma = s.materials[0].density * (s.gravity.norm() > 0 ? s.gravity.norm() : 9.81);
    else
      r.fail("water.ground_unit_weight", "required key is missing: r_u needs the unit weight of the ground (kN/m³) "
                                         "when the case has several materials");
    if (w.contains("unit_weight")) r.fail("water.unit_weight", "not used with ru (give ground_unit_weight)");
    s.water = model::porePressureRatio(s.blocks, ru, gamma);
    return;
  }
  if (w.contains("ground_unit_weight")) r.fail("water.ground_unit_weight", "used only with ru");
  if (w.contains("pressure_grid")) {
    if (w.contains("unit_weight")) r.fail("water.unit_weight", "not used with pressure_grid (its pressures are in Pa)");
    s.water.grid = readPressureGrid(r, w.at("pressure_grid"), "water.pressure_grid");
    return;
  }
  if (w.contains("level_series")) {
    const json& ls = w.at("level_series");
    r.onlyKeys(ls, "water.level_series", {"csv", "time_column", "level_column"});
    const std::string csv = r.string(r.required(ls, "water.level_series", "csv"), "water.level_series.csv");
    const auto column = [&](const char* key, const char* def) {
      return ls.contains(key) ? r.string(ls.at(key), std::string("water.level_series.") + key) : std::string(def);
    };
    const io::Series series =
        readCsvColumns((std::filesystem::path(r.file()).parent_path() / csv).string(), column("time_column", "time"),
                       column("level_column", "level"), r.file(), "water.level_series.csv");
    for (size_t i = 1; i < series.x.size(); ++i)
      if (!(series.x[i] > series.x[i - 1])) r.fail("water.level_series.csv", "expected times increasing in " + csv);
    s.water.seriesTimes = series.x;
    s.water.seriesLevels = series.y;
    s.water.line = {{0, series.y.front()}, {1, series.y.front()}};
    return;
  }
  if (w.contains("level")) {
    const double y = r.number(w.at("level"), "water.level");
    s.water.line = {{0, y}, {1, y}};
    return;
  }
  const json& line = w.at("phreatic_line");
  if (!line.is_array() || line.size() < 2) r.fail("water.phreatic_line", "expected at least two points [x, y]");
  for (size_t i = 0; i < line.size(); ++i) {
    const Vec2 p = r.point(line[i], Reader::index("water.phreatic_line", i));
    if (i > 0 && p.x() <= s.water.line.back().x())
    {
      std::ostringstream m;
      m << "expected x increasing along the line, found x = " << p.x() << " after " << s.water.line.back().x();
      r.fail(Reader::index("water.phreatic_line", i), m.str());
    }
    s.water.line.push_back(p);
  }
}

void readSeismic(const Reader& r, const json& doc, model::Scene& s) {
  if (!doc.contains("seismic")) return;
  const json& q = doc.at("seismic");
  r.onlyKeys(q, "seismic", {"k_h", "k_v", "record"});
  // Two g either way is beyond any recorded peak ground acceleration.
  s.seismic.kh = r.optionalIn(q, "seismic", "k_h", 0, -2, 2, false, false, "a coefficient in [-2, 2] (a fraction of g)");
  s.seismic.kv = r.optionalIn(q, "seismic", "k_v", 0, -2, 2, false, false, "a coefficient in [-2, 2] (a fraction of g)");
  if (!q.contains("record")) return;
  const json& rec = q.at("record");
  const std::string p = "seismic.record";
  r.onlyKeys(rec, p, {"file", "format", "units", "scale", "start", "dt", "time_column", "horizontal_column",
                      "vertical_column"});
  io::RecordSpec spec;
  const std::string file = r.string(r.required(rec, p, "file"), p + ".file");
  spec.file = (std::filesystem::path(r.file()).parent_path() / file).string();
  const auto text = [&](const char* key, const std::string& def) {
    return rec.contains(key) ? r.string(rec.at(key), p + "." + key) : def;
  };
  std::string ext = std::filesystem::path(file).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  spec.format = text("format", ext == ".csv" ? "csv" : "at2");
  if (spec.format != "at2" && spec.format != "csv") r.fail(p + ".format", "expected \"at2\" or \"csv\", found \"" + spec.format + "\"");
  spec.units = text("units", "");
  if (spec.format == "csv" && spec.units.empty())
    r.fail(p + ".units", "required for a CSV record: \"g\" or \"m/s2\" (a .AT2 record is in g)");
  if (!spec.units.empty() && spec.units != "g" && spec.units != "m/s2")
    r.fail(p + ".units", "expected \"g\" or \"m/s2\", found \"" + spec.units + "\"");
  spec.scale = r.optionalIn(rec, p, "scale", 1, -100, 100, false, false, "a scale factor in [-100, 100]");
  spec.start = r.optionalIn(rec, p, "start", 0, 0, model::limits::kMaxDuration, false, false, "a start time ≥ 0 s");
  if (rec.contains("dt")) spec.dt = r.numberIn(rec.at("dt"), p + ".dt", 0, 10, true, false, "a sample interval in (0, 10] s");
  spec.timeColumn = text("time_column", "time");
  spec.horizontalColumn = text("horizontal_column", "a_h");
  spec.verticalColumn = text("vertical_column", "");
  s.seismic.ground = io::readGroundMotion(spec, r.file(), p + ".file");
}

void readAnalysis(const Reader& r, const json& doc, model::Scene& s) {
  const json& a = r.required(doc, "", "analysis");
  const std::string p = "analysis";
  r.onlyKeys(a, p, {"duration", "time_step", "mode", "plane", "penalty", "penalty_factor",
                    "shear_penalty_ratio", "max_displacement_ratio", "open_close_max_iterations",
                    "friction_tolerance", "max_step_cuts", "max_steps", "wall_clock_limit", "step_cut_factor", "initial_equilibrium",
                    "settle_dynamically", "early_rest",
                    "equilibrium_max_steps", "edge_parallel_tolerance", "initial_contact_tolerance",
                    "contact_state_tolerance", "contact_treatment", "failure_displacement", "resting_speed", "preset",
                    "blocks", "strain_damping", "joint_end_offset", "system_path", "factor_updates",
                    "time_step_growth"});
  model::AnalysisSettings& st = s.settings;
  st.duration = r.numberIn(r.required(a, p, "duration"), p + ".duration", 0, limits::kMaxDuration, true, false,
                           "a duration in (0, 1e6] s");
  // A preset sets Δt, g2 and the penalty from the model's size; explicit keys below still win.
  // A case with neither a preset nor a time step runs at the default preset (balanced).
  if (a.contains("preset") || !a.contains("time_step")) {
    const std::string name = r.choice(a, p, "preset", model::kDefaultPreset, {"fast", "balanced", "accurate"});
    model::applyPreset(st, *model::findPreset(name), s.modelHalfSize(), s.gravity.norm());
    if (!a.contains("preset")) st.timeStepOrigin = "default " + st.timeStepOrigin;
  }
  if (a.contains("time_step")) {
    st.timeStep = r.numberIn(a.at("time_step"), p + ".time_step", limits::kMinTimeStep, limits::kMaxTimeStep, false,
                             false, "a time step in [1e-7, 10] s");
    st.timeStepOrigin = "analysis.time_step";
  }
  st.mode = r.choice(a, p, "mode", "dynamic", {"dynamic", "static"}) == "static" ? model::AnalysisMode::Static
                                                                                 : model::AnalysisMode::Dynamic;
  st.plane = r.choice(a, p, "plane", "strain", {"strain", "stress"}) == "stress" ? model::PlaneMode::Stress
                                                                              : model::PlaneMode::Strain;
  st.rigidBlocks = r.choice(a, p, "blocks", "deformable", {"deformable", "rigid"}) == "rigid";
  const std::string path = r.choice(a, p, "system_path", "auto", {"auto", "small", "large"});
  st.systemPath = path == "small" ? model::SystemPath::Small : path == "large" ? model::SystemPath::Large : model::SystemPath::Auto;
  st.factorUpdates = r.choice(a, p, "factor_updates", "on", {"on", "off"}) == "on";
  st.failureDisplacement = r.optionalIn(a, p, "failure_displacement", 0, 0, 1e6, false, false, "a distance ≥ 0 m (0: 1e-3 of w0)");
  st.jointEndOffset = r.optionalIn(a, p, "joint_end_offset", -1, 0, 1e6, false, false,
                                  "a distance ≥ 0 m (absent: automatic)");
  st.restingSpeed = r.optionalIn(a, p, "resting_speed", 0, 0, 1e6, false, false, "a speed ≥ 0 m/s (0: automatic)");
  st.strainDamping = r.optionalIn(a, p, "strain_damping", st.strainDamping, 0, 100, false, false,
                                  "a fraction of critical in [0, 100]");
  st.contactTreatment = r.choice(a, p, "contact_treatment", "edge", {"edge", "vertex"}) == "vertex"
                            ? model::ContactTreatment::Vertex
                            : model::ContactTreatment::Edge;
  st.penalty = r.optionalIn(a, p, "penalty", 0, 0, 1e18, false, false, "a penalty ≥ 0 N/m (0: automatic)");
  st.penaltyFactor = r.optionalIn(a, p, "penalty_factor", st.penaltyFactor, 0, 1e6, true, false, "a factor > 0");
  st.shearPenaltyRatio = r.optionalIn(a, p, "shear_penalty_ratio", st.shearPenaltyRatio, 0, 10, true, false, "a ratio > 0");
  st.maxDisplacementRatio = r.optionalIn(a, p, "max_displacement_ratio", st.maxDisplacementRatio,
                                         limits::kMinDisplacementRatio, 0.1, false, false, "a ratio in [1e-5, 0.1]");
  st.openCloseMaxIterations = r.integerIn(a, p, "open_close_max_iterations", st.openCloseMaxIterations, 1, 1000);
  st.frictionTolerance = r.optionalIn(a, p, "friction_tolerance", st.frictionTolerance, 0, 1, true, false, "a tolerance in (0, 1]");
  st.maxStepCuts = r.integerIn(a, p, "max_step_cuts", st.maxStepCuts, 0, 100);
  if (a.contains("time_step_growth")) {
    // "auto" (as absent): grown in a stability trial, not in a run. A whole factor, so that the
    // multiples of the cap a grown step lands on are steps of time_step.
    const json& g = a.at("time_step_growth");
    const std::string what = "\"auto\" or a whole factor in [1, 100] (1: Δt never grows past time_step)";
    if (g.is_string() && g.get<std::string>() == "auto")
      st.timeStepGrowth = 0;
    else if (g.is_string())
      r.fail(p + ".time_step_growth", "expected " + what + ", found \"" + g.get<std::string>() + "\"");
    else if (const double v = r.numberIn(g, p + ".time_step_growth", 1, 100, false, false, what); v != std::floor(v))
      r.fail(p + ".time_step_growth", "expected " + what + ", found " + g.dump());
    else
      st.timeStepGrowth = v;
  }
  st.maxSteps = r.integerIn(a, p, "max_steps", st.maxSteps, 0, 1000000000);
  st.wallClockLimit = r.optionalIn(a, p, "wall_clock_limit", st.wallClockLimit, 0, 1e7, false, false,
                                   "a wall time ≥ 0 s (0: none)");
  st.stepCutFactor = r.optionalIn(a, p, "step_cut_factor", st.stepCutFactor, 0, 1, true, true, "a factor in (0, 1)");
  st.initialEquilibrium = r.boolean(a, p, "initial_equilibrium", st.initialEquilibrium);
  st.settleDynamically = r.boolean(a, p, "settle_dynamically", st.settleDynamically);
  st.earlyRest = r.boolean(a, p, "early_rest", st.earlyRest);
  st.equilibriumMaxSteps = r.integerIn(a, p, "equilibrium_max_steps", st.equilibriumMaxSteps, 1, 100000);
  st.edgeParallelToleranceDeg = r.optionalIn(a, p, "edge_parallel_tolerance", st.edgeParallelToleranceDeg, 0, 10,
                                             true, false, "an angle in (0, 10] degrees");
  st.contactStateTolerance = r.optionalIn(a, p, "contact_state_tolerance", st.contactStateTolerance, 0, 1e-4,
                                          false, false, "a ratio in [0, 1e-4]");
  st.initialContactTolerance = r.optionalIn(a, p, "initial_contact_tolerance", st.initialContactTolerance, 0,
                                            1e-2, false, false, "a ratio in [0, 0.01]");
}

void readExpectations(const Reader& r, const json& doc, model::Scene& s) {
  if (!doc.contains("expected")) return;
  const json& ex = doc.at("expected");
  if (!ex.is_array()) r.fail("expected", "expected an array, found " + typeName(ex));
  for (size_t i = 0; i < ex.size(); ++i) {
    const std::string p = Reader::index("expected", i);
    const json& e = ex[i];
    r.onlyKeys(e, p, {"monitor", "quantity", "time", "value", "relative_tolerance", "absolute_tolerance",
                      "at_most", "at_least", "source"});
    model::Expectation x;
    x.monitor = r.string(r.required(e, p, "monitor"), p + ".monitor");
    bool found = false;
    for (const auto& m : s.monitors) found |= m.id == x.monitor;
    if (!found) r.fail(p + ".monitor", "unknown monitor \"" + x.monitor + "\"");
    x.quantity = r.choice(e, p, "quantity", "", {"ux", "uy", "vx", "vy", "displacement", "speed"});
    if (x.quantity.empty()) r.fail(p + ".quantity", "required key is missing");
    if (e.contains("time")) x.time = r.numberIn(e.at("time"), p + ".time", 0, s.settings.duration, false, false,
                                                "a time within the analysis duration");
    if (e.contains("value")) x.value = r.number(e.at("value"), p + ".value");
    x.relativeTolerance = r.optionalIn(e, p, "relative_tolerance", 0, 0, 1, false, false, "a tolerance in [0, 1]");
    x.absoluteTolerance = r.optionalIn(e, p, "absolute_tolerance", 0, 0, 1e12, false, false, "a tolerance ≥ 0");
    if (e.contains("at_most")) x.atMost = r.number(e.at("at_most"), p + ".at_most");
    if (e.contains("at_least")) x.atLeast = r.number(e.at("at_least"), p + ".at_least");
    if (!x.value && !x.atMost && !x.atLeast) r.fail(p, "expected one of value, at_most, at_least");
    if (x.value && x.relativeTolerance == 0 && x.absoluteTolerance == 0)
      r.fail(p, "a value needs relative_tolerance or absolute_tolerance");
    if (e.contains("source")) x.source = r.string(e.at("source"), p + ".source");
    s.expectations.push_back(x);
  }
}

}  // namespace

namespace {

/// The scene of a parsed case document.
model::Scene readCaseDocument(const json& doc, const std::string& file) {
  const Reader r(file);
  r.onlyKeys(doc, "", {"description", "gravity", "materials", "joints", "default_joint", "joint_pairs", "section",
                       "blocks", "monitors", "point_loads", "edge_loads", "supports", "fixed_points", "water", "seismic", "analysis", "expected",
                       "probability"});
  // "probability" (a study's uncertain inputs) is read by io/probability_reader.cpp: a run ignores it.
  model::Scene s;
  if (doc.contains("description")) s.description = r.string(doc.at("description"), "description");
  if (doc.contains("gravity")) {
    s.gravity = r.point(doc.at("gravity"), "gravity");
    if (s.gravity.norm() > model::limits::kMaxGravity) {
      std::ostringstream m;
      m << "expected gravity of at most " << model::limits::kMaxGravity << " m/s² (100 g), found " << s.gravity.norm();
      r.fail("gravity", m.str());
    }
  }
  std::map<std::string, int> materialIds, jointIds;
  readMaterials(r, doc, s, materialIds);
  readJoints(r, doc, s, jointIds);
  readSection(r, doc, s, materialIds, jointIds);
  readBlocks(r, doc, s, materialIds);
  checkGeometry(r, s);
  readJointPairs(r, doc, s, jointIds);
  readPointsAndLoads(r, doc, s);
  readWater(r, doc, s);
  readSeismic(r, doc, s);
  readAnalysis(r, doc, s);
  mergeFixedBlocks(s);
  normaliseOutlines(s);  // after the merge (its seams) and the settings (initial_contact_tolerance)
  moveJointEndsOffBends(s);
  readExpectations(r, doc, s);
  localiseOrigin(s);
  checkWorkload(s, file);
  return s;
}

}  // namespace

model::Scene parseCase(const std::string& text, const std::string& file) {
  return readCaseDocument(parseJsonText(text, file), file);
}

void checkWorkload(const model::Scene& s, const std::string& file) {
  const model::AnalysisSettings& st = s.settings;
  const double steps = st.duration / st.timeStep;
  std::ostringstream m;
  if (!(steps <= model::limits::kMaxNominalSteps)) {
    m << "duration / time_step = " << st.duration << " s / " << st.timeStep << " s = " << steps
      << " steps, more than the 1e7 a run may take: shorten analysis.duration or lengthen the time step";
    throw InputError(file, "analysis.duration", m.str());
  }
  // About 10 µs per block and step on one core (docs/performance.md): 1e10 is a day.
  const double work = steps * static_cast<double>(s.blocks.size());
  if (!(work <= 1e10)) {
    m << steps << " steps of " << s.blocks.size() << " blocks (" << work
      << " block-steps, about a day per 1e10): more than a run may take; shorten analysis.duration, lengthen "
         "the time step or use fewer blocks";
    throw InputError(file, "analysis.duration", m.str());
  }
}

namespace {

/// The JSON value at a dotted path with [index] parts, or nullptr where a key is missing (it may
/// be added). An index that names no element (blocks[x], blocks[-1], blocks[7] of two blocks, an
/// index into an object) is bad input here, naming the part of the path it is in.
json* locate(json& doc, const std::string& path, const std::string& file) {
  json* at = &doc;
  size_t i = 0;
  while (i < path.size()) {
    if (path[i] == '.') ++i;
    if (i < path.size() && path[i] == '[') {
      const size_t close = path.find(']', i);
      const std::string array = path.substr(0, i);
      if (close == std::string::npos)
        throw InputError(file, path, "in " + path.substr(0, i + 1) + "...: expected an index closed by ], found none");
      const std::string index = path.substr(i + 1, close - i - 1);
      const std::string part = path.substr(0, close + 1);
      if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos)
        throw InputError(file, path, "in " + part + ": expected an index (a whole number from 0), found \"" + index + "\"");
      if (!at->is_array())
        throw InputError(file, path, "in " + part + ": expected an array at " + (array.empty() ? "the top" : array) +
                                         " to index, found " + typeName(*at));
      // Compared as text first: an index of any length is refused, never converted out of range.
      const std::string size = std::to_string(at->size());
      const std::string digits = index.substr(std::min(index.find_first_not_of('0'), index.size() - 1));
      if (digits.size() > size.size() || (digits.size() == size.size() && digits >= size))
        throw InputError(file, path, "in " + part + ": expected an index below " + size + " (" + array + " has " + size +
                                         (at->size() == 1 ? " entry" : " entries") + "), found " + index);
      at = &(*at)[static_cast<size_t>(std::stoull(digits))];
      i = close + 1;
      continue;
    }
    const size_t end = path.find_first_of(".[", i);
    const std::string key = path.substr(i, end == std::string::npos ? std::string::npos : end - i);
    if (!at->is_object() || !at->contains(key)) return nullptr;
    at = &(*at)[key];
    i = end == std::string::npos ? path.size() : end;
  }
  return at;
}

}  // namespace

namespace {

/// Puts one override into the case's JSON (a path without `*`).
void applyOverride(json& doc, const std::string& path, const CaseOverride& o, const std::string& jsonPath) {
  json* at = locate(doc, jsonPath, path);
  const size_t dot = jsonPath.rfind('.');
  if (o.erase) {
    json* parent = dot == std::string::npos ? &doc : locate(doc, jsonPath.substr(0, dot), path);
    if (parent && parent->is_object()) parent->erase(jsonPath.substr(dot + 1));
    return;
  }
  if (!at) {
    // A key the case leaves at its default (analysis.open_close_max_iterations) may be set too:
    // it is added to its object, and the reader then checks it like any other key.
    json* parent = dot == std::string::npos ? nullptr : locate(doc, jsonPath.substr(0, dot), path);
    // So may a top-level object the case leaves out altogether (seismic.k_h on a static case).
    const std::string parentPath = dot == std::string::npos ? "" : jsonPath.substr(0, dot);
    if (!parent && !parentPath.empty() && parentPath.find_first_of(".[") == std::string::npos && doc.is_object())
      parent = &(doc[parentPath] = json::object());
    const std::string key = dot == std::string::npos ? "" : jsonPath.substr(dot + 1);
    if (parent && parent->is_object() && !key.empty() && key.find('[') == std::string::npos) at = &(*parent)[key];
  }
  const std::string kind = o.flag ? "true or false" : o.text ? "a string \"" + *o.text + "\"" : "a number";
  if (!at) throw InputError(path, jsonPath, "expected a value of the case at this path (to set it to " + kind + "), found none");
  if (!(at->is_null() || (o.flag ? at->is_boolean() : o.text ? at->is_string() : at->is_number())))
    throw InputError(path, jsonPath, "expected " + typeName(*at) + " here, as the case has it, found " + kind);
  if (o.flag) *at = *o.flag;
  else if (o.text) *at = *o.text;
  // A whole number stays an integer, so that integer settings accept it.
  else if (std::floor(o.value) == o.value && std::abs(o.value) < 9e15) *at = static_cast<long long>(o.value);
  else *at = o.value;
}

}  // namespace

model::Scene readCase(const std::string& path, const std::vector<CaseOverride>& overrides) {
  return parseCase(readInputFile(path, kMaxJsonFileBytes), path, overrides);
}

namespace {
model::Scene readWithOverrides(json doc, const std::string& path, const std::vector<CaseOverride>& overrides);
}  // namespace

struct ParsedCase::Document {
  json doc;
};

ParsedCase::ParsedCase(const std::string& text, std::string file)
    : document_(std::make_shared<const Document>(Document{parseJsonText(text, file)})), file_(std::move(file)) {}

model::Scene ParsedCase::read(const std::vector<CaseOverride>& overrides) const {
  return readWithOverrides(document_->doc, file_, overrides);
}

model::Scene parseCase(const std::string& text, const std::string& path, const std::vector<CaseOverride>& overrides) {
  return readWithOverrides(parseJsonText(text, path), path, overrides);
}

namespace {

model::Scene readWithOverrides(json doc, const std::string& path, const std::vector<CaseOverride>& overrides) {
  std::string origin;
  for (const CaseOverride& o : overrides) {
    const size_t star = o.jsonPath.find(".*.");
    if (star == std::string::npos) {
      applyOverride(doc, path, o, o.jsonPath);
    } else {
      // Every key of the object before the star (every joint).
      const json* object = locate(doc, o.jsonPath.substr(0, star), path);
      if (object && object->is_object())
        for (const auto& item : object->items())
          applyOverride(doc, path, o, o.jsonPath.substr(0, star) + "." + item.key() + o.jsonPath.substr(star + 2));
    }
    if (o.jsonPath == "analysis.time_step" || o.jsonPath == "analysis.preset") origin = o.origin;
  }
  model::Scene scene = readCaseDocument(doc, path);
  if (!origin.empty()) scene.settings.timeStepOrigin = origin;
  return scene;
}

}  // namespace

std::vector<CaseOverride> caseOverridesFor(const model::SettingsOverride& o) {
  std::vector<CaseOverride> out;
  if (!o.preset.empty()) {
    // The preset sets these from the model's size; the case's own values give way to it.
    for (const char* key : {"time_step", "max_displacement_ratio", "penalty_factor", "penalty"})
      out.push_back(CaseOverride::removal(std::string("analysis.") + key));
    out.push_back(CaseOverride::name("analysis.preset", o.preset));
    out.back().origin = o.origin + "preset " + o.preset;
  }
  if (o.timeStep > 0) {
    out.emplace_back("analysis.time_step", o.timeStep);
    out.back().origin = o.origin + "time-step";
  }
  if (!o.blocks.empty()) out.push_back(CaseOverride::name("analysis.blocks", o.blocks));
  if (!o.contactTreatment.empty()) out.push_back(CaseOverride::name("analysis.contact_treatment", o.contactTreatment));
  if (o.brittleJoints) out.emplace_back("joints.*.weakening_distance", 0);
  return out;
}

std::string expandSection(const std::string& path) {
  const model::Scene scene = readCase(path);
  nlohmann::ordered_json doc = nlohmann::ordered_json::parse(readInputFile(path, kMaxJsonFileBytes));
  // A water line drawn with the section, or the water of its tension crack, stays with the blocks
  // as the phreatic line it was.
  const auto drawnWater = nlohmann::ordered_json::json_pointer("/section/dxf/layers/water_line");
  if (doc.contains(drawnWater) || (scene.tensionCrack && scene.tensionCrack->waterFraction > 0)) {
    nlohmann::ordered_json line = nlohmann::ordered_json::array();
    for (const Vec2& p : scene.water.line) line.push_back({p.x() + scene.origin.x(), p.y() + scene.origin.y()});
    doc["water"]["phreatic_line"] = line;
  }
  doc.erase("section");
  nlohmann::ordered_json blocks = nlohmann::ordered_json::array();
  for (const model::Block& b : scene.blocks) {
    nlohmann::ordered_json jb;
    jb["id"] = b.id;
    jb["material"] = scene.materials[b.material].name;
    if (b.fixed) jb["fixed"] = true;
    nlohmann::ordered_json v = nlohmann::ordered_json::array();
    for (const Vec2& p : b.vertices) v.push_back({p.x() + scene.origin.x(), p.y() + scene.origin.y()});
    jb["vertices"] = v;
    if (b.velocity.head<2>().norm() > 0) jb["velocity"] = {b.velocity[0], b.velocity[1]};
    if (b.velocity[2] != 0) jb["angular_velocity"] = b.velocity[2];
    blocks.push_back(jb);
  }
  doc["blocks"] = blocks;
  if (!scene.pairJoints.empty()) {
    nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
    for (const auto& [pair, joint] : scene.pairJoints)
      pairs.push_back({{"blocks", {scene.blocks[pair.first].id, scene.blocks[pair.second].id}},
                       {"joint", scene.joints[joint].name}});
    doc["joint_pairs"] = pairs;
  }
  return doc.dump(2) + "\n";
}

model::Scene readCase(const std::string& path) { return parseCase(readInputFile(path, kMaxJsonFileBytes), path); }

std::string unitOfCaseValue(const std::string& path) {
  // By the path's end: the last key, or the last two where a key means different things in
  // different objects (a water unit weight in N/m³, a material's in kN/m³). Indices ("rate[0]",
  // "points[2][1]") are dropped.
  std::string clean;
  for (size_t k = 0; k < path.size(); ++k) {
    if (path[k] == '[') k = path.find(']', k);
    else clean += path[k];
    if (k == std::string::npos) break;
  }
  const size_t last = clean.find_last_of('.');
  const std::string key = last == std::string::npos ? clean : clean.substr(last + 1);
  std::string parent;
  if (last != std::string::npos && last > 0) {
    const size_t before = clean.find_last_of('.', last - 1);
    parent = before == std::string::npos ? clean.substr(0, last) : clean.substr(before + 1, last - before - 1);
  }
  static const std::map<std::string, std::string> inParent{
      {"water.unit_weight", "N/m³"}, {"water.level", "m"},        {"tension_crack.x", "m"},
      {"tension_crack.depth", "m"},  {"point_loads.force", "N/m"}, {"point_loads.rate", "N/m per s"},
      {"supports.stiffness", "N/m"}};
  if (const auto it = inParent.find(parent + "." + key); it != inParent.end()) return it->second;
  static const std::map<std::string, std::string> units{
      {"cohesion", "Pa"}, {"residual_cohesion", "Pa"}, {"tensile_strength", "Pa"}, {"young_modulus", "Pa"},
      {"jcs", "Pa"}, {"friction_angle", "°"}, {"residual_friction_angle", "°"}, {"angle", "°"},
      {"density", "kg/m³"}, {"unit_weight", "kN/m³"}, {"ground_unit_weight", "kN/m³"}, {"weakening_distance", "m"},
      {"lab_length", "m"}, {"field_length", "m"}, {"base_depth", "m"}, {"spacing", "m"},
      {"failure_displacement", "m"}, {"joint_end_offset", "m"}, {"pretension", "N"}, {"capacity", "N"},
      {"normal_stiffness", "Pa/m"}, {"shear_stiffness", "Pa/m"}, {"penalty", "N/m"}, {"bond_strength", "N/m"},
      {"time_step", "s"}, {"duration", "s"}};
  const auto it = units.find(key);
  return it == units.end() ? "" : it->second;
}

}  // namespace ddaslope::io
