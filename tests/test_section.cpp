// Blocks cut from a slope section: areas are conserved (the cut pieces tile the slide mass)
// and the pieces are where the joints put them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/geometry/cutting.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/model/kinks.hpp"
#include "test_io.hpp"
#include "ddaslope/model/section.hpp"

using namespace ddaslope;

namespace {
/// A 100 m wide section: level ground at y = 20, a sliding surface from (10, 20) down to a flat
/// seat at y = 5 and up to (90, 20): slide mass area = 80·15 − 2·(½·10·15) = 1050 m². Kink blocks
/// only where a test gives their width (the automatic ones are tested with the chair).
model::SectionSpec basin() {
  model::SectionSpec s;
  s.ground = {{0, 20}, {100, 20}};
  s.slidingSurface = {{10, 20}, {20, 5}, {80, 5}, {90, 20}};
  s.baseDepth = 10;
  s.kinkBlockAuto = false;
  return s;
}
}  // namespace

TEST(Section, SlideMassAndBaseTileTheSection) {
  const model::SectionBlocks b = model::cutSection(basin());
  ASSERT_EQ(b.slide.size(), 1u);
  EXPECT_NEAR(b.slide[0].moments.area, 1050, 1e-9);
  // Base: 100 × (20 − (5 − 10)) minus the mass.
  EXPECT_NEAR(b.base.moments.area, 100 * 25 - 1050, 1e-9);
  EXPECT_TRUE(b.base.fixed);
}

TEST(Section, JointsCutTheMassConservingArea) {
  model::SectionSpec s = basin();
  s.joints.push_back({{50, 5}, {50, 20}});  // one explicit vertical joint, extended as a line
  s.jointSets.push_back({90, 10, {0, 0}});  // vertical lines every 10 m (x = 10, 20, …, 90)
  const model::SectionBlocks b = model::cutSection(s);
  // The seven lines x = 20 … 80 cut the mass (x = 50 twice: the explicit joint and the set cut
  // nothing new the second time); x = 10 and 90 touch its corners only: 8 pieces.
  ASSERT_EQ(b.slide.size(), 8u);
  double total = 0;
  for (const auto& blk : b.slide) total += blk.moments.area;
  EXPECT_NEAR(total, 1050, 1e-8);
  EXPECT_NEAR(b.slide[3].moments.area, 150, 1e-9);  // a full 10 × 15 column in the middle
  EXPECT_LT(b.slide.front().moments.centroid.x(), b.slide.back().moments.centroid.x());
}

// A vertical step in the ground where the sliding surface meets it (a toe 1 m above a bench, as
// cases/toppling_slope.json) stays in the base: areas by the shoelace formula. Ground (0, 20),
// (10, 20), (20, 10), (20, 9), (30, 9); sliding surface from (0, 20) to the toe (20, 10).
// Mass: the triangle (0, 20), (10, 20), (20, 10): ½·10·10 = 50 m². Base to y = −1: the section
// below the ground, 10·21 + 10·(21 + 11)/2 + 10·10 = 470 m², minus the mass.
TEST(Section, VerticalStepAtTheToeStaysInTheBase) {
  model::SectionSpec s;
  s.ground = {{0, 20}, {10, 20}, {20, 10}, {20, 9}, {30, 9}};
  s.slidingSurface = {{0, 20}, {20, 10}};
  s.baseDepth = 10;
  const model::SectionBlocks b = model::cutSection(s);
  ASSERT_EQ(b.slide.size(), 1u);
  EXPECT_NEAR(b.slide[0].moments.area, 50, 1e-9);
  EXPECT_NEAR(b.base.moments.area, 470 - 50, 1e-9);
  bool stepCorner = false;
  for (const Vec2& v : b.base.vertices) stepCorner |= (v - Vec2(20, 9)).norm() < 1e-12;
  EXPECT_TRUE(stepCorner) << "the bench corner (20, 9) must be a vertex of the base";
}

TEST(Section, BadSectionsAreReported) {
  model::SectionSpec s = basin();
  s.slidingSurface[1] = {20, 25};  // above the ground
  try {
    model::cutSection(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.jsonPath(), "sliding_surface[1]");
  }
  s = basin();
  s.baseDepth = 0;
  EXPECT_THROW(model::cutSection(s), InputError);
  // Crown and toe on the ground: within 1e-3 of the section's size (0.1 m here) a digitising
  // error is absorbed; the toe 12 m in the air or the crown 2 m down is refused, not a face or
  // crest redrawn through it.
  for (const auto& [end, at] : {std::pair{size_t{3}, Vec2(90, 32)}, std::pair{size_t{0}, Vec2(10, 18)}}) {
    s = basin();
    s.slidingSurface[end] = at;
    try {
      model::cutSection(s);
      ADD_FAILURE() << "accepted an end off the ground at " << at.transpose();
    } catch (const InputError& e) {
      EXPECT_EQ(e.jsonPath(), "sliding_surface[" + std::to_string(end) + "]");
      EXPECT_NE(std::string(e.what()).find(end == 0 ? "first point, an end of the slide, on the ground"
                                                    : "last point, an end of the slide, on the ground"),
                std::string::npos)
          << e.what();
    }
  }
  s = basin();
  s.slidingSurface[3] = {90, 20.05};
  EXPECT_NO_THROW(model::cutSection(s));
}

TEST(Cutting, HalfPlaneClipOfASquare) {
  const std::vector<Vec2> sq{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const auto left = geometry::clipToLeft(sq, {1, 0}, {0, 1});  // keep x ≤ 1
  EXPECT_NEAR(std::abs(geometry::signedArea(left)), 2.0, 1e-14);
  EXPECT_EQ(geometry::lineCrossings(sq, {1, 0}, {0, 1}), 2);
  EXPECT_EQ(geometry::lineCrossings(sq, {5, 0}, {0, 1}), 0);
  // A U-shaped polygon crossed by a horizontal line through both arms: 4 crossings.
  const std::vector<Vec2> u{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  EXPECT_EQ(geometry::lineCrossings(u, {0, 2}, {1, 0}), 4);
}

// Kink blocks: the basin's sliding surface flattens at (20, 5) and turns up into the toe at
// (80, 5), both concave, so a 2 m kink block is cut at x = 18 and x = 78. Areas by integration of
// ground minus sliding surface: x ∈ [10, 18]: ∫ 1.5 t dt over [0, 8] = 48 m²; x ∈ [78, 90]:
// 2 · 15 + ∫ (15 − 1.5 t) dt over [0, 10] = 105 m²; the middle the rest of 1050: 897 m².
TEST(Section, KinkBlocksAreCutUpTheSlopeOfConcaveKinks) {
  model::SectionSpec s = basin();
  s.kinkBlockWidth = 2;
  const model::SectionBlocks b = model::cutSection(s);
  ASSERT_EQ(b.slide.size(), 3u);
  EXPECT_NEAR(b.slide[0].moments.area, 48, 1e-9);
  EXPECT_NEAR(b.slide[1].moments.area, 897, 1e-9);
  EXPECT_NEAR(b.slide[2].moments.area, 105, 1e-9);
  s.kinkBlockWidth = -1;
  EXPECT_THROW(model::cutSection(s), InputError);
}

// The same slope facing −x (its sliding surface, x increasing, rising from the toe to the crown)
// is cut into the mirror images of the blocks the +x slope gets: the shipped sections with kink
// blocks, internal joints, joint sets and the automatic kink block (chair, Vajont, bilinear slab,
// toppling slope), each block matched by its mirrored centroid and area.
TEST(Section, ASlopeFacingMinusXIsCutAsTheMirrorImage) {
  const auto flip = [](const std::vector<Vec2>& line) {
    std::vector<Vec2> out;
    for (auto it = line.rbegin(); it != line.rend(); ++it) out.emplace_back(-it->x(), it->y());
    return out;
  };
  for (const char* name : {"chair_slide", "vajont", "bilinear_slab", "toppling_slope"}) {
    SCOPED_TRACE(name);
    std::ifstream in(std::string(DDASLOPE_SOURCE_DIR) + "/cases/" + name + ".json");
    const nlohmann::json doc = nlohmann::json::parse(in);
    const nlohmann::json& j = doc.at("section");
    const auto line = [](const nlohmann::json& a) {
      std::vector<Vec2> v;
      for (const auto& p : a) v.emplace_back(p[0].get<double>(), p[1].get<double>());
      return v;
    };
    model::SectionSpec spec;
    spec.ground = line(j.at("ground"));
    spec.slidingSurface = line(j.at("sliding_surface"));
    spec.baseDepth = j.at("base_depth").get<double>();
    if (j.contains("kink_block_width")) spec.kinkBlockWidth = j.at("kink_block_width").get<double>(), spec.kinkBlockAuto = false;
    for (const auto& jt : j.value("joints", nlohmann::json::array()))
      spec.joints.emplace_back(line(jt)[0], line(jt)[1]);
    for (const auto& js : j.value("joint_sets", nlohmann::json::array()))
      spec.jointSets.push_back({js.at("angle").get<double>(), js.at("spacing").get<double>(), line(nlohmann::json::array({js.at("origin")}))[0]});
    model::SectionSpec mirrored = spec;
    mirrored.ground = flip(spec.ground);
    mirrored.slidingSurface = flip(spec.slidingSurface);
    for (auto& [a, b] : mirrored.joints) a.x() = -a.x(), b.x() = -b.x();
    for (model::JointSet& js : mirrored.jointSets) js.angleDeg = 180 - js.angleDeg, js.origin.x() = -js.origin.x();
    ASSERT_FALSE(model::facesMinusX(spec));
    ASSERT_TRUE(model::facesMinusX(mirrored));
    const model::SectionBlocks a = model::cutSection(spec), b = model::cutSection(mirrored);
    ASSERT_EQ(a.slide.size(), b.slide.size());
    const double size = spec.ground.back().x() - spec.ground.front().x();
    EXPECT_NEAR(a.base.moments.area, b.base.moments.area, 1e-9 * size * size);
    // Left to right in both: the k-th block from the crown is the k-th from the right.
    for (size_t k = 0; k < a.slide.size(); ++k) {
      const model::Block& p = a.slide[k];
      const model::Block& q = b.slide[b.slide.size() - 1 - k];
      EXPECT_NEAR(p.moments.area, q.moments.area, 1e-9 * size * size) << k;
      EXPECT_NEAR(p.moments.centroid.x(), -q.moments.centroid.x(), 1e-9 * size) << k;
      EXPECT_NEAR(p.moments.centroid.y(), q.moments.centroid.y(), 1e-9 * size) << k;
      EXPECT_EQ(p.vertices.size(), q.vertices.size()) << k;
    }
  }
}

// A joint within half the width of a kink cut (x = 17.5 m, 0.5 m from the cut at 18 m) already
// makes the kink block: no second cut beside it, so no 0.5 m sliver. Areas: x ∈ [10, 17.5]:
// ∫ 1.5 t dt over [0, 7.5] = 42.1875 m²; the toe side's cut at 78 m stays: 105 m²; the rest of 1050.
TEST(Section, KinkCutBesideAJointIsSkipped) {
  model::SectionSpec s = basin();
  s.kinkBlockWidth = 2;
  s.joints = {{{17.5, 0}, {17.5, 30}}};
  const model::SectionBlocks b = model::cutSection(s);
  ASSERT_EQ(b.slide.size(), 3u);
  EXPECT_NEAR(b.slide[0].moments.area, 42.1875, 1e-9);
  EXPECT_NEAR(b.slide[1].moments.area, 1050 - 42.1875 - 105, 1e-9);
  EXPECT_NEAR(b.slide[2].moments.area, 105, 1e-9);
}

// Concave kinks under the blocks (model/kinks.hpp): the chair slide's sliding surface turns from
// 30° to 8° at the kink and from 8° to the level valley floor at the toe, so by geometry it bends
// up by 22° at (500, 49.19) and by 8° at (850, 0); a block on a plane (the B1 ramp) has none, and
// the 90° steps of the stepped toppling base are steps, not kinks.
TEST(Kinks, ConcaveBendsOfTheSlidingSurfaceUnderTheBlocks) {
  const std::string dir = std::string(DDASLOPE_SOURCE_DIR) + "/cases/";
  const auto chair = model::concaveKinksUnderBlocks(io::readCase(dir + "chair_slide.json"));
  ASSERT_EQ(chair.size(), 2u);
  const auto& kink = chair[0].point.x() < chair[1].point.x() ? chair[0] : chair[1];
  const auto& toe = chair[0].point.x() < chair[1].point.x() ? chair[1] : chair[0];
  EXPECT_NEAR(kink.bendDeg, 22, 1e-9);
  EXPECT_NEAR(kink.point.x(), 500, 1e-9);
  EXPECT_NEAR(kink.point.y(), 350 * std::tan(degToRad(8)), 1e-9);
  EXPECT_NEAR(toe.bendDeg, 8, 1e-9);
  EXPECT_NEAR(toe.point.x(), 850, 1e-9);
  // The case's kink block (section.kink_block_width 3 m) has its corner on the kink; at the toe
  // the 50 m block's corner sits on the valley floor's kink.
  EXPECT_NEAR(kink.upslopeReach, 3, 1e-9);
  EXPECT_NEAR(toe.upslopeReach, 50, 1e-9);
  EXPECT_TRUE(model::concaveKinksUnderBlocks(io::readCase(dir + "cohesive_block_42kpa.json")).empty());
  EXPECT_TRUE(model::concaveKinksUnderBlocks(io::readCase(dir + "stepped_toppling.json")).empty());
  // A block spanning the bend has a corner there alone; on the kink block's bend two blocks meet
  // (the kink block and the one above), and on the toe's one.
  EXPECT_EQ(kink.blocksWithCorner, 2);
  EXPECT_EQ(toe.blocksWithCorner, 1);
}

// RS2 joint verification problem 9 (docs/research/bilinear-slab.md): the cross joint ends exactly
// where the bedding bends 20° into the toe-breakout joint, so the slab and the toe wedge both have
// a corner on that bend: a joint's end, not a block spanning it. The slab reaches 36.8 m up the
// slope from it: not a thin kink block, so `check` and the searches say the answer may follow the
// contact stiffness, and do not advise a kink block.
// Here the slab as drawn (analysis.joint_end_offset 0: the joint is not moved off the bend).
TEST(Kinks, AJointEndingOnABendIsToldFromABlockSpanningIt) {
  const std::string slab = std::string(DDASLOPE_SOURCE_DIR) + "/cases/bilinear_slab.json";
  const std::string drawn = " --set analysis.joint_end_offset=0";
  const auto kinks = model::concaveKinksUnderBlocks(io::readCase(slab, {{"analysis.joint_end_offset", 0}}));
  ASSERT_EQ(kinks.size(), 1u);
  EXPECT_NEAR(kinks[0].bendDeg, 20, 1e-6);
  EXPECT_EQ(kinks[0].blocksWithCorner, 2);
  std::string ignored;
  const std::string check = clitest::captureCli("check " + slab + drawn, &ignored);
  EXPECT_NE(check.find("a joint ends on the bend"), std::string::npos) << check;
  EXPECT_EQ(check.find("section.kink_block_width)"), std::string::npos) << check;
  std::string warnings;
  clitest::captureCli("fos " + slab + drawn + " --quiet", &warnings);
  EXPECT_NE(warnings.find("may follow the contact stiffness"), std::string::npos) << warnings;
  EXPECT_EQ(warnings.find("was moved"), std::string::npos) << warnings;
  // Moved (as shipped), the answer is the moved outline's, and the searches say so: the automatic
  // move grows with the whole scene, the fixed base included (5e-3 w0 = 0.5 m here).
  clitest::captureCli("fos " + slab + " --quiet --width 0.05", &warnings);
  EXPECT_NE(warnings.find("was moved 0.5 m up the upper face"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("grows with the whole scene's size"), std::string::npos) << warnings;
}

// A joint ending on a concave bend of the base (the bilinear slab's cross joint), in a block
// model drawn by hand as a CAD user would: the reader moves it up the upper face by the automatic
// width (5e-3 w0 = 0.5 m here), parallel to itself, so that the block below owns the bend (a vertex
// on it and a short edge up the upper face) and the block above lies on the straight upper face
// alone. Mirrored, with vertices on straight edges, or as a section, the same; a vertical joint
// (a kink block's cut) and analysis.joint_end_offset 0 leave it where it was drawn.
namespace {
nlohmann::json slabOnABend(double jointEndX) {
  const double toeX = 10 / (1 - std::tan(degToRad(20)));  // 45° face y = 20 − x, 20° lower face from (0, 10)
  const nlohmann::json K = {0, 10}, J = {jointEndX, 20 - jointEndX}, T = {toeX, 20 - toeX};
  nlohmann::json doc;
  doc["materials"]["rock"] = {{"density", 2500}, {"young_modulus", 1e10}, {"poisson_ratio", 0.25}};
  doc["joints"]["j"] = {{"friction_angle", 30}, {"cohesion", 0}};
  doc["blocks"] = nlohmann::json::array(
      {{{"id", "base"}, {"material", "rock"}, {"fixed", true},
        {"vertices", {{-100, -30}, {100, -30}, {100, 0}, {20, 0}, T, K, {-25, 35}, {-50, 60}, {-100, 60}}}},
       {{"id", "slab"}, {"material", "rock"}, {"vertices", {K, J, {-40, 60}, {-50, 60}, {-25, 35}}}},
       {{"id", "wedge"}, {"material", "rock"}, {"vertices", {K, T, J}}}});
  doc["analysis"] = {{"duration", 0.1}};
  return doc;
}

bool hasVertex(const model::Block& b, const Vec2& p) {
  return std::any_of(b.vertices.begin(), b.vertices.end(), [&](const Vec2& v) { return (v - p).norm() < 1e-9; });
}
}  // namespace

TEST(Kinks, AJointEndingOnABendIsMovedUpTheUpperFace) {
  const std::string at = std::string(DDASLOPE_SOURCE_DIR) + "/cases/variant.json";
  const Vec2 kink(0, 10), up = Vec2(-1, 1).normalized();
  const auto expectMoved = [&](const model::Scene& s, double sign, const std::string& what) {
    const Vec2 k(sign * kink.x(), kink.y()), u(sign * up.x(), up.y());
    ASSERT_EQ(s.movedJointEnds.size(), 1u) << what;
    const model::MovedJointEnd& m = s.movedJointEnds[0];
    EXPECT_NEAR((m.kink - k).norm(), 0, 1e-9) << what;
    EXPECT_NEAR((m.shift - 0.5 * u).norm(), 0, 1e-9) << what;
    EXPECT_TRUE(m.parallel) << what;
    const model::Block& slab = s.blocks[static_cast<size_t>(s.blockIndex("slab"))];
    const model::Block& wedge = s.blocks[static_cast<size_t>(s.blockIndex("wedge"))];
    EXPECT_EQ(s.blocks[static_cast<size_t>(m.upper)].id, "slab") << what;
    EXPECT_FALSE(hasVertex(slab, k)) << what;
    EXPECT_TRUE(hasVertex(slab, k + 0.5 * u)) << what;
    EXPECT_TRUE(hasVertex(slab, Vec2(sign * 5, 15) + 0.5 * u)) << what << ": the joint's other end, along the face";
    EXPECT_TRUE(hasVertex(wedge, k)) << what;
    EXPECT_TRUE(hasVertex(wedge, k + 0.5 * u)) << what;
    EXPECT_EQ(wedge.vertices.size(), 4u) << what;
  };
  const nlohmann::json drawn = slabOnABend(5);
  const model::Scene scene = io::parseCase(drawn.dump(), at);
  expectMoved(scene, 1, "as drawn");
  nlohmann::json mirrored = drawn;
  for (auto& b : mirrored["blocks"]) {
    for (auto& p : b["vertices"]) p[0] = -p[0].get<double>();
    std::reverse(b["vertices"].begin(), b["vertices"].end());
  }
  expectMoved(io::parseCase(mirrored.dump(), at), -1, "mirrored");
  // The same areas before and after: the sliver the slab gives is the wedge's gain.
  nlohmann::json kept = drawn;
  kept["analysis"]["joint_end_offset"] = 0;
  const model::Scene asDrawn = io::parseCase(kept.dump(), at);
  EXPECT_TRUE(asDrawn.movedJointEnds.empty());
  EXPECT_NEAR(scene.blocks[1].moments.area + scene.blocks[2].moments.area,
              asDrawn.blocks[1].moments.area + asDrawn.blocks[2].moments.area, 1e-9);
  EXPECT_NEAR(asDrawn.blocks[2].moments.area + 0.5 * 5 * std::sqrt(2.0), scene.blocks[2].moments.area, 1e-9)
      << "the wedge gains the 0.5 m strip along the 7.07 m joint";
  // A vertical joint ending on the bend is a kink block's cut: left where it is.
  EXPECT_TRUE(io::parseCase(slabOnABend(0).dump(), at).movedJointEnds.empty());
}

// RS2 joint verification problem 9 (Alejano et al.'s bilinear slab, cases/bilinear_slab.json):
// UDEC 1.03, RS2 1.01, the drawn blocks' own limit equilibrium 1.0363 (scripts/block_equilibrium.py
// --solve fos; 1.0400 with the joint moved 0.5 m). The issue asks F within 3 % of UDEC and of the
// blocks' bound, and within ±1.5 % over penalty factors 10-2000, the presets, Δt 0.2-4 ms, threads,
// rigid blocks and the vertex treatment. Drawn with the cross joint ending on the bend, F went
// 0.80-1.01 over the penalty factors alone (docs/research/bilinear-slab.md).
TEST(Kinks, BilinearSlabFactorOfSafetyHoldsOverTheContactStiffnessAndSettings) {
  const std::string slab = std::string(DDASLOPE_SOURCE_DIR) + "/cases/bilinear_slab.json";
  double lo = INFINITY, hi = 0;
  for (const std::string setting :
       {"", "--set analysis.penalty_factor=10", "--set analysis.penalty_factor=100", "--set analysis.penalty_factor=2000",
        "--preset fast", "--preset accurate", "--time-step 2e-4", "--time-step 4e-3", "--threads 1", "--blocks rigid",
        "--contact-treatment vertex"}) {
    std::string err;
    const nlohmann::json r = nlohmann::json::parse(clitest::captureCli("fos " + slab + " --json --quiet " + setting, &err));
    ASSERT_TRUE(r["factor_of_safety"].is_number()) << setting << ": " << r.dump();
    const double f = r["factor_of_safety"];
    EXPECT_NEAR(f, 1.03, 0.03 * 1.03) << setting << ": UDEC";
    EXPECT_NEAR(f, 1.0363, 0.03 * 1.0363) << setting << ": the blocks' limit equilibrium";
    lo = std::min(lo, f), hi = std::max(hi, f);
  }
  EXPECT_LE(hi - lo, 0.03 * 0.5 * (hi + lo)) << "F from " << lo << " to " << hi;
}

// Sections without accidental corners (issue #38): with no kink_block_width the section is cut with
// an automatic kink block (max(5e-3 w0, 2 × failure displacement): 2.875 m on the chair), so where
// the joint set falls against the kink no longer moves the answer. Without it the chair's critical
// cohesion at φ = 18° went 17.4 / 44.9 / 36.0 / 25.9 kPa at joint offsets 0 / 10 / 25 / 40 m; the
// slices with the joints' friction need 48.5 / 48.5 / 48.9 / 48.9 kPa (scripts/chair_slide.py le,
// docs/calibration.md), and the issue asks 10 %. The automatic block is not cut where an inclined
// joint ends on the kink (the bilinear slab: 3 blocks) nor at a head scarp whose crown piece has no
// other joint (Jiufengershan: 8 blocks, as with no kink block).
TEST(Kinks, DefaultKinkBlockKeepsTheChairWithinTenPercentOfTheSlicesAtEveryJointOffset) {
  const std::string dir = std::string(DDASLOPE_SOURCE_DIR) + "/";
  for (const auto& [offset, slices] : {std::pair{0.0, 48.5e3}, {10.0, 48.5e3}, {25.0, 48.9e3}, {40.0, 48.9e3}}) {
    std::ifstream in(dir + "cases/chair_slide.json");
    nlohmann::json doc = nlohmann::json::parse(in);
    doc["section"].erase("kink_block_width");
    doc["section"]["joint_sets"][0]["origin"][0] = 500 - offset;  // the nearest joint `offset` m up the slope
    const model::Scene scene = io::parseCase(doc.dump(), dir + "cases/chair_slide.json");
    int joint = 0;
    while (scene.joints[joint].name != "sliding_surface") ++joint;
    const calibration::CriticalResult r = calibration::criticalCohesion(scene, joint, 18, 500);
    ASSERT_TRUE(r.found) << "offset " << offset << ": " << r.message;
    EXPECT_NEAR(r.critical, slices, 0.1 * slices) << "joint offset " << offset << " m";
  }
  EXPECT_EQ(io::readCase(dir + "cases/bilinear_slab.json").blocks.size(), 3u);
  EXPECT_EQ(io::readCase(dir + "cases/jiufengershan.json").blocks.size(), 8u);
}
