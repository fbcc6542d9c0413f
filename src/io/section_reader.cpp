#include "section_reader.hpp"

#include "ddaslope/model/section.hpp"

namespace ddaslope::io {

using case_json::json;
using case_json::Reader;

void readSection(const Reader& r, const json& doc, model::Scene& s, const std::map<std::string, int>& materialIds,
                 const std::map<std::string, int>& jointIds) {
  if (!doc.contains("section")) return;
  const std::string p = "section";
  const json& j = doc.at(p);
  r.onlyKeys(j, p, {"ground", "sliding_surface", "base_depth", "material", "base_material", "sliding_joint", "joints",
                    "joint_sets", "kink_block_width"});
  const auto polyline = [&](const char* key) {
    const json& a = r.required(j, p, key);
    if (!a.is_array()) r.fail(p + "." + key, "expected an array of points [x, y]");
    std::vector<Vec2> pts;
    for (size_t i = 0; i < a.size(); ++i) pts.push_back(r.point(a[i], Reader::index(p + "." + key, i)));
    return pts;
  };
  model::SectionSpec spec;
  spec.ground = polyline("ground");
  spec.slidingSurface = polyline("sliding_surface");
  spec.baseDepth = r.number(r.required(j, p, "base_depth"), p + ".base_depth");
  if (j.contains("kink_block_width")) spec.kinkBlockWidth = r.number(j.at("kink_block_width"), p + ".kink_block_width");
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
    r.fail(p + "." + e.jsonPath(), e.message());
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

}  // namespace ddaslope::io
