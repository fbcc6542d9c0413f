// Slope sections drawn in CAD (issue #19): a DXF's layers give the ground, the sliding surface,
// the joints and the water line. The drawings are made by a CAD library (ezdxf) at build time,
// tests/make_dxf_fixtures.py; Vajont's is shipped (cases/vajont_section.dxf,
// scripts/make_vajont_dxf.py).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/geometry/polyline_chain.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/dxf_section.hpp"
#include "test_io.hpp"

using namespace ddaslope;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::string fixture(const std::string& name) { return std::string(DDASLOPE_DXF_FIXTURES) + "/" + name; }

/// The handle ezdxf gave the entity a fixture's error must name (fixtures.json).
std::string handleOf(const std::string& name) {
  std::ifstream in(fixture("fixtures.json"));
  return json::parse(in).at(name).get<std::string>();
}

const json kLayers = {{"ground", "GROUND"}, {"sliding_surface", "SLIP"}, {"joints", "JOINTS"}, {"water_line", "WATER"}};

/// A case cutting the drawn basin (tests/make_dxf_fixtures.py) with `dxf` as section.dxf.
json drawnCase(const json& dxf) {
  return {{"gravity", {0, -9.81}},
          {"materials", {{"rock", {{"density", 2600}, {"young_modulus", 5e9}, {"poisson_ratio", 0.25}}}}},
          {"joints", {{"rock", {{"friction_angle", 35}}}}},
          {"section", {{"dxf", dxf}, {"base_depth", 10}, {"material", "rock"}}},
          {"analysis", {{"duration", 1}, {"time_step", 0.001}}}};
}

json drawn(const std::string& name, const json& layers = kLayers) {
  return {{"file", fixture(name + ".dxf")}, {"layers", layers}};
}

/// The same basin given in the case itself (tests/test_section.cpp): slide mass 1050 m², cut in
/// two by the joint at x = 50; water at y = 10.
model::Scene jsonBasin() {
  json c = drawnCase({});
  c["section"] = {{"ground", {{0, 20}, {100, 20}}},
                  {"sliding_surface", {{10, 20}, {20, 5}, {80, 5}, {90, 20}}},
                  {"joints", {{{50, 0}, {50, 30}}}},
                  {"base_depth", 10},
                  {"material", "rock"}};
  c["water"] = {{"phreatic_line", {{0, 10}, {100, 10}}}};
  return io::parseCase(c.dump(), "case.json");
}

/// Same blocks in the same order: areas within `rel` of each other (relative), every vertex
/// within `rel` of the model's size.
void expectSameBlocks(const model::Scene& a, const model::Scene& b, double rel) {
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  const double size = 2 * a.modelHalfSize();
  for (size_t k = 0; k < a.blocks.size(); ++k) {
    const model::Block &p = a.blocks[k], &q = b.blocks[k];
    SCOPED_TRACE("block " + p.id);
    EXPECT_EQ(p.id, q.id);
    EXPECT_EQ(p.fixed, q.fixed);
    EXPECT_LE(std::abs(p.moments.area - q.moments.area), rel * std::abs(q.moments.area));
    ASSERT_EQ(p.vertices.size(), q.vertices.size());
    for (size_t i = 0; i < p.vertices.size(); ++i) EXPECT_LE((p.vertices[i] - q.vertices[i]).norm(), rel * size);
  }
}

void expectSameWater(const model::Scene& a, const model::Scene& b) {
  ASSERT_TRUE(a.water.active() && b.water.active());
  for (double x = -100; x <= 2000; x += 10) EXPECT_EQ(a.water.headAt(x), b.water.headAt(x)) << "x = " << x;
}

/// Expects the drawn case to be refused at `path`, the message containing each of `parts`.
void expectRefused(const json& dxf, const std::string& path, const std::vector<std::string>& parts,
                   const std::function<void(json&)>& edit = {}) {
  json c = drawnCase(dxf);
  if (edit) edit(c);
  for (const std::string& part : parts)
    clitest::expectInputError([&] { io::parseCase(c.dump(), "case.json"); }, "case.json", path, part);
}

}  // namespace

// Joining pieces end to end: any order, any direction; gaps, branches and loops are reported.
TEST(PolylineChain, JoinsPiecesInAnyOrderAndDirection) {
  // (0,0)-(1,0)-(2,1)-(3,1) given as three pieces, the middle one reversed and last.
  const geometry::Chain c = geometry::joinEndToEnd({{{0, 0}, {1, 0}}, {{3, 1}, {2, 1}}, {{2, 1}, {1, 0}}}, 1e-12);
  ASSERT_EQ(c.points.size(), 4u);
  EXPECT_EQ(c.stray, -1);
  EXPECT_FALSE(c.closed);
  const std::vector<Vec2> expected{{0, 0}, {1, 0}, {2, 1}, {3, 1}};
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(c.points[i], expected[i]);
  EXPECT_EQ(c.pieceOf, (std::vector<int>{0, 0, 2, 1}));

  const geometry::Chain gap = geometry::joinEndToEnd({{{0, 0}, {1, 0}}, {{1.5, 0}, {2, 0}}}, 1e-9);
  EXPECT_EQ(gap.stray, 1);
  const geometry::Chain branch = geometry::joinEndToEnd({{{0, 0}, {1, 0}, {2, 0}}, {{1, 0}, {1, 1}}}, 1e-9);
  EXPECT_EQ(branch.stray, 1);
  const geometry::Chain loop = geometry::joinEndToEnd({{{0, 0}, {1, 0}}, {{1, 0}, {0, 1}}, {{0, 1}, {0, 0}}}, 1e-9);
  EXPECT_EQ(loop.stray, -1);
  EXPECT_TRUE(loop.closed);
}

// Issue #19's acceptance: the shipped Vajont drawing cuts into the JSON section's blocks, count
// and areas within 1e-9 relative (measured: identical to the last bit, as the drawing holds the
// JSON's doubles), and its reservoir line is the JSON case's level.
TEST(DxfSection, VajontDrawingCutsIntoTheJsonSectionsBlocks) {
  const std::string cases = std::string(DDASLOPE_SOURCE_DIR) + "/cases/";
  const model::Scene fromJson = io::readCase(cases + "vajont.json");
  const model::Scene fromDxf = io::readCase(cases + "vajont_dxf.json");
  ASSERT_EQ(fromDxf.blocks.size(), 29u);  // base + 28 slide blocks
  expectSameBlocks(fromDxf, fromJson, 1e-9);
  expectSameWater(fromDxf, fromJson);
  EXPECT_EQ(fromDxf.pairJoints, fromJson.pairJoints);
}

// The basin drawn in every way the reader accepts gives the basin of the JSON section.
TEST(DxfSection, LinesPolylinesUnitsAndViewsGiveTheSameSection) {
  const model::Scene reference = jsonBasin();
  ASSERT_EQ(reference.blocks.size(), 3u);
  EXPECT_NEAR(reference.blocks[1].moments.area + reference.blocks[2].moments.area, 1050, 1e-9);
  const auto read = [](const json& dxf) { return io::parseCase(drawnCase(dxf).dump(), "case.json"); };
  for (const char* name :
       {"basin", "basin_drawn_otherwise", "basin_from_below", "basin_crlf", "basin_blank_lines_after_eof"}) {
    SCOPED_TRACE(name);
    const model::Scene s = read(drawn(name));
    expectSameBlocks(s, reference, 1e-12);
    expectSameWater(s, reference);
  }
  // Millimetres as the drawing declares them; feet given by the case for a drawing without units:
  // coordinates × 0.001 and × 0.3048 carry a rounding of a unit in the last place.
  json mm = drawn("basin_mm");
  expectSameBlocks(read(mm), reference, 1e-12);
  mm["units"] = "mm";
  expectSameBlocks(read(mm), reference, 1e-12);
  // AutoCAD R12 (no LWPOLYLINE, no $INSUNITS): old-style POLYLINEs, units from the case.
  json r12 = drawn("basin_r12");
  r12["units"] = "m";
  expectSameBlocks(read(r12), reference, 1e-12);
  json ft = drawn("basin_unitless_ft");
  ft["units"] = "ft";
  expectSameBlocks(read(ft), reference, 1e-12);
  // A sheet at 1:1000 in millimetres: scale 1000 gives the basin's true size.
  json sheet = drawn("basin_sheet_1000");
  sheet["scale"] = 1000;
  expectSameBlocks(read(sheet), reference, 1e-12);
}

// The drawing gives back the doubles it was written with, to the last bit (ezdxf writes the
// shortest decimal that rounds back; dxflib reads it correctly rounded).
TEST(DxfSection, CoordinatesRoundTripExactly) {
  std::ifstream in(fixture("awkward_doubles.json"));
  const json written = json::parse(in);
  io::DxfSectionSource src;
  src.file = fixture("awkward_doubles.dxf");
  src.groundLayer = "ground";  // CAD layer names are case-insensitive
  src.slidingSurfaceLayer = "Slip";
  const io::DxfSection s = io::readDxfSection(src, "case.json", "section.dxf");
  ASSERT_EQ(s.ground.size(), written["ground"].size());
  for (size_t i = 0; i < s.ground.size(); ++i) {
    EXPECT_EQ(s.ground[i].x(), written["ground"][i][0].get<double>());
    EXPECT_EQ(s.ground[i].y(), written["ground"][i][1].get<double>());
  }
  ASSERT_EQ(s.slidingSurface.size(), written["sliding_surface"].size());
  for (size_t i = 0; i < s.slidingSurface.size(); ++i) {
    EXPECT_EQ(s.slidingSurface[i].x(), written["sliding_surface"][i][0].get<double>());
    EXPECT_EQ(s.slidingSurface[i].y(), written["sliding_surface"][i][1].get<double>());
  }
  EXPECT_NE(s.summary.find("ground 4 points from 1 LWPOLYLINE on \"ground\""), std::string::npos) << s.summary;
}

// Each malformed drawing is refused (exit 2) naming the case, the JSON path of what it was read
// for, the DXF, the layer and the entity (type, index on its layer, handle).
TEST(DxfSection, MalformedDrawingsNameTheFileTheLayerAndTheEntity) {
  struct EntityError {
    const char *fixture, *key, *layer, *type;
    int index;  // on its layer
    const char* what;
  };
  const EntityError entityErrors[] = {
      {"closed_ground", "ground", "GROUND", "LWPOLYLINE", 1, "a closed polyline, where the ground is an open line"},
      {"sliding_surface_loop", "sliding_surface", "SLIP", "LINE", 1, "close into a loop"},
      {"ground_gap", "ground", "GROUND", "LINE", 2, "does not meet the other entities on the layer end to end"},
      {"ground_one_point", "ground", "GROUND", "LINE", 1, "its points all coincide"},
      {"arc_on_joints", "joints", "JOINTS", "ARC", 2, "an entity of type ARC"},
      {"arc_segment", "sliding_surface", "SLIP", "LWPOLYLINE", 1, "vertex 2 starts an arc segment (bulge)"},
      {"three_d", "ground", "GROUND", "LINE", 1, "point 2 is at z = 5"},
      {"bent_joint", "joints", "JOINTS", "LWPOLYLINE", 1, "bends at point 2"},
      {"water_line_back", "water_line", "WATER", "LWPOLYLINE", 1, "at (40, 11) m: expected x increasing"},
      // The cut's own check, pointed at the drawing.
      {"sliding_surface_above_ground", "sliding_surface", "SLIP", "LWPOLYLINE", 1,
       "at (20, 25) m: expected the sliding surface below the ground"},
  };
  for (const EntityError& e : entityErrors) {
    SCOPED_TRACE(e.fixture);
    const std::string entity = "layer \"" + std::string(e.layer) + "\", " + e.type + " #" + std::to_string(e.index) +
                               " (handle " + handleOf(e.fixture) + ")";
    expectRefused(drawn(e.fixture), std::string("section.dxf.layers.") + e.key,
                  {fixture(std::string(e.fixture) + ".dxf"), entity, e.what});
  }
  // Layers.
  json layers = kLayers;
  layers["ground"] = "TERRAIN";
  expectRefused(drawn("basin", layers), "section.dxf.layers.ground",
                {fixture("basin.dxf"), "no layer \"TERRAIN\" in the drawing (its layers: \"0\", \"Defpoints\", \"GROUND\", \"SLIP\""});
  expectRefused(drawn("empty_joints_layer"), "section.dxf.layers.joints",
                {fixture("empty_joints_layer.dxf"), "layer \"JOINTS\" holds no lines or polylines in model space"});
  // Units.
  expectRefused(drawn("parsecs"), "section.dxf.units", {fixture("parsecs.dxf"), "parsecs ($INSUNITS = 20)"});
  json mInMm = drawn("basin_mm");
  mInMm["units"] = "m";
  expectRefused(mInMm, "section.dxf.units",
                {fixture("basin_mm.dxf"), "declares its units as millimetres ($INSUNITS = 4), the case says \"m\""});
  expectRefused(drawn("basin_unitless_ft"), "section.dxf.units",
                {fixture("basin_unitless_ft.dxf"), "declares no units ($INSUNITS 0 or absent)"});
  json furlongs = drawn("basin");
  furlongs["units"] = "furlong";
  expectRefused(furlongs, "section.dxf.units", {"expected one of in, ft, mi, mm, cm, m, km"});
  json huge = drawn("basin_mm");
  huge["scale"] = 1e6;
  expectRefused(huge, "section.dxf.scale", {"span 100000000 m read in millimetres at scale 1000000", "outside the 1 mm to 1000 km"});
  // Files that are not sound DXF.
  expectRefused(drawn("not_dxf"), "section.dxf.file", {fixture("not_dxf.dxf"), "not a DXF file"});
  expectRefused(drawn("binary"), "section.dxf.file", {"a binary DXF: save the drawing as ASCII DXF"});
  expectRefused(drawn("truncated"), "section.dxf.file", {"truncated"});
  expectRefused(drawn("text_after_eof"), "section.dxf.file", {"text after the end-of-file marker (group 0, EOF)"});
  expectRefused(drawn("huge_count"), "section.dxf.file",
                {"group 90 of LWPOLYLINE gives a count of \"2147483647\": expected a whole number of at most 1000000"});
  expectRefused(drawn("no_such_drawing"), "section.dxf.file", {fixture("no_such_drawing.dxf"), "does not exist"});
}

// What the case says must not contradict what the drawing gives.
TEST(DxfSection, TheCaseAndTheDrawingDoNotBothGiveALine) {
  expectRefused(drawn("basin"), "section.ground", {"given twice: by the case and by the drawing's layer \"GROUND\""},
                [](json& c) { c["section"]["ground"] = {{0, 20}, {100, 20}}; });
  expectRefused(drawn("basin"), "water", {"the water line is drawn (section.dxf.layers.water_line)"},
                [](json& c) { c["water"] = {{"level", 12}}; });
  json layers = kLayers;
  layers.erase("water_line");
  // Unmapped, the drawn water is ignored and the case's level applies.
  json c = drawnCase(drawn("basin", layers));
  c["water"] = {{"level", 12}, {"unit_weight", 10000}};
  const model::Scene s = io::parseCase(c.dump(), "case.json");
  EXPECT_EQ(s.water.headAt(50), 12);
  layers.erase("sliding_surface");
  expectRefused(drawn("basin", layers), "section.dxf.layers.sliding_surface", {"required key is missing"});
}

// The command line: `cut` writes the drawn Vajont's blocks as a plain case that keeps the drawn
// water line; `check` on a malformed drawing exits 2 naming the case, the DXF, layer and entity.
TEST(Cli, CutAndCheckADrawnSection) {
  const std::string cases = std::string(DDASLOPE_SOURCE_DIR) + "/cases/";
  const fs::path out = fs::temp_directory_path() / ("ddaslope_dxf_cut_" + std::to_string(::getpid()));
  std::string err;
  const std::string printed = clitest::captureCli("cut " + cases + "vajont_dxf.json --out " + out.string(), &err);
  EXPECT_NE(printed.find("29 blocks (28 free, 1 fixed)"), std::string::npos) << printed;
  EXPECT_NE(printed.find("section drawn in " + cases + "vajont_section.dxf (metres, declared by the drawing; scale 1)"),
            std::string::npos)
      << printed;
  EXPECT_TRUE(fs::exists(out / "section.png"));
  const model::Scene plain = io::readCase((out / "blocks.json").string());
  const model::Scene fromJson = io::readCase(cases + "vajont.json");
  expectSameBlocks(plain, fromJson, 1e-12);
  expectSameWater(plain, fromJson);
  fs::remove_all(out);

  const std::string bad = clitest::writeTemp("closed_ground.json", drawnCase(drawn("closed_ground")).dump());
  EXPECT_EQ(clitest::runCli("check " + bad, &err), 2);
  for (const std::string& part : {bad, std::string("section.dxf.layers.ground"), fixture("closed_ground.dxf"),
                                  "layer \"GROUND\", LWPOLYLINE #1 (handle " + handleOf("closed_ground") + ")"})
    EXPECT_NE(err.find(part), std::string::npos) << part << " not in: " << err;
  fs::remove(bad);
}
