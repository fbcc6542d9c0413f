// Water pressure against hydrostatics (Archimedes) and Hoek & Bray's planar failure with a
// water-filled tension crack (benchmarks.md §C).
#include <gtest/gtest.h>

#include <cmath>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ddaslope/assembly/water_terms.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/model/pressure_grid.hpp"
#include "scene_builders.hpp"
#include "test_io.hpp"

using namespace ddaslope;

namespace {
model::WaterTable level(double y) {
  model::WaterTable w;
  w.line = {{0, y}, {1, y}};
  return w;
}
model::Block polygon(std::vector<Vec2> v) {
  model::Block b;
  b.vertices = std::move(v);
  b.moments = geometry::computeMoments(b.vertices);
  return b;
}
}  // namespace

// Vertical face submerged to depth H = 4 m: resultant γw H²/2, horizontal, pushing into the
// block (hydrostatics). The face runs downward: the left face of a counter-clockwise block.
TEST(Water, TriangularPressureOnAVerticalFace) {
  const Vec2 r = assembly::edgeWaterResultant({0, 6}, {0, 0}, level(4));  // 2 m of it above water
  EXPECT_NEAR(r.x(), 9810 * 16.0 / 2, 1e-6);
  EXPECT_NEAR(r.y(), 0, 1e-9);
}

// Archimedes: a fully submerged polygon feels γw·area upward, through its centroid (no moment),
// for any shape and orientation; a half-submerged one feels γw times its submerged area.
TEST(Water, BuoyancyEqualsDisplacedWeight) {
  const model::Block b = polygon({{1, -5}, {4, -6}, {6, -3}, {3, -1}, {0, -2}});
  const Vec6 f = assembly::waterForce(b, level(0));
  EXPECT_NEAR(f[0], 0, 1e-6);
  EXPECT_NEAR(f[1], 9810 * b.moments.area, 1e-6 * 9810 * b.moments.area);
  EXPECT_NEAR(f[2], 0, 1e-6 * 9810 * b.moments.area);
  const model::Block sq = polygon({{0, -1}, {2, -1}, {2, 1}, {0, 1}});
  EXPECT_NEAR(assembly::waterForce(sq, level(0))[1], 9810 * 2.0, 1e-6);
}

// A sloping phreatic line h(x) = x: on the top edge y = −1, 0 ≤ x ≤ 2 of a block below it, the
// pressure is γw (x + 1) and the resultant ∫ γw (x + 1) dx = 4 γw pushes down.
TEST(Water, SlopingPhreaticLineFollowsTheHead) {
  model::WaterTable sloping;
  sloping.line = {{0, 0}, {2, 2}};
  const Vec2 r = assembly::edgeWaterResultant({2, -1}, {0, -1}, sloping);
  EXPECT_NEAR(r.y(), -9810 * 4.0, 1e-6);
  EXPECT_NEAR(r.x(), 0, 1e-9);
}

// A reservoir level history (load history): a 2 × 1 m block hanging on a fixed point at its
// centroid, water rising from below it (t = 0) past mid-height (t = 1 s) to above it (t = 2 s).
// In static mode the fixed point's penalty spring carries the weight less the buoyancy of the
// submerged part: stretch (W − γw A_sub)/p (Archimedes and Hooke), within 1e-3 of W/p.
TEST(Water, RisingReservoirUnloadsAHangingBlock) {
  model::Scene s;
  s.materials.push_back({"rock", 2600, 5e9, 0.25});
  s.joints.push_back(model::JointProperties::coulomb("j", 0.5, 0));
  model::Block b;
  b.id = "block";
  b.vertices = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  b.moments = geometry::computeMoments(b.vertices);
  s.blocks = {b};
  const Vec2 c = b.moments.centroid;
  s.monitors.push_back({"centre", {0, c, c}});
  s.fixedPoints.push_back({{0, c, c}});
  s.water.seriesTimes = {0, 2};
  s.water.seriesLevels = {-0.5, 1.5};  // rises 1 m/s: bottom reached at 0.5 s, top at 1.5 s
  s.water.line = {{0, -0.5}, {1, -0.5}};
  s.settings.mode = model::AnalysisMode::Static;
  s.settings.duration = 2.0;
  const io::Trace t = scenes::runTrace(s);
  const double w = 2600 * 9.81 * 2, p = s.normalPenalty();
  for (const auto& [time, submerged] : {std::pair{1.0, 1.0}, std::pair{2.0, 2.0}}) {
    const double expected = -(w - 9810 * submerged) / p;
    EXPECT_NEAR(scenes::measureAt(t, "centre", "uy", time), expected, 1e-3 * w / p) << "t = " << time;
  }
}

// A pore-pressure ratio r_u on Hoek & Bray's planar failure (cases/planar_failure.json with
// "water": {"ru": r_u}): u = r_u γ h, h the depth below the ground, on every block face. On the
// wedge that is an uplift U = r_u γ ∫h ds on the sliding plane and a push V = r_u γ z²/2 on its
// back face (the open tension crack, depth z); Hoek & Bray's general form
// F = (cA + (W cos ψ − U − V sin ψ) tan φ)/(W sin ψ + V cos ψ) within 1 % for r_u = 0.1, 0.2, 0.3.
TEST(Water, PorePressureRatioOnThePlanarFailureMatchesTheClosedForm) {
  std::ifstream in(std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json");
  std::stringstream text;
  text << in.rdbuf();
  const double psi = std::atan2(14.004150764194, 20.0), phi = degToRad(30), c = 25e3;
  const double gamma = 2600 * 9.81;
  // ∫h ds along the plane y = x tan ψ under the ground y = min(x tan 60°, 20), x from 0 to 20.
  const double x1 = 20 / std::tan(degToRad(60));
  const double hdx = (std::tan(degToRad(60)) - std::tan(psi)) * x1 * x1 / 2 +
                     (20 * (20 - x1) - std::tan(psi) * (20 * 20 - x1 * x1) / 2);
  const double plane = 20 / std::cos(psi), z = 20 - 14.004150764194;
  for (double ru : {0.1, 0.2, 0.3}) {
    nlohmann::json doc = nlohmann::json::parse(text.str());
    doc["water"] = {{"ru", ru}};
    doc.erase("expected");
    const model::Scene s = io::parseCase(doc.dump(), "planar_failure_ru.json");
    const double w = s.blocks[1].moments.area * gamma;
    const double u = ru * gamma * hdx / std::cos(psi), v = ru * gamma * z * z / 2;
    const double expected =
        (c * plane + (w * std::cos(psi) - u - v * std::sin(psi)) * std::tan(phi)) / (w * std::sin(psi) + v * std::cos(psi));
    const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(s, {}, 1e-3);
    ASSERT_TRUE(r.found) << r.message;
    EXPECT_NEAR(r.factor, expected, 0.01 * expected) << "r_u = " << ru;
  }
}

// A pressure grid's thin-plate spline passes through every point (any data), and an affine field
// (a hydrostatic pressure under a planar water table) comes back exactly everywhere, also far
// from the points and with the points 1e5 m from the origin.
TEST(Water, PressureGridSplineIsExactAtItsPointsAndForAnAffineField) {
  std::vector<Vec2> pts;
  std::vector<double> bumpy, affine;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 5; ++j) {
      const Vec2 p(1e5 + 3.0 * i + 0.4 * j, 2.5 * j);
      pts.push_back(p);
      bumpy.push_back(1e4 * std::sin(0.7 * i) * std::cos(1.3 * j));
      affine.push_back(9810 * (4 + 0.3 * (p.x() - 1e5) - p.y()));
    }
  const model::PressureGrid g(pts, bumpy), a(pts, affine);
  for (size_t k = 0; k < pts.size(); ++k) EXPECT_NEAR(g.spline(pts[k]), bumpy[k], 1e-6 * 1e4);
  for (const Vec2& q : {Vec2(1e5 + 1.7, 3.3), Vec2(1e5 + 40, -20), Vec2(1e5 - 10, 1)})
    EXPECT_NEAR(a.spline(q), 9810 * (4 + 0.3 * (q.x() - 1e5) - q.y()), 1e-6 * 9810 * 30);
  EXPECT_EQ(a.at(Vec2(1e5, 50)), 0.0);  // above the table: suction taken as 0
}

// Hoek & Bray's water-filled crack (cases/planar_failure_water.json) given as a grid of points
// instead of its phreatic line: the line runs from the toe (0, 0) to (20, 20), so the pressure
// γw (x − y) is affine, and a grid sampling it below the line gives the line's F, which is
// Hoek & Bray's 0.8327 (benchmarks.md §C), within 1e-3. The grid read from a CSV file gives the same.
TEST(Water, PressureGridGivesThePhreaticLinesFactorOfSafety) {
  std::ifstream in(std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure_water.json");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json doc = nlohmann::json::parse(text.str());
  doc.erase("expected");
  const auto fos = [](const nlohmann::json& d, const std::string& file) {
    const model::Scene s = io::parseCase(d.dump(), file);
    const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(s, {}, 1e-3);
    EXPECT_TRUE(r.found) << r.message;
    return r.factor;
  };
  const double line = fos(doc, "line.json");
  EXPECT_NEAR(line, 0.8327, 0.01 * 0.8327);
  nlohmann::json points = nlohmann::json::array();
  std::string csv = "x,y,pressure\n";
  for (int i = 0; i <= 5; ++i)
    for (int j = 0; j <= 5; ++j) {
      const double x = 5.0 * i, y = -5.0 + 5.0 * j;
      if (y > x) continue;  // above the line: a grid lists what it knows, the wet points
      points.push_back({x, y, 9810 * (x - y)});
      csv += std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(9810 * (x - y)) + "\n";
    }
  doc["water"] = {{"pressure_grid", {{"points", points}}}};
  EXPECT_NEAR(fos(doc, "grid.json"), line, 1e-3);
  const std::string csvPath = clitest::writeTemp("grid.csv", csv);
  doc["water"] = {{"pressure_grid", {{"csv", std::filesystem::path(csvPath).filename().string()}}}};
  EXPECT_NEAR(fos(doc, (std::filesystem::path(csvPath).parent_path() / "grid_case.json").string()), line, 1e-3);
}

// Every bad value of a pressure grid is refused with the file and its JSON path.
TEST(Water, BadPressureGridsAreRefusedWithTheirPath) {
  std::ifstream in(std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json");
  std::stringstream text;
  text << in.rdbuf();
  const auto refused = [&](const nlohmann::json& water, const std::string& path, const std::string& what) {
    nlohmann::json doc = nlohmann::json::parse(text.str());
    doc["water"] = water;
    clitest::expectInputError([&] { io::parseCase(doc.dump(), "bad.json"); }, "bad.json", path, what);
  };
  const nlohmann::json three = {{0, 0, 1e4}, {10, 0, 2e4}, {0, 10, 0}};
  refused({{"pressure_grid", {{"points", {{0, 0, 1e4}, {10, 0, 2e4}}}}}}, "water.pressure_grid.points", "at least three");
  refused({{"pressure_grid", {{"points", {{0, 0, 1e4}, {5, 5, 2e4}, {10, 10, 0}}}}}}, "water.pressure_grid.points", "one line");
  refused({{"pressure_grid", {{"points", {{0, 0, 1e4}, {10, 0, 2e4}, {0, 0, 0}}}}}}, "water.pressure_grid.points[2]", "repeats point 0");
  refused({{"pressure_grid", {{"points", {{0, 0}, {10, 0, 2e4}, {0, 10, 0}}}}}}, "water.pressure_grid.points[0]", "[x, y, p]");
  refused({{"pressure_grid", {{"points", three}, {"csv", "g.csv"}}}}, "water.pressure_grid", "exactly one of points");
  refused({{"pressure_grid", {{"points", three}}}, {"unit_weight", 9810}}, "water.unit_weight", "not used with pressure_grid");
  refused({{"pressure_grid", {{"points", three}}}, {"level", 3}}, "water", "exactly one of level");
  refused({{"pressure_grid", {{"csv", "missing_grid.csv"}}}}, "water.pressure_grid.csv", "");
}
