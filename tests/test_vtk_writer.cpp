// The VTK XML writer (io/vtk_writer.hpp) byte by byte, and the scene's grids (io/scene_vtk.hpp).
// VTK's own reader reads the files back in scripts/test_vtk_output.py.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/scene_vtk.hpp"
#include "ddaslope/io/vtk_writer.hpp"
#include "ddaslope/model/incline_scene.hpp"

namespace ddaslope::io {
namespace {

/// A unit square and a line beside it: one Int32 and one Float64 3-vector cell array, a string
/// and a number as field data.
VtkGrid tinyGrid() {
  VtkGrid g;
  g.addCell(VtkCellType::Polygon, {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  g.addCell(VtkCellType::Line, {{2, 0}, {3, 0.5}});
  g.cellData = {{"id", 1, {}, std::vector<std::int32_t>{7, -1}},
                {"displacement", 3, {"x", "y", "z"}, std::vector<double>{0.25, -0.5, 0, 1e-300, 2, 0}}};
  g.fieldData = {{"names", 1, {}, std::vector<std::string>{"rock", "clay"}},
                 {"TimeValue", 1, {}, std::vector<double>{0.5}}};
  return g;
}

/// The offset attribute of the element named `name`.
size_t offsetOf(const std::string& xml, const std::string& name) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(xml, m, std::regex("Name=\"" + name + "\"[^>]*offset=\"([0-9]+)\""))) << name;
  return std::stoul(m[1]);
}

/// The appended array at `offset`: its UInt64 byte count, then its bytes.
std::string appendedArray(const std::string& file, size_t offset) {
  const size_t start = file.find("<AppendedData encoding=\"raw\">\n   _") + std::strlen("<AppendedData encoding=\"raw\">\n   _");
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, file.data() + start + offset, sizeof bytes);
  return file.substr(start + offset + sizeof bytes, bytes);
}

template <class T>
std::vector<T> valuesIn(const std::string& bytes) {
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), bytes.size());
  return v;
}

TEST(VtkWriter, CellsEndOffsetsAndTypes) {
  const VtkGrid g = tinyGrid();
  EXPECT_EQ(g.points.size(), 6u);
  EXPECT_EQ(g.connectivity, (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(g.offsets, (std::vector<std::int64_t>{4, 6}));  // VTK: the end of each cell
  EXPECT_EQ(g.types, (std::vector<std::uint8_t>{7, 3}));    // VTK_POLYGON, VTK_LINE
}

TEST(VtkWriter, HeaderSaysByteOrderAndHeaderType) {
  const std::string xml = vtuBytes(tinyGrid());
  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"", 0), 0u);
  EXPECT_NE(xml.find(std::endian::native == std::endian::little ? "byte_order=\"LittleEndian\"" : "byte_order=\"BigEndian\""),
            std::string::npos);
  EXPECT_NE(xml.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_NE(xml.find("<Piece NumberOfPoints=\"6\" NumberOfCells=\"2\">"), std::string::npos);
  EXPECT_NE(xml.find("<Array type=\"String\" Name=\"names\" NumberOfTuples=\"2\""), std::string::npos);
  EXPECT_NE(xml.find("Name=\"displacement\" NumberOfComponents=\"3\" ComponentName0=\"x\""), std::string::npos);
  EXPECT_TRUE(xml.ends_with("\x07\x03\n  </AppendedData>\n</VTKFile>\n"));  // the cell types end the data
}

TEST(VtkWriter, AppendedOffsetsFollowEachArraysHeaderAndBytes) {
  const std::string file = vtuBytes(tinyGrid());
  // In the order written: field data, cell data, points, cells. Each array takes 8 bytes of
  // UInt64 count plus its bytes: "rock\0clay\0" 10, one Float64 8, two Int32 8, six Float64 48,
  // six points × 3 Float64 144, six Int64 48, two Int64 16.
  EXPECT_EQ(offsetOf(file, "names"), 0u);
  EXPECT_EQ(offsetOf(file, "TimeValue"), 18u);
  EXPECT_EQ(offsetOf(file, "id"), 34u);
  EXPECT_EQ(offsetOf(file, "displacement"), 50u);
  EXPECT_EQ(offsetOf(file, "Points"), 106u);
  EXPECT_EQ(offsetOf(file, "connectivity"), 258u);
  EXPECT_EQ(offsetOf(file, "offsets"), 314u);
  EXPECT_EQ(offsetOf(file, "types"), 338u);
  EXPECT_EQ(appendedArray(file, 0), std::string("rock\0clay\0", 10));
  EXPECT_EQ(valuesIn<double>(appendedArray(file, 18)), std::vector<double>{0.5});
  EXPECT_EQ(valuesIn<std::int32_t>(appendedArray(file, 34)), (std::vector<std::int32_t>{7, -1}));
  EXPECT_EQ(valuesIn<double>(appendedArray(file, 50)), (std::vector<double>{0.25, -0.5, 0, 1e-300, 2, 0}));
  const std::vector<double> xyz = valuesIn<double>(appendedArray(file, 106));
  ASSERT_EQ(xyz.size(), 18u);
  EXPECT_EQ(xyz[15], 3.0);  // the line's end (3, 0.5, 0)
  EXPECT_EQ(xyz[16], 0.5);
  EXPECT_EQ(xyz[17], 0.0);
  EXPECT_EQ(valuesIn<std::int64_t>(appendedArray(file, 314)), (std::vector<std::int64_t>{4, 6}));
  EXPECT_EQ(appendedArray(file, 338), std::string("\x07\x03", 2));
}

TEST(VtkWriter, EmptyGridIsValid) {
  const std::string file = vtuBytes(VtkGrid{});
  EXPECT_NE(file.find("<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\">"), std::string::npos);
  EXPECT_EQ(appendedArray(file, offsetOf(file, "types")), "");
}

TEST(VtkWriter, RefusesNonFiniteNumbersAndShortCellArrays) {
  VtkGrid g = tinyGrid();
  std::get<std::vector<double>>(g.cellData[1].values)[4] = NAN;
  EXPECT_THROW(vtuBytes(g), InternalError);
  g = tinyGrid();
  std::get<std::vector<std::int32_t>>(g.cellData[0].values).pop_back();
  EXPECT_THROW(vtuBytes(g), InternalError);
}

TEST(VtkWriter, PvdListsByTimestepAndEscapes) {
  const std::string text = pvdText({{0.5, "b_1.vtu"}, {0, "a&<\".vtu"}, {1e-3, "c.vtu"}});
  EXPECT_EQ(text,
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n"
            "    <DataSet timestep=\"0\" part=\"0\" file=\"a&amp;&lt;&quot;.vtu\"/>\n"
            "    <DataSet timestep=\"0.001\" part=\"0\" file=\"c.vtu\"/>\n"
            "    <DataSet timestep=\"0.5\" part=\"0\" file=\"b_1.vtu\"/>\n"
            "  </Collection>\n</VTKFile>\n");
}

TEST(VtkWriter, CollectionIsRewrittenAfterEachEntryAndKeepsOneEntryPerFile) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "ddaslope_pvd_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "s.pvd").string();
  const auto read = [&] {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  PvdCollection c(path);
  c.add(1.5, "x.vtu");
  EXPECT_EQ(read(), pvdText({{1.5, "x.vtu"}}));
  c.add(0.25, "y.vtu");
  c.add(0.75, "x.vtu");  // the same file again: its entry moves, it is not listed twice
  EXPECT_EQ(read(), pvdText({{0.25, "y.vtu"}, {0.75, "x.vtu"}}));
  c.add(0.5, "w.vtu");  // between two: the file is rewritten in order
  c.add(2, "z.vtu");    // after the last: written over the closing tags
  EXPECT_EQ(read(), pvdText({{0.25, "y.vtu"}, {0.5, "w.vtu"}, {0.75, "x.vtu"}, {2, "z.vtu"}}));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  std::filesystem::remove_all(dir);
}

TEST(SceneVtk, BlocksAndContactsOfAnIncline) {
  model::InclineSpec spec;  // 2 × 1 m block on a 30° ramp, resting on it
  const model::Scene scene = model::makeInclineScene(spec);
  const solver::Simulation sim(scene);
  std::vector<Vec2> centroids;
  for (const model::Block& b : scene.blocks) centroids.push_back(b.moments.centroid);
  const VtkGrid blocks = blocksGrid(sim, centroids);
  ASSERT_EQ(blocks.cells(), scene.blocks.size());
  for (size_t b = 0; b < scene.blocks.size(); ++b) {
    EXPECT_EQ(blocks.types[b], static_cast<std::uint8_t>(VtkCellType::Polygon));
    EXPECT_EQ(std::get<std::vector<std::int32_t>>(blocks.cellData[0].values)[b], static_cast<int>(b));  // block_id
  }
  // Nothing has moved yet: every displacement is exactly zero.
  const auto& u = std::get<std::vector<double>>(blocks.cellData[3].values);
  EXPECT_EQ(blocks.cellData[3].name, "displacement");
  for (double x : u) EXPECT_EQ(x, 0.0);

  const VtkGrid contacts = contactsGrid(sim);
  ASSERT_EQ(contacts.cells(), sim.contacts().contacts().size());
  ASSERT_GT(contacts.cells(), 0u);
  for (size_t k = 0; k < contacts.cells(); ++k) {
    const contact::Contact& c = sim.contacts().contacts()[k];
    const model::Block& vb = scene.blocks[c.key().vertexBlock];
    const model::Block& eb = scene.blocks[c.key().edgeBlock];
    // A line from the contact vertex, 0.15 √(smaller area) long, along the edge's outward normal.
    const Vec2 from = contacts.points[2 * k], to = contacts.points[2 * k + 1];
    EXPECT_EQ(from, vb.vertices[c.key().vertex]);
    EXPECT_NEAR((to - from).norm(), 0.15 * std::sqrt(std::min(vb.moments.area, eb.moments.area)), 1e-12);
    const Vec2 edge = eb.vertices[(c.key().edge + 1) % eb.vertices.size()] - eb.vertices[c.key().edge];
    EXPECT_NEAR(edge.dot(to - from), 0, 1e-12);
    EXPECT_LT(cross(edge, to - from), 0);  // right of a counter-clockwise edge: outward
    EXPECT_EQ(std::get<std::vector<std::int32_t>>(contacts.cellData[0].values)[k], static_cast<int>(c.state));
  }
  EXPECT_EQ(waterGrid(sim).cells(), 0u);  // a dry scene
}

}  // namespace
}  // namespace ddaslope::io
