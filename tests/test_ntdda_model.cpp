// Models of Shi's DDA (ntdda's .geo and .ana): the polygoniser on closed forms, the wall that
// ../shared/ntdda/json2ntdda.py writes read back, a case through ntdda's files and back, our own
// model in both of ntdda's forms, and bad input refused with exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include "ddaslope/geometry/line_arrangement.hpp"
#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/ntdda_model.hpp"
#include "fuzz_mutations.hpp"
#include "test_io.hpp"

namespace {

using ddaslope::Vec2;
using ddaslope::geometry::arrangeLines;
using ddaslope::geometry::LineArrangement;
using ddaslope::geometry::TypedSegment;
using ddaslope::model::Scene;
using clitest::runCli;
using clitest::writeTemp;

const std::string kData = std::string(DDASLOPE_SOURCE_DIR) + "/tests/data/ntdda/";

std::vector<double> sortedAreas(const LineArrangement& a) {
  std::vector<double> areas;
  for (const auto& f : a.faces) areas.push_back(ddaslope::geometry::signedArea(f));
  std::sort(areas.begin(), areas.end());
  return areas;
}

TypedSegment seg(double x1, double y1, double x2, double y2, int type = 1) { return {{x1, y1}, {x2, y2}, type}; }

// --- The polygoniser, on figures whose blocks are known exactly ---

TEST(LineArrangement, SquareCutByOneDiagonalGivesTwoHalfTriangles) {
  const auto a = arrangeLines({seg(0, 0, 1, 0), seg(1, 0, 1, 1), seg(1, 1, 0, 1), seg(0, 1, 0, 0), seg(0, 0, 1, 1, 2)}, 1e-9);
  ASSERT_EQ(a.faces.size(), 2u);
  for (const auto& f : a.faces) {
    EXPECT_EQ(f.size(), 3u);
    EXPECT_NEAR(ddaslope::geometry::signedArea(f), 0.5, 1e-15);  // counter-clockwise
  }
  // The diagonal is the one edge between the two blocks, with its own type.
  int shared = 0;
  for (const auto& e : a.edges)
    if (e.left >= 0 && e.right >= 0) {
      ++shared;
      EXPECT_EQ(e.type, 2);
      EXPECT_NEAR(e.length, std::sqrt(2.0), 1e-15);
    }
  EXPECT_EQ(shared, 1);
  EXPECT_EQ(a.danglingEdges, 0);
}

TEST(LineArrangement, ThreeByTwoGridGivesSixUnitCells) {
  std::vector<TypedSegment> lines;
  for (int x = 0; x <= 3; ++x) lines.push_back(seg(x, 0, x, 2));
  for (int y = 0; y <= 2; ++y) lines.push_back(seg(0, y, 3, y));
  const auto a = arrangeLines(lines, 1e-9);
  ASSERT_EQ(a.faces.size(), 6u);
  for (double area : sortedAreas(a)) EXPECT_NEAR(area, 1.0, 1e-15);
  // Bottom row first, left to right, each starting at its lower-left corner.
  EXPECT_EQ(a.faces[0][0], Vec2(0, 0));
  EXPECT_EQ(a.faces[2][0], Vec2(2, 0));
  EXPECT_EQ(a.faces[3][0], Vec2(0, 1));
  int inner = 0;
  for (const auto& e : a.edges) inner += e.left >= 0 && e.right >= 0;
  EXPECT_EQ(inner, 7);  // 4 vertical + 3 horizontal unit edges inside
}

TEST(LineArrangement, TJunctionsSplitTheLinesTheyEndOn) {
  // A vertical line ending on the square's bottom and top, and a half line ending on it.
  const auto a = arrangeLines({seg(0, 0, 2, 0), seg(2, 0, 2, 2), seg(2, 2, 0, 2), seg(0, 2, 0, 0), seg(1, 0, 1, 2), seg(0, 1, 1, 1)}, 1e-9);
  ASSERT_EQ(a.faces.size(), 3u);
  EXPECT_EQ(sortedAreas(a), (std::vector<double>{1, 1, 2}));
  // The right block keeps four corners: the T-junction vertex (1, 1) on its left side is removed.
  for (const auto& f : a.faces) EXPECT_EQ(f.size(), 4u);
}

TEST(LineArrangement, DanglingLinesAreDropped) {
  // A square, a line from inside it through its side into the air, and a lone line elsewhere.
  const auto a = arrangeLines({seg(0, 0, 1, 0), seg(1, 0, 1, 1), seg(1, 1, 0, 1), seg(0, 1, 0, 0), seg(0.5, 0.2, 2, 0.2), seg(5, 5, 6, 6)}, 1e-9);
  ASSERT_EQ(a.faces.size(), 1u);
  EXPECT_NEAR(ddaslope::geometry::signedArea(a.faces[0]), 1.0, 1e-15);
  EXPECT_EQ(a.faces[0].size(), 4u);
  EXPECT_EQ(a.danglingEdges, 3);
}

TEST(LineArrangement, ALineJoiningTwoBlocksBoundsNeither) {
  // Two unit squares joined by a line between their facing sides: a bridge, not a block's edge.
  const auto a = arrangeLines({seg(0, 0, 1, 0), seg(1, 0, 1, 1), seg(1, 1, 0, 1), seg(0, 1, 0, 0), seg(2, 0, 3, 0), seg(3, 0, 3, 1),
                               seg(3, 1, 2, 1), seg(2, 1, 2, 0), seg(1, 0.5, 2, 0.5)},
                              1e-9);
  ASSERT_EQ(a.faces.size(), 2u);
  EXPECT_EQ(sortedAreas(a), (std::vector<double>{1, 1}));
  EXPECT_EQ(a.bridgeEdges, 1);
  for (const auto& f : a.faces) EXPECT_EQ(f.size(), 4u);
}

TEST(LineArrangement, OvershootsAndGapsWithinTheEdgeNodeDistanceClose) {
  // Corners drawn 1 mm short or long, as drawn by hand in ntdda; merged within 5 mm.
  const auto a = arrangeLines({seg(-0.001, 0, 1.001, 0), seg(1, 0.001, 1, 0.999), seg(1.001, 1, 0, 1), seg(0, 1.001, 0, 0.001)}, 5e-3);
  ASSERT_EQ(a.faces.size(), 1u);
  EXPECT_NEAR(ddaslope::geometry::signedArea(a.faces[0]), 1.0, 3e-3);
}

TEST(LineArrangement, ThreeLineStarClosesNoBlock) {
  const auto a = arrangeLines({seg(-1, 0, 1, 0), seg(-0.5, -1, 0.5, 1), seg(0.5, -1, -0.5, 1)}, 1e-9);
  EXPECT_TRUE(a.faces.empty());
  // As a model: refused, naming the file and what was expected.
  ddaslope::io::NtddaGeometry g;
  g.file = "star.geo";
  for (const auto& s : {seg(-1, 0, 1, 0), seg(-0.5, -1, 0.5, 1), seg(0.5, -1, -0.5, 1)}) g.joints.push_back({s.a, s.b, 1, {}});
  try {
    ddaslope::io::convertNtddaModel(g, nullptr);
    ADD_FAILURE() << "a star of lines accepted";
  } catch (const ddaslope::InputError& e) {
    EXPECT_EQ(e.file(), "star.geo");
    EXPECT_NE(e.message().find("close at least one block"), std::string::npos) << e.what();
  }
}

TEST(LineArrangement, ABlockWithAnotherInsideItIsNotABlock) {
  // An island square inside a bigger one, not touching it: the ring has a hole.
  const auto a = arrangeLines({seg(0, 0, 4, 0), seg(4, 0, 4, 4), seg(4, 4, 0, 4), seg(0, 4, 0, 0), seg(1, 1, 2, 1), seg(2, 1, 2, 2),
                               seg(2, 2, 1, 2), seg(1, 2, 1, 1)},
                              1e-9);
  ASSERT_EQ(a.faces.size(), 1u);
  EXPECT_NEAR(ddaslope::geometry::signedArea(a.faces[0]), 1.0, 1e-15);
  EXPECT_EQ(a.holedFaces, 1);
}

// --- Whole models ---

Scene convertToScene(const std::string& geo, const std::string& ana, std::vector<std::string>* notes = nullptr) {
  const auto g = ddaslope::io::readNtddaGeometry(geo);
  const auto a = ddaslope::io::readNtddaAnalysis(ana);
  const auto m = ddaslope::io::convertNtddaModel(g, &a);
  if (notes) *notes = m.notes;
  return ddaslope::io::parseCase(m.caseJson, geo + " (converted)");
}

/// The block of `s` whose centroid is within `tol` of c; −1 for none.
int blockAt(const Scene& s, const Vec2& c, double tol) {
  for (size_t b = 0; b < s.blocks.size(); ++b)
    if ((s.blocks[b].moments.centroid + s.origin - c).norm() <= tol) return static_cast<int>(b);
  return -1;
}

/// Do two polygons share a stretch of boundary of positive length?
bool shareFace(const std::vector<Vec2>& p, const std::vector<Vec2>& q, double tol) {
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = 0; j < q.size(); ++j) {
      const Vec2 &a = p[i], &b = p[(i + 1) % p.size()], &c = q[j], &d = q[(j + 1) % q.size()];
      const Vec2 u = (b - a).normalized();
      if (std::abs(ddaslope::cross(u, c - a)) > tol || std::abs(ddaslope::cross(u, d - a)) > tol) continue;
      const double s0 = std::max(0.0, std::min(u.dot(c - a), u.dot(d - a))), s1 = std::min((b - a).norm(), std::max(u.dot(c - a), u.dot(d - a)));
      if (s1 - s0 > tol) return true;
    }
  return false;
}

/// Same blocks (areas and centroids within 1e-9 relative, fixed alike, same material density),
/// joints, settings and monitors. Returns the block map original → converted.
std::vector<int> expectSameModel(const Scene& want, const Scene& got) {
  EXPECT_EQ(got.blocks.size(), want.blocks.size());
  const double w0 = want.modelHalfSize();
  std::vector<int> map;
  for (const auto& b : want.blocks) {
    const Vec2 c = b.moments.centroid + want.origin;
    const int k = blockAt(got, c, 1e-9 * w0);
    map.push_back(k);
    if (k < 0) {
      ADD_FAILURE() << "block " << b.id << " (centroid " << c.transpose() << ") not found";
      continue;
    }
    const auto& o = got.blocks[k];
    EXPECT_NEAR(o.moments.area, b.moments.area, 1e-9 * b.moments.area) << b.id;
    EXPECT_EQ(o.fixed, b.fixed) << b.id;
    EXPECT_EQ(got.materials[o.material].density, want.materials[b.material].density) << b.id;
    EXPECT_EQ(got.materials[o.material].youngModulus, want.materials[b.material].youngModulus) << b.id;
    EXPECT_EQ(got.materials[o.material].poissonRatio, want.materials[b.material].poissonRatio) << b.id;
  }
  EXPECT_NEAR(got.gravity.y(), want.gravity.y(), 1e-15);
  // ntdda counts whole steps.
  EXPECT_NEAR(got.settings.duration, want.settings.duration, 0.5 * want.settings.timeStep);
  EXPECT_EQ(got.settings.timeStep, want.settings.timeStep);
  EXPECT_NEAR(got.normalPenalty(), want.normalPenalty(), 1e-9 * want.normalPenalty());
  // ntdda's g2 is written as ddaslope holds it: at most a tenth of the thinnest free block.
  double thinnest = INFINITY;
  for (const auto& b : want.blocks)
    if (!b.fixed) thinnest = std::min(thinnest, 2 * b.moments.area / ddaslope::geometry::perimeter(b.vertices));
  EXPECT_NEAR(got.settings.maxDisplacementRatio, std::min(want.settings.maxDisplacementRatio, 0.1 * thinnest / w0),
              1e-15);
  EXPECT_EQ(got.settings.mode, want.settings.mode);
  EXPECT_EQ(got.settings.plane, want.settings.plane);
  // The joint of every pair of blocks that share a face (which joint is the default may differ).
  for (size_t i = 0; i < want.blocks.size(); ++i)
    for (size_t j = i + 1; j < want.blocks.size(); ++j) {
      if (map[i] < 0 || map[j] < 0 || !shareFace(want.blocks[i].vertices, want.blocks[j].vertices, 1e-9 * w0)) continue;
      const auto& ji = want.joints[want.jointBetween(static_cast<int>(i), static_cast<int>(j))];
      const auto& jo = got.joints[got.jointBetween(map[i], map[j])];
      EXPECT_NEAR(jo.frictionAngle, ji.frictionAngle, 1e-14) << want.blocks[i].id << "/" << want.blocks[j].id;
      EXPECT_EQ(jo.cohesion, ji.cohesion) << want.blocks[i].id << "/" << want.blocks[j].id;
      EXPECT_EQ(jo.tensileStrength, ji.tensileStrength) << want.blocks[i].id << "/" << want.blocks[j].id;
    }
  EXPECT_EQ(got.monitors.size(), want.monitors.size());
  for (size_t m = 0; m < std::min(got.monitors.size(), want.monitors.size()); ++m) {
    EXPECT_EQ(got.monitors[m].point.initial + got.origin, want.monitors[m].point.initial + want.origin);
    EXPECT_EQ(got.monitors[m].point.block, map[want.monitors[m].point.block]);
  }
  return map;
}

// ../shared/ntdda/json2ntdda.py's wall (tests/data/ntdda/make_fixtures.sh) reads back as the case
// it came from.
TEST(NtddaModel, Json2ntddaWallReadsBackAsItsCase) {
  const Scene want = ddaslope::io::readCase(kData + "wall3.json");
  const Scene got = convertToScene(kData + "wall3.geo", kData + "wall3.ana");
  expectSameModel(want, got);
}

TEST(NtddaModel, Json2ntddaWallWithTwoMaterialsAndTwoJointsReadsBack) {
  const Scene want = ddaslope::io::readCase(kData + "wall3_mixed.json");
  const Scene got = convertToScene(kData + "wall3_mixed.geo", kData + "wall3_mixed.ana");
  const auto map = expectSameModel(want, got);
  // The weak joint between the first two bricks, friction 20°, and only there.
  const int a = want.blockIndex("r0b0"), b = want.blockIndex("r0b1");
  ASSERT_GE(map[a], 0);
  ASSERT_GE(map[b], 0);
  EXPECT_NEAR(got.joints[got.jointBetween(map[a], map[b])].frictionAngle, 20 * std::numbers::pi / 180, 1e-14);
  EXPECT_EQ(got.pairJoints.size(), 1u);
}

// A case through ntdda's files and back in C++: the same blocks, vertex for vertex.
void expectCaseRoundTrip(const std::string& casePath) {
  SCOPED_TRACE(casePath);
  const Scene want = ddaslope::io::readCase(casePath);
  const auto files = ddaslope::io::writeNtddaModel(want, casePath);
  const std::string stem = std::filesystem::path(casePath).stem().string();
  const std::string geo = writeTemp(stem + ".geo", files.geometry), ana = writeTemp(stem + ".ana", files.analysis);
  const Scene got = convertToScene(geo, ana);
  const auto map = expectSameModel(want, got);
  const double tol = 1e-9 * want.modelHalfSize();
  for (size_t i = 0; i < want.blocks.size(); ++i) {
    if (map[i] < 0) continue;
    const auto& vw = want.blocks[i].vertices;
    const auto& vg = got.blocks[map[i]].vertices;
    ASSERT_EQ(vg.size(), vw.size()) << want.blocks[i].id;
    for (const Vec2& p : vw) {
      const bool found = std::any_of(vg.begin(), vg.end(), [&](const Vec2& q) { return (q + got.origin - p - want.origin).norm() <= tol; });
      EXPECT_TRUE(found) << want.blocks[i].id << ": vertex " << (p + want.origin).transpose();
    }
  }
}

TEST(NtddaModel, CaseThroughNtddaFilesAndBackKeepsItsBlocks) {
  expectCaseRoundTrip(kData + "wall3_mixed.json");
  expectCaseRoundTrip(std::string(DDASLOPE_SOURCE_DIR) + "/cases/stepped_toppling_tjunctions.json");
  expectCaseRoundTrip(std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_multiblock_slide.json");
}

// The same on the command line: a case to ntdda's two files, and back to a case `check` accepts.
TEST(NtddaModel, CaseToNtddaFilesOnTheCommandLine) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("ddaslope_ntdda_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::string err;
  ASSERT_EQ(runCli("convert " + kData + "wall3_mixed.json -o " + (dir / "wall.geo").string(), &err), 0) << err;
  EXPECT_TRUE(std::filesystem::exists(dir / "wall.ana"));  // the default analysis name
  EXPECT_NE(err.find("initial_equilibrium"), std::string::npos) << err;
  ASSERT_EQ(runCli("convert " + (dir / "wall.geo").string() + " --analysis " + (dir / "wall.ana").string() + " -o " +
                       (dir / "wall.json").string(),
                   &err),
            0)
      << err;
  EXPECT_EQ(runCli("check " + (dir / "wall.json").string(), &err), 0) << err;
  expectSameModel(ddaslope::io::readCase(kData + "wall3_mixed.json"), ddaslope::io::readCase((dir / "wall.json").string()));
  std::filesystem::remove_all(dir);
}

TEST(NtddaModel, SupportsAndLoadsGoThroughNtddaFiles) {
  const Scene want = ddaslope::io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/cases/goodman_bray_toppling_anchor.json");
  const auto files = ddaslope::io::writeNtddaModel(want, "anchor");
  const Scene got = convertToScene(writeTemp("anchor.geo", files.geometry), writeTemp("anchor.ana", files.analysis));
  ASSERT_EQ(got.supports.size(), want.supports.size());
  for (size_t s = 0; s < want.supports.size(); ++s) {
    EXPECT_EQ(got.supports[s].head.initial + got.origin, want.supports[s].head.initial + want.origin);
    EXPECT_EQ(got.supports[s].end.initial + got.origin, want.supports[s].end.initial + want.origin);
    EXPECT_EQ(got.supports[s].pretension, want.supports[s].pretension);
  }
}

// Our own model (tests/data/ntdda/benches.*: ntdda's own examples carry no licence, so none is
// copied), in DDAML: lines overshooting their corners, T-junctions, a line into the air, two
// fixed points, a load point, a measured point and a material line.
TEST(NtddaModel, OwnDdamlModelConvertsAndChecks) {
  std::vector<std::string> notes;
  const Scene s = convertToScene(kData + "benches.geo", kData + "benches.ana", &notes);
  ASSERT_EQ(s.blocks.size(), 4u);  // base, block A, block B's two triangles
  const int base = blockAt(s, {10, 1}, 1e-9), a = blockAt(s, {4, 3}, 1e-9);
  const int lower = blockAt(s, {32.0 / 3, 7.0 / 3}, 1e-9), upper = blockAt(s, {28.0 / 3, 8.0 / 3}, 1e-9);
  ASSERT_GE(base, 0);
  ASSERT_GE(a, 0);
  ASSERT_GE(lower, 0);
  ASSERT_GE(upper, 0);
  EXPECT_TRUE(s.blocks[base].fixed);  // two fixed points hold it
  EXPECT_FALSE(s.blocks[a].fixed);
  EXPECT_EQ(s.materials[s.blocks[a].material].density, 2200);  // the material line's
  EXPECT_EQ(s.materials[s.blocks[lower].material].density, 2600);
  EXPECT_NEAR(s.blocks[lower].moments.area, 2, 1e-12);
  EXPECT_NEAR(s.joints[s.jointBetween(lower, upper)].frictionAngle, 25 * std::numbers::pi / 180, 1e-14);
  EXPECT_EQ(s.joints[s.jointBetween(lower, upper)].cohesion, 2000);
  EXPECT_NEAR(s.joints[s.jointBetween(base, a)].frictionAngle, 35 * std::numbers::pi / 180, 1e-14);
  ASSERT_EQ(s.pointLoads.size(), 1u);
  EXPECT_EQ(s.pointLoads[0].point.block, lower);
  EXPECT_EQ(s.pointLoads[0].force, Vec2(-1000, 0));
  EXPECT_EQ(s.pointLoads[0].rate, Vec2(0, 0));
  ASSERT_EQ(s.monitors.size(), 1u);
  EXPECT_EQ(s.monitors[0].point.block, a);
  EXPECT_NEAR(s.normalPenalty(), 20 * 1e10, 1);
  EXPECT_DOUBLE_EQ(s.settings.duration, 1.0);
  // The line into the air is dropped and said so; so is ntdda's sudden gravity.
  const auto said = [&](const std::string& what) {
    return std::any_of(notes.begin(), notes.end(), [&](const std::string& n) { return n.find(what) != std::string::npos; });
  };
  EXPECT_TRUE(said("bound no block")) << ::testing::PrintToString(notes);
  EXPECT_TRUE(said("Gravity flag"));
  EXPECT_TRUE(said("<Saveinterval>: not mapped"));

  // The command line: converted, and `check` accepts the case.
  const std::string out = (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_benches.json")).string();
  clitest::tempFiles().paths.push_back(out);
  std::string err;
  EXPECT_EQ(runCli("convert " + kData + "benches.geo --analysis " + kData + "benches.ana -o " + out, &err), 0) << err;
  EXPECT_NE(err.find("note: "), std::string::npos);
  EXPECT_EQ(runCli("check " + out, &err), 0) << err;
}

// The same model in Shi's original text form gives the same blocks (no load history there).
TEST(NtddaModel, OwnTextModelGivesTheSameBlocks) {
  const Scene xml = convertToScene(kData + "benches.geo", kData + "benches.ana");
  const auto g = ddaslope::io::readNtddaGeometry(kData + "benches_text.geo");
  EXPECT_FALSE(g.xml);
  const Scene text = convertToScene(kData + "benches_text.geo", kData + "benches_text.ana");
  ASSERT_EQ(text.blocks.size(), xml.blocks.size());
  for (size_t b = 0; b < xml.blocks.size(); ++b) {
    EXPECT_EQ(text.blocks[b].vertices, xml.blocks[b].vertices);
    EXPECT_EQ(text.blocks[b].fixed, xml.blocks[b].fixed);
    EXPECT_EQ(text.blocks[b].material, xml.blocks[b].material);
  }
  EXPECT_EQ(text.monitors.size(), 1u);
  EXPECT_NEAR(text.gravity.y(), -25506.0 / 2600, 1e-12);  // the text form's gravity: unit weight / mass
  EXPECT_NEAR(text.normalPenalty(), 50 * 1e10, 1);         // and its automatic penalty, 50 E
}

// --- Bad input: exit 2, naming the file, the line and element, expected and found ---

struct BadModel {
  std::string geo, ana, what;
};

TEST(NtddaModel, BadInputExitsTwoWithWhereAndWhat) {
  const std::string ana = kData + "benches.ana";
  const std::string square = "<Joint type=\"1\"> 0 0 1 0 </Joint><Joint type=\"1\"> 1 0 1 1 </Joint>"
                             "<Joint type=\"1\"> 1 1 0 1 </Joint><Joint type=\"1\"> 0 1 0 0 </Joint>";
  const auto ddaml = [](const std::string& body) {
    return "<?xml version=\"1.0\"?>\n<Berkeley:DDA xmlns:Berkeley=\"x\">\n<Berkeley:Geometry>\n" + body + "\n</Berkeley:Geometry>\n</Berkeley:DDA>\n";
  };
  const std::vector<BadModel> cases{
      {"/nonexistent/model.geo", "", "does not exist"},
      {writeTemp("unclosed.geo", ddaml("<Jointlist>" + square)), "", "line 5: malformed XML: expected </Jointlist>"},
      {writeTemp("nan.geo", ddaml("<Jointlist>\n<Joint type=\"1\"> 0 0 nan 1 </Joint>\n</Jointlist>")), "",
       "line 5: <Joint>: expected x1 y1 x2 y2 (4 finite numbers), found \"0 0 nan 1\""},
      {writeTemp("three.geo", ddaml("<Jointlist><Joint type=\"1\"> 0 0 1 </Joint></Jointlist>")), "", "found \"0 0 1\""},
      {writeTemp("notype.geo", ddaml("<Jointlist><Joint> 0 0 1 1 </Joint></Jointlist>")), "", "expected the attribute type"},
      {writeTemp("star.geo", ddaml("<Jointlist><Joint type=\"1\"> -1 0 1 0 </Joint><Joint type=\"1\"> -0.5 -1 0.5 1 </Joint>"
                                   "<Joint type=\"1\"> 0.5 -1 -0.5 1 </Joint></Jointlist>")),
       "", "expected joint lines that close at least one block, found 3 lines closing none"},
      {writeTemp("type9.geo", ddaml("<Jointlist>" + square + "<Joint type=\"9\"> 0 0 1 1 </Joint></Jointlist>")), ana,
       "expected a joint type from 1 to 2"},
      {writeTemp("root.geo", "<?xml version=\"1.0\"?>\n<Model></Model>\n"), "", "expected the root element <Berkeley:DDA>"},
      {writeTemp("text.geo", "0.01\n2 0\n0\n0\n0\n0\n0\n0\n0 0 1 0 1\n0 0 x 1 1\n"), "", "line 10: expected joint line x1 y1 x2 y2 type (a finite number), found \"x\""},
      {writeTemp("short.geo", "0.01\n4 0\n0\n0\n0\n0\n0\n0\n0 0 1 0 1\n"), "", "found the end of the file"},
      {writeTemp("ok.geo", ddaml("<Jointlist>" + square + "</Jointlist>")),
       writeTemp("bad.ana", "<?xml version=\"1.0\"?>\n<Berkeley:DDA><Analysis>\n<Numtimesteps timesteps=\"ten\"/>\n</Analysis></Berkeley:DDA>\n"),
       "line 3: <Numtimesteps>: expected timesteps to be a finite number, found \"ten\""},
  };
  for (const auto& c : cases) {
    std::string err;
    const std::string args = "convert " + c.geo + (c.ana.empty() ? "" : " --analysis " + c.ana) + " -o /tmp/ddaslope_never_" +
                             std::to_string(::getpid()) + ".json";
    EXPECT_EQ(runCli(args, &err), 2) << c.geo << ": " << err;
    EXPECT_NE(err.find(c.what), std::string::npos) << c.geo << ": " << err;
    EXPECT_TRUE(err.find(c.geo) != std::string::npos || (!c.ana.empty() && err.find(c.ana) != std::string::npos)) << err;
  }
  std::string err;
  EXPECT_EQ(runCli("convert " + kData + "benches.geo -o /tmp/ddaslope_never.geo", &err), 2);
  EXPECT_NE(err.find("expected the case to write to be named .json"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists("/tmp/ddaslope_never_" + std::to_string(::getpid()) + ".json"));
}

// Mutated models (issue #44's fuzzing, on this input surface): refused as bad input naming the
// geometry or the analysis, or converted into a case that is read (or refused by the case
// reader); never another exception, and never a number that is not finite.
TEST(NtddaModel, MutatedModelsAreRefusedOrConverted) {
  struct Seed {
    std::string geo, ana;
  };
  const std::vector<Seed> seeds{{"benches.geo", "benches.ana"}, {"benches_text.geo", "benches_text.ana"}, {"wall3_mixed.geo", "wall3_mixed.ana"}};
  const auto slurp = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  std::mt19937 rng(clitest::fuzzSeed(43));
  const int kModels = clitest::fuzzCount(400);
  int refused = 0, converted = 0, read = 0;
  for (int n = 0; n < kModels; ++n) {
    const Seed& s = seeds[static_cast<size_t>(n) % seeds.size()];
    std::string geoText = slurp(kData + s.geo), anaText = slurp(kData + s.ana);
    std::string& target = n % 2 == 0 ? geoText : anaText;
    const int changes = static_cast<int>(fuzz::uniform(rng, 1, 2));
    for (int k = 0; k < changes; ++k) target = fuzz::mutateText(target, rng);
    const std::string geo = writeTemp("fuzz_" + s.geo, geoText), ana = writeTemp("fuzz_" + s.ana, anaText);
    SCOPED_TRACE("mutation " + std::to_string(n) + " of " + (n % 2 == 0 ? s.geo : s.ana));
    ddaslope::io::ConvertedModel m;
    try {
      const auto g = ddaslope::io::readNtddaGeometry(geo);
      const auto a = ddaslope::io::readNtddaAnalysis(ana);
      m = ddaslope::io::convertNtddaModel(g, &a);
      ++converted;
    } catch (const ddaslope::InputError& e) {
      ++refused;
      EXPECT_TRUE(e.file() == geo || e.file() == ana) << e.what();
      continue;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an InputError: " << e.what();
      continue;
    }
    EXPECT_EQ(m.caseJson.find("null"), std::string::npos) << m.caseJson;
    try {
      const Scene scene = ddaslope::io::parseCase(m.caseJson, "converted.json");
      ++read;
      for (const auto& b : scene.blocks)
        for (const Vec2& p : b.vertices) ASSERT_TRUE(std::isfinite(p.x()) && std::isfinite(p.y())) << b.id;
    } catch (const ddaslope::InputError& e) {
      EXPECT_EQ(e.file(), "converted.json");
    } catch (const std::exception& e) {
      ADD_FAILURE() << "reading the converted case: not an InputError: " << e.what();
    }
  }
  EXPECT_GT(refused, kModels / 10);
  EXPECT_GT(read, kModels / 10);
  std::printf("fuzz ntdda models: %d refused, %d converted (%d read as cases)\n", refused, converted, read);
}

}  // namespace
