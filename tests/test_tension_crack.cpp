// Tension cracks as a section feature (issue #41) against Hoek & Bray's planar failure with a
// tension crack (Hoek & Bray, Rock Slope Engineering, ch. 7; Wyllie & Mah 2004, §6.3): the
// factor of safety dry, half-full and full, and the critical crack position of a dry slope.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ddaslope/calibration/position_search.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "test_io.hpp"

using namespace ddaslope;

namespace {

// The shipped section: toe at (0, 0), a 60° face H = 20 m high, a 35° plane through the toe.
constexpr double kH = 20, kC = 25e3, kGammaRock = 2600 * 9.81, kGammaWater = 9810;
const double kPsiF = degToRad(60), kPsiP = std::atan2(20.0, 28.562960138), kPhi = degToRad(30);

nlohmann::json crackCase() {
  std::ifstream in(std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure_crack.json");
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

/// Hoek & Bray: F = (cA + (W cos ψp − U − V sin ψp) tan φ)/(W sin ψp + V cos ψp), with the crack
/// b behind the toe (horizontally), z = H − b tan ψp deep, water zw = fraction·z in it draining to
/// the toe: U = γw zw A/2, V = γw zw²/2; W from the wedge's corners.
double hoekBray(double b, double fraction) {
  const double yb = b * std::tan(kPsiP), z = kH - yb, crest = kH / std::tan(kPsiF);
  // Shoelace of (0, 0), (b, yb), (b, H), (crest, H).
  const double area = 0.5 * std::abs(b * kH - b * yb + b * kH - crest * kH);
  const double w = kGammaRock * area, a = b / std::cos(kPsiP), zw = fraction * z;
  const double u = kGammaWater * zw * a / 2, v = kGammaWater * zw * zw / 2;
  return (kC * a + (w * std::cos(kPsiP) - u - v * std::sin(kPsiP)) * std::tan(kPhi)) /
         (w * std::sin(kPsiP) + v * std::cos(kPsiP));
}

double fosOf(const nlohmann::json& doc, const std::string& name) {
  const model::Scene s = io::parseCase(doc.dump(), name);
  const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(s, {}, 1e-3);
  EXPECT_TRUE(r.found) << r.message;
  return r.factor;
}

}  // namespace

// F within 1 % of Hoek & Bray dry, half-full and full, at two crack positions (the crack is at
// x = −b in the section, which faces +x).
TEST(TensionCrack, PlanarFailureDryHalfAndFullMatchHoekAndBray) {
  for (const double b : {20.0, 16.0})
    for (const double fraction : {0.0, 0.5, 1.0}) {
      nlohmann::json doc = crackCase();
      doc["section"]["tension_crack"] = {{"x", -b}, {"water_fraction", fraction}};
      const double expected = hoekBray(b, fraction);
      EXPECT_NEAR(fosOf(doc, "crack.json"), expected, 0.01 * expected) << "b = " << b << ", fraction " << fraction;
    }
}

// The same slope written other ways gives the same F (within the search's width 1e-3): the crack
// placed by its depth, the section moved 1e5 m away, extra vertices on the crest plateau and on
// the sliding plane (behind the crack, and under the wedge); and the hand-drawn blocks with a phreatic line
// (cases/planar_failure_water.json, the crack's wall 0.05 m behind instead of 0.035 m).
TEST(TensionCrack, SameSlopeWrittenAnotherWayGivesTheSameF) {
  nlohmann::json doc = crackCase();
  doc["section"]["tension_crack"] = {{"x", -20}, {"water_fraction", 1}};
  const double reference = fosOf(doc, "crack.json");
  EXPECT_NEAR(reference, hoekBray(20, 1), 0.01 * hoekBray(20, 1));

  nlohmann::json byDepth = crackCase();
  byDepth["section"]["tension_crack"] = {{"depth", kH - 20 * std::tan(kPsiP)}, {"water_fraction", 1}};
  EXPECT_NEAR(fosOf(byDepth, "depth.json"), reference, 1e-3);

  nlohmann::json far = doc;
  const double dx = 1e5, dy = 3e3;
  for (const char* line : {"ground", "sliding_surface"})
    for (auto& p : far["section"][line]) p = {p[0].get<double>() + dx, p[1].get<double>() + dy};
  far["section"]["tension_crack"]["x"] = -20 + dx;
  far["section"]["tension_crack"].erase("search");
  far["monitors"][0]["point"] = {-5 + dx, 5 + dy};
  EXPECT_NEAR(fosOf(far, "far.json"), reference, 1e-3);

  nlohmann::json extra = doc;
  extra["section"]["ground"] = {{-50, 20}, {-30, 20}, {-11.547005383793, 20}, {0, 0}, {2.886751345948, -5}, {20, -5}};
  extra["section"]["sliding_surface"] = {
      {-28.562960138, 20}, {-24, 24 * std::tan(kPsiP)}, {-10, 10 * std::tan(kPsiP)}, {0, 0}};
  EXPECT_NEAR(fosOf(extra, "extra.json"), reference, 1e-3);

  std::ifstream in(std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure_water.json");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json blocks = nlohmann::json::parse(text.str());
  blocks.erase("expected");
  EXPECT_NEAR(fosOf(blocks, "planar_failure_water.json"), reference, 1e-3);
}

// fos searches the crack's position: on the dry slope the least safe crack lies b/H =
// sqrt(cot ψf cot ψp) − cot ψf behind the crest (Hoek & Bray), found within 2 % of that distance,
// with F within 1 % of its closed-form minimum; `critical` finds the same position for c.
TEST(TensionCrack, SearchFindsHoekAndBraysCriticalCrack) {
  const double crest = kH / std::tan(kPsiF);
  const double behind = kH * (std::sqrt(1 / std::tan(kPsiF) / std::tan(kPsiP)) - 1 / std::tan(kPsiF));
  ASSERT_NEAR(behind, 6.614, 1e-3);  // the book's b/H = 0.3307
  const double fMin = hoekBray(crest + behind, 0);
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure_crack.json";
  std::string err;
  const nlohmann::json fos = nlohmann::json::parse(clitest::captureCli("fos " + path + " --width 1e-4 --quiet --json", &err));
  ASSERT_TRUE(fos["found"].get<bool>()) << err;
  const double x = fos["tension_crack"]["x"].get<double>();
  EXPECT_NEAR(-x - crest, behind, 0.02 * behind);
  EXPECT_NEAR(fos["factor_of_safety"].get<double>(), fMin, 0.01 * fMin);
  EXPECT_FALSE(fos["tension_crack"]["at_end"].get<bool>());
  const nlohmann::json critical = nlohmann::json::parse(clitest::captureCli("critical " + path + " --quiet --json", &err));
  ASSERT_TRUE(critical["found"].get<bool>()) << err;
  EXPECT_NEAR(-critical["tension_crack"]["x"].get<double>() - crest, behind, 0.02 * behind);
}

// The position search alone, on a curve like the slope's (a minimum with a cubic lean, values
// rounded to the searches' precision as bisection rounds them): the vertex within 1 % of the
// range; at an end of the range when the curve falls all the way.
TEST(TensionCrack, PositionSearchFindsAFlatMinimumThroughRounding) {
  const double precision = 1e-4;
  const auto rounded = [&](double v) { return precision * std::floor(v / precision) + precision / 2; };
  const auto curve = [](double x) { return 1.111 + 8e-4 * (x - 18.16) * (x - 18.16) - 4e-5 * std::pow(x - 18.16, 3); };
  const auto evaluate = [&](const std::vector<double>& xs) {
    std::vector<calibration::PositionSample> out;
    for (double x : xs) out.push_back({x, rounded(curve(x)), true, ""});
    return out;
  };
  const auto r = calibration::searchLeastSafePosition(12, 26, 9, false, precision, evaluate);
  EXPECT_TRUE(r.fitted);
  EXPECT_FALSE(r.atEnd);
  EXPECT_NEAR(r.best, 18.16, 0.01 * 14);
  EXPECT_LT(r.flatLo, 18.16);
  EXPECT_GT(r.flatHi, 18.16);
  const auto falling = calibration::searchLeastSafePosition(12, 26, 9, false, precision, [&](const std::vector<double>& xs) {
    std::vector<calibration::PositionSample> out;
    for (double x : xs) out.push_back({x, 2 - 0.05 * x, true, ""});
    return out;
  });
  EXPECT_TRUE(falling.atEnd);
  EXPECT_DOUBLE_EQ(falling.best, 26);
}

// Every bad value of section.tension_crack is refused with the file and its JSON path.
TEST(TensionCrack, BadValuesAreRefusedWithTheirPath) {
  const auto refused = [](const nlohmann::json& crack, const std::string& path, const std::string& what,
                          bool withWater = false) {
    nlohmann::json doc = crackCase();
    doc["section"]["tension_crack"] = crack;
    if (withWater) doc["water"] = {{"level", 5}};
    clitest::expectInputError([&] { io::parseCase(doc.dump(), "bad.json"); }, "bad.json", path, what);
  };
  refused({{"x", 5}}, "section.tension_crack.x", "expected x between the crown");
  refused({{"x", -28.56}}, "section.tension_crack.x", "expected x between the crown");
  refused({{"x", -20}, {"depth", 5}}, "section.tension_crack", "exactly one of x");
  refused(nlohmann::json::object(), "section.tension_crack", "exactly one of x");
  refused({{"depth", 50}}, "section.tension_crack.depth", "nowhere this deep");
  refused({{"depth", -1}}, "section.tension_crack.depth", "a depth > 0 m");
  refused({{"x", -20}, {"water_fraction", 1.5}}, "section.tension_crack.water_fraction", "in [0, 1]");
  refused({{"x", -20}, {"search", {-12, -26}}}, "section.tension_crack.search", "x_min < x_max");
  refused({{"x", -20}, {"search", -12}}, "section.tension_crack.search", "expected [x_min, x_max]");
  refused({{"x", -20}, {"width", 1}}, "section.tension_crack.width", "");
  refused({{"x", -20}, {"water_fraction", 0.5}}, "water", "the tension crack's water", true);
}
