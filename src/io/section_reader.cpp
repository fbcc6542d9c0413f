#include "section_reader.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/dxf_section.hpp"
#include "json_input.hpp"
#include "ddaslope/model/section.hpp"

namespace ddaslope::io {

using case_json::json;
using case_json::Reader;

namespace {

/// section.dxf: the drawing (relative to the case), its units and scale, and the layer of each line.
DxfSectionSource readDxfSource(const Reader& r, const json& j, const std::string& p) {
  r.onlyKeys(j, p, {"file", "units", "scale", "layers"});
  DxfSectionSource src;
  src.file = (std::filesystem::path(r.file()).parent_path() / r.string(r.required(j, p, "file"), p + ".file")).string();
  if (j.contains("units")) src.units = r.string(j.at("units"), p + ".units");
  src.scale = r.optionalIn(j, p, "scale", 1, 1e-6, 1e6, false, false, "a scale in [1e-6, 1e6] (metres = drawn × unit × scale)");
  const std::string q = p + ".layers";
  const json& layers = r.required(j, p, "layers");
  r.onlyKeys(layers, q, {"ground", "sliding_surface", "joints", "water_line"});
  const auto layer = [&](const char* key, bool required) -> std::string {
    if (!required && !layers.contains(key)) return "";
    const std::string name = r.string(r.required(layers, q, key), q + "." + key);
    if (name.empty()) r.fail(q + "." + key, "expected a layer name, found an empty string");
    return name;
  };
  src.groundLayer = layer("ground", true);
  src.slidingSurfaceLayer = layer("sliding_surface", true);
  src.jointsLayer = layer("joints", false);
  src.waterLineLayer = layer("water_line", false);
  return src;
}

/// A cut's complaint about a drawn line (its path `ground[3]`, `joints[0]`, …) pointed at the
/// drawing: the layer's key as JSON path, the file, layer, entity and point in the message.
std::optional<std::pair<std::string, std::string>> inDrawing(const DxfSection& d, const DxfSectionSource& src,
                                                             const std::string& cutPath) {
  const size_t bracket = cutPath.find('[');
  const std::string name = cutPath.substr(0, bracket);
  const std::vector<std::string>* from = name == "ground" ? &d.groundFrom
                                         : name == "sliding_surface" ? &d.slidingSurfaceFrom
                                         : name == "joints" && !src.jointsLayer.empty() ? &d.jointFrom
                                                                                         : nullptr;
  if (!from) return std::nullopt;
  const std::string& layer = name == "ground" ? src.groundLayer
                             : name == "sliding_surface" ? src.slidingSurfaceLayer
                                                         : src.jointsLayer;
  std::string where = src.file + ": layer \"" + layer + "\"";
  if (bracket != std::string::npos) {
    const size_t i = std::stoul(cutPath.substr(bracket + 1));
    if (i < from->size()) where = (*from)[i];
  }
  return std::make_pair("section.dxf.layers." + name, where);
}

/// section.tension_crack: its position (x, or the depth at which it reaches the sliding surface),
/// its water and the range its position is searched in; the search range when given.
std::optional<std::pair<double, double>> readTensionCrack(const Reader& r, const json& t, const std::string& p,
                                                          model::SectionSpec& spec) {
  r.onlyKeys(t, p, {"x", "depth", "water_fraction", "search"});
  if (t.contains("x") == t.contains("depth"))
    r.fail(p, "expected exactly one of x (the crack's position, m) or depth (m: the crack reaches the sliding surface "
              "this far below the ground)");
  model::TensionCrack crack;
  if (t.contains("x")) {
    crack.x = r.number(t.at("x"), p + ".x");
  } else {
    const double depth = r.numberIn(t.at("depth"), p + ".depth", 0, 1e6, true, false, "a depth > 0 m");
    if (spec.slidingSurface.size() < 2 || spec.ground.size() < 2) r.fail(p + ".depth", "needs the section's ground and sliding surface");
    crack.x = model::crackPositionAtDepth(spec, depth);
    crack.placedByDepth = true;
    if (!std::isfinite(crack.x))
      r.fail(p + ".depth", "the sliding surface is nowhere this deep below the ground between crown and toe");
  }
  crack.waterFraction = r.optionalIn(t, p, "water_fraction", 0, 0, 1, false, false, "a fraction of the crack's depth in [0, 1]");
  spec.tensionCrack = crack;
  if (!t.contains("search")) return std::nullopt;
  const json& range = t.at("search");
  if (!range.is_array() || range.size() != 2)
    r.fail(p + ".search", "expected [x_min, x_max]: the range fos and critical search the crack's position in");
  const double lo = r.number(range[0], p + ".search[0]"), hi = r.number(range[1], p + ".search[1]");
  char found[96];
  std::snprintf(found, sizeof found, ", found [%g, %g]", lo, hi);
  if (!(lo < hi)) r.fail(p + ".search", std::string("expected x_min < x_max") + found);
  // The crack is cut between the sliding surface's crown and its toe (model/section.cpp).
  if (spec.slidingSurface.size() >= 2) {
    const bool minusX = model::facesMinusX(spec);
    const double left = spec.slidingSurface.front().x(), right = spec.slidingSurface.back().x();
    if (!(lo > left && hi < right)) {
      char m[200];
      std::snprintf(m, sizeof m, "expected a range between the sliding surface's %s (x = %g m) and its %s (x = %g m)",
                    minusX ? "toe" : "crown", left, minusX ? "crown" : "toe", right);
      r.fail(p + ".search", m + std::string(found));
    }
  }
  return std::make_pair(lo, hi);
}

}  // namespace

void readSection(const Reader& r, const json& doc, model::Scene& s, const std::map<std::string, int>& materialIds,
                 const std::map<std::string, int>& jointIds) {
  if (!doc.contains("section")) return;
  const std::string p = "section";
  const json& j = doc.at(p);
  r.onlyKeys(j, p, {"ground", "sliding_surface", "base_depth", "material", "base_material", "sliding_joint", "joints",
                    "joint_sets", "kink_block_width", "dxf", "tension_crack"});
  const auto polyline = [&](const char* key) {
    const json& a = r.required(j, p, key);
    if (!a.is_array()) r.fail(p + "." + key, "expected an array of points [x, y]");
    std::vector<Vec2> pts;
    for (size_t i = 0; i < a.size(); ++i) pts.push_back(r.point(a[i], Reader::index(p + "." + key, i)));
    return pts;
  };
  model::SectionSpec spec;
  // A drawn section: the drawing gives the lines its layers map, the case everything else.
  std::optional<DxfSectionSource> source;
  std::optional<DxfSection> drawn;
  if (j.contains("dxf")) {
    source = readDxfSource(r, j.at("dxf"), p + ".dxf");
    for (const auto& [key, layer] : {std::pair<std::string, std::string>{"ground", source->groundLayer},
                                     {"sliding_surface", source->slidingSurfaceLayer},
                                     {"joints", source->jointsLayer}})
      if (!layer.empty() && j.contains(key))
        r.fail(p + "." + key, "given twice: by the case and by the drawing's layer \"" + layer + "\" (section.dxf.layers." +
                                  key + "); remove one");
    drawn = readDxfSection(*source, r.file(), p + ".dxf");
    spec.ground = drawn->ground;
    spec.slidingSurface = drawn->slidingSurface;
    spec.joints = drawn->joints;
    // Read with the rest of the water (readWater), which refuses a second water line.
    s.water.line = drawn->waterLine;
  } else {
    spec.ground = polyline("ground");
    spec.slidingSurface = polyline("sliding_surface");
  }
  spec.baseDepth = r.number(r.required(j, p, "base_depth"), p + ".base_depth");
  if (j.contains("kink_block_width")) {
    spec.kinkBlockWidth = r.number(j.at("kink_block_width"), p + ".kink_block_width");
    spec.kinkBlockAuto = false;
  }
  // The automatic kink block must outlast the verdict's failure displacement (read with the rest of
  // the analysis, which checks it; here only its size matters).
  if (doc.contains("analysis") && doc.at("analysis").is_object() && doc.at("analysis").contains("failure_displacement") &&
      doc.at("analysis").at("failure_displacement").is_number())
    spec.failureDisplacement = doc.at("analysis").at("failure_displacement").get<double>();
  if (j.contains("joints")) {
    const json& js = j.at("joints");
    if (!js.is_array()) r.fail(p + ".joints", "expected an array of joints [[x1, y1], [x2, y2]]");
    for (size_t i = 0; i < js.size(); ++i) {
      const std::string q = Reader::index(p + ".joints", i);
      if (!js[i].is_array() || js[i].size() != 2) r.fail(q, "expected two points [[x1, y1], [x2, y2]]");
      spec.joints.emplace_back(r.point(js[i][0], q + "[0]"), r.point(js[i][1], q + "[1]"));
    }
  }
  if (j.contains("joint_sets")) {
    const json& sets = j.at("joint_sets");
    if (!sets.is_array()) r.fail(p + ".joint_sets", "expected an array");
    for (size_t i = 0; i < sets.size(); ++i) {
      const std::string q = Reader::index(p + ".joint_sets", i);
      r.onlyKeys(sets[i], q, {"angle", "spacing", "origin"});
      model::JointSet set;
      set.angleDeg = r.number(r.required(sets[i], q, "angle"), q + ".angle");
      set.spacing = r.number(r.required(sets[i], q, "spacing"), q + ".spacing");
      set.origin = r.point(r.required(sets[i], q, "origin"), q + ".origin");
      spec.jointSets.push_back(set);
    }
  }
  std::optional<std::pair<double, double>> crackSearch;
  if (j.contains("tension_crack")) crackSearch = readTensionCrack(r, j.at("tension_crack"), p + ".tension_crack", spec);
  const auto materialOf = [&](const char* key, const std::string& def) {
    const std::string m = j.contains(key) ? r.string(j.at(key), p + "." + key) : def;
    if (!materialIds.count(m)) r.fail(p + "." + key, "unknown material \"" + m + "\" (not in materials)");
    return materialIds.at(m);
  };
  const int material = materialOf("material", "");
  const std::string materialName = r.string(j.at("material"), p + ".material");
  const int baseMaterial = materialOf("base_material", materialName);
  model::SectionBlocks blocks;
  try {
    blocks = model::cutSection(spec);
  } catch (const InputError& e) {
    if (drawn)
      if (const auto at = inDrawing(*drawn, *source, e.jsonPath())) r.fail(at->first, at->second + ": " + e.message());
    r.fail(p + "." + e.jsonPath(), e.message());
  }
  if (blocks.crack) {
    s.tensionCrack = blocks.crack;
    s.crackSearch = crackSearch;
    if (blocks.crack->waterFraction > 0) s.water.line = model::crackWaterLine(*blocks.crack, spec.ground);
  }
  const int baseIndex = static_cast<int>(s.blocks.size());
  blocks.base.material = baseMaterial;
  s.blocks.push_back(blocks.base);
  for (model::Block& b : blocks.slide) {
    b.material = material;
    s.blocks.push_back(b);
  }
  if (j.contains("sliding_joint")) {
    const std::string jn = r.string(j.at("sliding_joint"), p + ".sliding_joint");
    if (!jointIds.count(jn)) r.fail(p + ".sliding_joint", "unknown joint \"" + jn + "\" (not in joints)");
    for (size_t k = 0; k < blocks.slide.size(); ++k) s.pairJoints[{baseIndex, baseIndex + 1 + static_cast<int>(k)}] = jointIds.at(jn);
  }
}

std::string sectionDrawingSummary(const std::string& casePath) {
  const json doc = readJsonFile(casePath);
  if (!doc.is_object() || !doc.contains("section") || !doc.at("section").is_object() ||
      !doc.at("section").contains("dxf"))
    return "";
  const Reader r(casePath);
  return readDxfSection(readDxfSource(r, doc.at("section").at("dxf"), "section.dxf"), casePath, "section.dxf").summary;
}

}  // namespace ddaslope::io
