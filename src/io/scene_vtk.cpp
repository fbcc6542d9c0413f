#include "ddaslope/io/scene_vtk.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::io {
namespace {

namespace fs = std::filesystem;

constexpr const char* kKinds[] = {"blocks", "contacts", "water", "supports"};

VtkArray numbers(const std::string& name, int components = 1, std::vector<std::string> componentNames = {}) {
  return {name, components, std::move(componentNames), std::vector<double>{}};
}
VtkArray integers(const std::string& name) { return {name, 1, {}, std::vector<std::int32_t>{}}; }
std::vector<double>& numbersOf(VtkArray& a) { return std::get<std::vector<double>>(a.values); }
std::vector<std::int32_t>& integersOf(VtkArray& a) { return std::get<std::vector<std::int32_t>>(a.values); }

VtkArray names(const std::string& name, std::vector<std::string> values) { return {name, 1, {}, std::move(values)}; }

std::vector<std::string> blockNames(const model::Scene& scene) {
  std::vector<std::string> out;
  for (const model::Block& b : scene.blocks) out.push_back(b.id);
  return out;
}

/// The grid's points in the case's own coordinates (model::Scene::origin).
void inCaseCoordinates(VtkGrid& g, const model::Scene& scene) {
  for (Vec2& p : g.points) p += scene.origin;
}

}  // namespace

VtkGrid blocksGrid(const solver::Simulation& sim, const std::vector<Vec2>& initialCentroids) {
  const model::Scene& scene = sim.scene();
  DDASLOPE_ASSERT(initialCentroids.size() == scene.blocks.size(), "one initial centroid per block");
  VtkGrid g;
  VtkArray id = integers("block_id"), material = integers("material"), fixed = integers("fixed");
  // Vectors have a zero z component: ParaView's glyphs and warps take 3-vectors.
  VtkArray displacement = numbers("displacement", 3), velocity = numbers("velocity", 3);
  VtkArray rotation = numbers("rotation"), spin = numbers("angular_velocity");
  VtkArray stress = numbers("stress", 3, {"xx", "yy", "xy"});
  for (size_t b = 0; b < scene.blocks.size(); ++b) {
    const model::Block& blk = scene.blocks[b];
    g.addCell(VtkCellType::Polygon, blk.vertices);
    integersOf(id).push_back(static_cast<std::int32_t>(b));
    integersOf(material).push_back(blk.material);
    integersOf(fixed).push_back(blk.fixed ? 1 : 0);
    const Vec2 u = blk.moments.centroid - initialCentroids[b];
    numbersOf(displacement).insert(numbersOf(displacement).end(), {u.x(), u.y(), 0.0});
    // T at the centroid is [I 0]: u0, v0 of the velocity are the centroid's.
    numbersOf(velocity).insert(numbersOf(velocity).end(), {blk.velocity[0], blk.velocity[1], 0.0});
    numbersOf(rotation).push_back(blk.rotation);
    numbersOf(spin).push_back(blk.velocity[2]);
    numbersOf(stress).insert(numbersOf(stress).end(), {blk.stress[0], blk.stress[1], blk.stress[2]});
  }
  g.cellData = {id, material, fixed, displacement, velocity, rotation, spin, stress};
  inCaseCoordinates(g, scene);
  std::vector<std::string> materials;
  for (const model::Material& m : scene.materials) materials.push_back(m.name);
  g.fieldData = {names("block_names", blockNames(scene)), names("material_names", materials)};
  return g;
}

VtkGrid contactsGrid(const solver::Simulation& sim) {
  const model::Scene& scene = sim.scene();
  VtkGrid g;
  VtkArray state = integers("state"), bonded = integers("bonded"), joint = integers("joint");
  VtkArray vertexBlock = integers("vertex_block"), edgeBlock = integers("edge_block"), edgeToEdge = integers("edge_to_edge");
  VtkArray normal = numbers("normal_force"), shear = numbers("shear_force"), slip = numbers("slip");
  for (const contact::Contact& c : sim.contacts().contacts()) {
    const contact::ContactKey& k = c.key();
    const model::Block &vb = scene.blocks[k.vertexBlock], &eb = scene.blocks[k.edgeBlock];
    const Vec2 p = vb.vertices[k.vertex];
    const Vec2 edge = eb.vertices[(k.edge + 1) % eb.vertices.size()] - eb.vertices[k.edge];
    // Counter-clockwise vertices: the edge's outward normal, toward the vertex block, is its
    // direction turned clockwise.
    const Vec2 inward = Vec2(edge.y(), -edge.x()).normalized();
    const double length = 0.15 * std::sqrt(std::min(vb.moments.area, eb.moments.area));
    g.addCell(VtkCellType::Line, {p, p + length * inward});
    integersOf(state).push_back(static_cast<std::int32_t>(c.state));
    // An open contact carries nothing; its stored force is the penalty times its gap.
    numbersOf(normal).push_back(c.closed() ? c.normalForce : 0.0);
    numbersOf(shear).push_back(c.closed() ? std::abs(c.shearForce) : 0.0);
    integersOf(bonded).push_back(c.bonded ? 1 : 0);
    integersOf(joint).push_back(c.joint);
    integersOf(vertexBlock).push_back(k.vertexBlock);
    integersOf(edgeBlock).push_back(k.edgeBlock);
    integersOf(edgeToEdge).push_back(c.geometry.pairedEdge >= 0 ? 1 : 0);
    numbersOf(slip).push_back(c.slipDistance);
  }
  g.cellData = {state, normal, shear, bonded, joint, vertexBlock, edgeBlock, edgeToEdge, slip};
  inCaseCoordinates(g, scene);
  std::vector<std::string> joints;
  for (const model::JointProperties& j : scene.joints) joints.push_back(j.name);
  g.fieldData = {names("joint_names", joints), names("block_names", blockNames(scene))};
  return g;
}

VtkGrid waterGrid(const solver::Simulation& sim) {
  const model::Scene& scene = sim.scene();
  VtkGrid g;
  if (scene.water.line.empty()) return g;  // a pressure grid has no line to draw
  const model::WaterTable water = scene.water.at(sim.time());
  double lo = INFINITY, hi = -INFINITY;
  for (const model::Block& b : scene.blocks)
    for (const Vec2& v : b.vertices) lo = std::min(lo, v.x()), hi = std::max(hi, v.x());
  std::vector<Vec2> line{{lo, water.headAt(lo)}};
  for (const Vec2& p : water.line)
    if (p.x() > lo && p.x() < hi) line.push_back(p);
  line.push_back({hi, water.headAt(hi)});
  g.addCell(VtkCellType::PolyLine, line);
  inCaseCoordinates(g, scene);
  return g;
}

VtkGrid supportsGrid(const solver::Simulation& sim) {
  const model::Scene& scene = sim.scene();
  VtkGrid g;
  VtkArray state = integers("state"), force = numbers("force"), elongation = numbers("elongation");
  VtkArray plastic = numbers("plastic_elongation");
  for (const model::Support& b : scene.supports) {
    g.addCell(VtkCellType::Line, {b.head.current, b.end.current});
    integersOf(state).push_back(static_cast<std::int32_t>(b.state));
    numbersOf(force).push_back(b.force);
    numbersOf(elongation).push_back(b.elongation());
    numbersOf(plastic).push_back(b.plasticElongation);
  }
  g.cellData = {state, force, elongation, plastic};
  inCaseCoordinates(g, scene);
  std::vector<std::string> ids;
  for (const model::Support& b : scene.supports) ids.push_back(b.id);
  g.fieldData = {names("support_names", ids),
                 names("state_names", {"elastic", "yielded", "slack", "broken"})};
  return g;
}

VtkRecorder::VtkRecorder(const std::string& dir, const model::Scene& scene)
    : dir_(dir),
      water_(!scene.water.line.empty()),
      supports_(!scene.supports.empty()),
      blocks_(dir + "/blocks.pvd"),
      contacts_(dir + "/contacts.pvd"),
      waterSeries_(dir + "/water.pvd"),
      supportSeries_(dir + "/supports.pvd") {
  for (const model::Block& b : scene.blocks) initialCentroids_.push_back(b.moments.centroid);
  removeVtkSeries(dir);
  fs::create_directories(dir);
}

void VtkRecorder::write(const solver::Simulation& sim, double timestep, const std::string& label,
                        const std::vector<VtkArray>& notes) {
  // TimeValue: the field-data name VTK's file-series readers take a file's time from.
  std::vector<VtkArray> field{{"TimeValue", 1, {}, std::vector<double>{timestep}},
                              {"simulated_time", 1, {}, std::vector<double>{sim.time()}}};
  field.insert(field.end(), notes.begin(), notes.end());
  const auto save = [&](VtkGrid g, const char* kind, PvdCollection& series) {
    g.fieldData.insert(g.fieldData.begin(), field.begin(), field.end());
    const std::string file = std::string(kind) + "_" + label + ".vtu";
    writeVtu(dir_ + "/" + file, g);
    return [&series, timestep, file] { series.add(timestep, file); };
  };
  // Every file of the frame first, then the .pvd entries: a series never lists a missing file.
  std::vector<std::function<void()>> entries{save(blocksGrid(sim, initialCentroids_), kKinds[0], blocks_),
                                             save(contactsGrid(sim), kKinds[1], contacts_)};
  if (water_) entries.push_back(save(waterGrid(sim), kKinds[2], waterSeries_));
  if (supports_) entries.push_back(save(supportsGrid(sim), kKinds[3], supportSeries_));
  for (const auto& add : entries) add();
}

bool finiteState(const solver::Simulation& sim) {
  for (const model::Block& b : sim.scene().blocks) {
    if (!b.velocity.allFinite() || !b.stress.allFinite() || !std::isfinite(b.rotation)) return false;
    for (const Vec2& v : b.vertices)
      if (!v.allFinite()) return false;
  }
  for (const contact::Contact& c : sim.contacts().contacts())
    if (!std::isfinite(c.normalForce) || !std::isfinite(c.shearForce) || !std::isfinite(c.slipDistance)) return false;
  return true;
}

void removeVtkSeries(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  std::vector<fs::path> ours;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    for (const std::string kind : kKinds) {
      const bool frame = name.starts_with(kind + "_") && (name.ends_with(".vtu") || name.ends_with(".vtu.tmp"));
      if (frame || name == kind + ".pvd" || name == kind + ".pvd.tmp") ours.push_back(e.path());
    }
  }
  for (const fs::path& p : ours) fs::remove(p);
  if (fs::is_empty(dir, ec)) fs::remove(dir, ec);
}

}  // namespace ddaslope::io
