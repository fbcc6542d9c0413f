// Critical strength and strength reduction against closed forms (benchmarks.md A5, B1, C).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "ddaslope/calibration/strength_search.hpp"
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "ddaslope/io/case_reader.hpp"
#include "scene_builders.hpp"
#include "test_io.hpp"

using namespace ddaslope;
using scenes::InclineSpec;
using scenes::Planar;
using scenes::planar;

namespace {

/// The same with water standing zw m deep in the tension crack and draining to the toe along the
/// plane (Hoek & Bray's assumption): a phreatic line from the toe (0, 0) to the crack's water
/// surface, flat beyond it. FS = (c A + (W cos ψ − U − V sin ψ) tan φ)/(W sin ψ + V cos ψ),
/// U = γw zw A / 2 on the plane, V = γw zw² / 2 in the crack.
double hoekBrayWithWater(const Planar& p, double c, double phi, double zw) {
  const double u = 9810 * zw * p.length / 2, v = 9810 * zw * zw / 2;
  return (c * p.length + (p.weight * std::cos(p.psi) - u - v * std::sin(p.psi)) * std::tan(phi)) /
         (p.weight * std::sin(p.psi) + v * std::cos(p.psi));
}

}  // namespace

// The verdict does not depend on Δt: a block just past failure (φ = 29.9° on 30°, a = 0.020 m/s²)
// fails and one just short of it (φ = 30.1°) holds at Δt = 0.1, 1 and 10 ms (issue #4), brought
// to rest first (where the failing block gives way before t = 0: rule (0)) or started as drawn
// (the run decides).
TEST(Verdict, IndependentOfTimeStep) {
  for (bool settle : {true, false}) {
    for (double dt : {1e-4, 1e-3, 1e-2}) {
      for (double phi : {29.9, 30.1}) {
        InclineSpec s;
        s.phiDeg = phi;
        s.timeStep = dt;
        model::Scene scene = scenes::makeIncline(s);
        scene.settings.initialEquilibrium = settle;
        const calibration::TrialResult r = calibration::judgeStability(scene);
        EXPECT_EQ(r.stable, phi > 30) << "dt " << dt << " phi " << phi << " settle " << settle << ": " << r.reason;
        if (!settle) {
          EXPECT_NE(r.rule, calibration::VerdictRule::MovedWhileSettling);
        }
      }
    }
  }
}

// A5: critical friction on a 30° plane, c = 0: 30.00° ± 0.05° (benchmarks.md A5).
TEST(CriticalStrength, A5CriticalFrictionOnThirtyDegrees) {
  const model::Scene s = scenes::makeIncline(InclineSpec{});
  const calibration::CriticalResult r = calibration::criticalFriction(s, 0, 0, 0.01);
  ASSERT_TRUE(r.found) << r.message;
  EXPECT_NEAR(r.critical, 30.0, 0.05);
  EXPECT_LE(r.failingEnd, r.stableEnd);
}

// B1 through the critical-cohesion search: 36.40 kPa within 1 % (benchmarks.md B1).
TEST(CriticalStrength, B1CriticalCohesionOfTheA2Block) {
  InclineSpec spec{40, 10, 5, 20, 0, 2000, 10};
  spec.duration = 0.5;
  const calibration::CriticalResult r = calibration::criticalCohesion(scenes::makeIncline(spec), 0, 20, 20);
  ASSERT_TRUE(r.found) << r.message;
  EXPECT_NEAR(r.critical, 36400, 0.01 * 36400);
}

// C: strength-reduction factor of safety of a planar failure within 2 % of Hoek & Bray's
// FS = (c A + W cos ψ tan φ)/(W sin ψ), dry, for three (c, φ, ψ) sets including FS < 1.
TEST(StrengthReduction, PlanarFailureMatchesHoekAndBray) {
  struct Set {
    double c, phi, psi;
  };
  for (const Set& set : {Set{25e3, 30, 35}, Set{10e3, 35, 40}, Set{0, 30, 35}}) {
    const Planar p = planar(set.psi, set.c, set.phi);
    const double expected = p.factor(set.c, set.phi * M_PI / 180);
    const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(p.scene, {}, 0.005);
    SCOPED_TRACE("c " + std::to_string(set.c) + " phi " + std::to_string(set.phi) + " psi " + std::to_string(set.psi));
    ASSERT_TRUE(r.found) << r.message;
    EXPECT_NEAR(r.factor, expected, 0.02 * expected);
    EXPECT_LE(r.failingEnd - r.stableEnd, 0.005 + 1e-12);
  }
}

// The same three planar failures with every trial started from the rest at the case's own
// strengths (TrialStart::Settled): Hoek & Bray's FS within the same 2 %. The set with FS < 1 fails
// at its own strengths, so its trials start from every contact held and say so.
TEST(StrengthReduction, TrialsFromTheSettledStateMatchHoekAndBray) {
  struct Set {
    double c, phi, psi;
  };
  calibration::SearchSettings settled;
  settled.trialStart = calibration::TrialStart::Settled;
  for (const Set& set : {Set{25e3, 30, 35}, Set{10e3, 35, 40}, Set{0, 30, 35}}) {
    const Planar p = planar(set.psi, set.c, set.phi);
    const double expected = p.factor(set.c, set.phi * M_PI / 180);
    const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(p.scene, {}, 0.005, settled);
    SCOPED_TRACE("c " + std::to_string(set.c) + " phi " + std::to_string(set.phi) + " psi " + std::to_string(set.psi));
    ASSERT_TRUE(r.found) << r.message;
    EXPECT_NEAR(r.factor, expected, 0.02 * expected);
    EXPECT_EQ(r.trialStart, expected > 1 ? calibration::TrialStart::Settled : calibration::TrialStart::Held);
  }
}

// The critical (c, φ) curve of the planar failure matches c_cr = W (sin ψ − cos ψ tan φ)/A
// (Hoek & Bray's FS = 1, benchmarks.md §C) at every point within 1 %, and is 0 once φ ≥ ψ.
TEST(CriticalStrength, CurveOfPlanarFailureMatchesClosedForm) {
  const Planar p = planar(35, 0, 30);
  const auto curve = calibration::criticalCurve(p.scene, 0, 10, 40, 7, 20);
  ASSERT_EQ(curve.size(), 7u);
  for (const auto& pt : curve) {
    const double phi = pt.frictionDeg * M_PI / 180;
    const double expected = std::max(0.0, p.weight * (std::sin(p.psi) - std::cos(p.psi) * std::tan(phi)) / p.length);
    SCOPED_TRACE("phi " + std::to_string(pt.frictionDeg));
    ASSERT_TRUE(pt.cohesion.found) << pt.cohesion.message;
    if (expected == 0) EXPECT_EQ(pt.cohesion.critical, 0);
    else EXPECT_NEAR(pt.cohesion.critical, expected, 0.01 * expected);
  }
}

// Two-wedge limit equilibrium (the idealisation used for Vajont): an active block on a 40° plane
// thrusts through a vertical joint (friction δ = 40°) on a passive block sliding on a flat toe.
// Active block: P = W_a (sin α − tan φ cos α) / ((sin α − tan φ cos α) tan δ + cos α + tan φ sin α);
// passive block: P = W_p / (cot φ − tan δ). The critical φ makes them equal; DDA's critical
// friction of calibration/two_block_slide must match it within 0.1°.
TEST(CriticalStrength, TwoWedgeSlideMatchesLimitEquilibrium) {
  const model::Scene s = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/calibration/two_block_slide/case.json");
  const double wa = 2400 * 9.81 * s.blocks[1].moments.area, wp = 2400 * 9.81 * s.blocks[2].moments.area;
  const double a = 40 * M_PI / 180, td = std::tan(40 * M_PI / 180);
  const auto imbalance = [&](double phi) {
    const double t = std::tan(phi), k = std::sin(a) - t * std::cos(a);
    const double needed = wa * k / (k * td + std::cos(a) + t * std::sin(a));
    const double capacity = wp / (1 / t - td);
    return needed - capacity;
  };
  double lo = 1 * M_PI / 180, hi = 30 * M_PI / 180;  // imbalance > 0 at lo (fails), < 0 at hi
  for (int i = 0; i < 60; ++i) (imbalance(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double limitEquilibrium = 0.5 * (lo + hi) * 180 / M_PI;
  int surface = 0;
  while (s.joints[surface].name != "sliding_surface") ++surface;
  const calibration::CriticalResult r = calibration::criticalFriction(s, surface, 0, 0.01);
  ASSERT_TRUE(r.found) << r.message;
  EXPECT_NEAR(r.critical, limitEquilibrium, 0.1);
}

// Trials that differ only in joint strength may share the first equilibrium stage (it holds
// every contact, so strength does not enter it). Sharing must not change a verdict: A2 with
// cohesion just above and below c_cr = 36.40 kPa (benchmarks.md B1), from one shared state.
TEST(Verdict, SharedEquilibriumGivesTheSameVerdicts) {
  InclineSpec spec{40, 10, 5, 20, 0, 2000, 10};
  spec.duration = 0.5;
  const model::Scene base = scenes::makeIncline(spec);
  const solver::HeldEquilibrium held = solver::Simulation(base).holdEquilibrium();
  for (double c : {0.99 * 36397, 1.01 * 36397}) {
    model::Scene s = base;
    s.joints[0].cohesion = c;
    const calibration::TrialResult own = calibration::judgeStability(s);
    const calibration::TrialResult shared = calibration::judgeStability(s, {}, &held);
    EXPECT_EQ(own.stable, c > 36397) << c;
    EXPECT_EQ(shared.stable, own.stable) << c;
    if (own.stable) {
      EXPECT_NEAR(shared.maxDisplacement, own.maxDisplacement, 1e-6);
    }
  }
}

// C with a water-filled tension crack: strength reduction within 2 % of Hoek & Bray with water
// (benchmarks.md §C) for the crack half and completely full.
TEST(StrengthReduction, PlanarFailureWithWaterInTheTensionCrack) {
  for (const double fill : {0.5, 1.0}) {
    Planar p = planar(35, 25e3, 30);
    const double zw = fill * p.crackDepthToPlane, xc = 20, planeAtCrack = xc * std::tan(p.psi);
    p.scene.water.line = {{0, 0}, {xc, planeAtCrack + zw}};
    const double expected = hoekBrayWithWater(p, 25e3, 30 * M_PI / 180, zw);
    const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(p.scene, {}, 0.005);
    SCOPED_TRACE("zw " + std::to_string(zw));
    ASSERT_TRUE(r.found) << r.message;
    EXPECT_NEAR(r.factor, expected, 0.02 * expected);
  }
}

// D: the Alejano & Alonso toppling slope (benchmarks.md D, cases/toppling_slope.json). Published
// strength-reduction factors: UDEC 0.87, RS2 0.86 and 0.82, Goodman-Bray limit equilibrium 0.76.
// The numerical models spread by 6 %; DDA must land within 5 % of UDEC's 0.87 and above Goodman
// & Bray on the same blocks (0.773, scripts/toppling_limit_equilibrium.py), as every published
// numerical model lies above its limit equilibrium.
TEST(StrengthReduction, TopplingSlopeMatchesPublishedDistinctElementResult) {
  const model::Scene s = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/cases/toppling_slope.json");
  const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(s, {}, 0.005);
  ASSERT_TRUE(r.found) << r.message;
  EXPECT_NEAR(r.factor, 0.87, 0.05 * 0.87);
  EXPECT_GT(r.stableEnd, 0.773);
}

// A6/A7 (benchmarks.md; Hoek & Bray's sliding and toppling chart): a block with b/h < tan α
// topples about its toe whatever the strength of its base, so strength reduction has no F, and
// says why rather than calling it a failure at some small F. b = 1, h = 2.5 on 30° (b/h 0.4 <
// 0.577), φ = 40°. The critical cohesion and friction searches agree: no cohesion or friction
// holds it. The same block lying down (b = 2, h = 1: b/h 2 > tan α) only slides, at F = tan 40°/
// tan 30° = 1.4533 (A5's closed form); 0.008 is the bracket's width of 0.005 plus A5's 0.05°
// resolution of the critical friction, 0.0026 in F.
TEST(StrengthReduction, ABlockThatTopplesWhateverItsStrengthHasNoFactor) {
  InclineSpec s;
  s.phiDeg = 40;
  s.b = 1;
  s.h = 2.5;
  const model::Scene toppling = scenes::makeIncline(s);
  const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(toppling, {}, 0.005);
  EXPECT_FALSE(r.found);
  EXPECT_NE(r.message.find("no strength of the reduced joints holds this scene"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("topples"), std::string::npos) << r.message;
  const calibration::CriticalResult c = calibration::criticalCohesion(toppling, 0, 40, 1000);
  EXPECT_FALSE(c.found);
  EXPECT_NE(c.message.find("strength cannot hold this scene"), std::string::npos) << c.message;
  const calibration::CriticalResult f = calibration::criticalFriction(toppling, 0, 0, 0.1);
  EXPECT_FALSE(f.found);
  EXPECT_NE(f.message.find("strength cannot hold this scene"), std::string::npos) << f.message;

  // The toppling block as a user writes it, a case file placed 1e5 m from the origin: `fos` exits
  // with 3 (no answer) and says why.
  const double a = M_PI / 6, x0 = 1e5, y0 = 1e5;
  const auto on = [&](double along, double up) {
    return nlohmann::json::array({x0 + along * std::cos(a) - up * std::sin(a), y0 + along * std::sin(a) + up * std::cos(a)});
  };
  nlohmann::json d = {
      {"gravity", {0, -9.81}},
      {"materials", {{"rock", {{"density", 2600}, {"young_modulus", 5e9}, {"poisson_ratio", 0.25}}}}},
      {"joints", {{"base", {{"friction_angle", 40}, {"cohesion", 0}, {"tensile_strength", 0}}}}},
      {"blocks",
       {{{"id", "ramp"}, {"material", "rock"}, {"fixed", true}, {"vertices", {on(-2, -3), on(20, -3), on(20, 0), on(-2, 0)}}},
        {{"id", "column"}, {"material", "rock"}, {"vertices", {on(10, 0), on(11, 0), on(11, 2.5), on(10, 2.5)}}}}},
      {"monitors", {{{"id", "m"}, {"block", "column"}, {"point", on(10.5, 1.25)}}}},
      {"analysis", {{"duration", 1.0}, {"time_step", 0.001}}}};
  const std::string path = clitest::writeTemp("toppling_column.json", d.dump());
  std::string err;
  EXPECT_EQ(clitest::runCli("fos " + path + " --quiet --out " + path + ".out", &err), 3) << err;
  EXPECT_NE(err.find("no strength of the reduced joints holds this scene"), std::string::npos) << err;
  EXPECT_NE(err.find("`ddaslope run " + path + " --at-fos 0.01`"), std::string::npos) << "the user's case in the hint: " << err;
  std::string text;
  EXPECT_EQ(clitest::runCliCapturing("fos " + path + " --quiet --json --out " + path + ".out", &text, &err), 3) << err;
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_TRUE(j["factor_of_safety"].is_null());
  EXPECT_TRUE(j["bracket"][0].is_null() && j["bracket"][1].is_null()) << j["bracket"];  // no answer, no numbers
  EXPECT_NE(j["message"].get<std::string>().find("`ddaslope run " + path + " --at-fos 0.01`"), std::string::npos);
  std::filesystem::remove_all(path + ".out");

  s.b = 2;
  s.h = 1;
  const calibration::FactorOfSafetyResult lying = calibration::factorOfSafety(scenes::makeIncline(s), {}, 0.005);
  ASSERT_TRUE(lying.found) << lying.message;
  EXPECT_NEAR(lying.factor, std::tan(40 * M_PI / 180) / std::tan(30 * M_PI / 180), 0.008);
}

// D with the basal joint ending at the bench level: the columns can leave only by sliding on the
// 30° basal joint itself, so the slope holds while the reduced friction exceeds the base's 30°:
// F ≥ tan 31°/tan 30° = 1.0407 (closed form of a block on a plane; the verdict's resolution is
// the 0.005 bracket). The bench blocks the toe column's tip, so the slide must push that column
// over the bench corner, which can add at most what the column carries by friction: all its
// weight W_t on the tip, P ≤ W_t tan 31°/(cos 30° − sin 30° tan 31°) = 1.063 W_t, plus its base,
// W_t cos 30° tan 31° = 0.520 W_t. Its area is 0.731 of the slide's 54.474 m² (a = 0.01342, from
// `ddaslope cut cases/toppling_slope_bench_toe.json`), so
// (1 − a)(sin 30° − cos 30° tan 31°/F) ≤ 1.583 a bounds F ≤ 1.0876. Measured: 1.0463 once the
// scene starts truly at rest (stage 3 of the equilibrium); 1.041 when the start's out-of-balance
// force kicked the toe column over the corner.
TEST(StrengthReduction, TopplingSlopeWithObstructedToeFailsOnlyByBaseSliding) {
  const model::Scene s = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/cases/toppling_slope_bench_toe.json");
  const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(s, {}, 0.005);
  ASSERT_TRUE(r.found) << r.message;
  const double slidingBound = std::tan(31 * M_PI / 180) / std::tan(30 * M_PI / 180);
  EXPECT_GE(r.stableEnd, slidingBound - 0.005);
  const double a = 0.731 / 54.474, tan31 = std::tan(31 * M_PI / 180), c30 = std::cos(M_PI / 6), s30 = 0.5;
  const double toeCapacity = tan31 / (c30 - s30 * tan31) + c30 * tan31;  // × W_t
  const double upperBound = c30 * tan31 / (s30 - toeCapacity * a / (1 - a));
  EXPECT_LE(r.factor, upperBound);
}

// `run --at-fos F` is the search's trial at F, for a user to look at (issue #43): on the planar
// failure (Hoek & Bray, FS 1.1133) it reduces c and tan φ by F as `fos` does (c/F, the printed
// values against the closed form), and at the bracket's stable end the wedge holds (the case's
// own bar: at most 0.01 m) while at its failing end it slides past it, as the search found.
// summary.json names the factor and the joints; the case's expectations (made for its own
// strengths) are not checked.
TEST(StrengthReduction, RunAtFosShowsTheSearchsVerdicts) {
  namespace fs = std::filesystem;
  const std::string c = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  std::string err;
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_atfos_" + std::to_string(::getpid()));
  // The search's pictures in this test's own folder, not in the working directory's out/fos,
  // which other tests running at the same time write too.
  const auto fos = nlohmann::json::parse(
      clitest::captureCli("fos " + c + " --width 1e-3 --json --out " + (dir / "fos").string(), &err));
  const double stable = fos["bracket"][0], failing = fos["bracket"][1];
  const auto displacement = [&](double f, std::string* printed) {
    char digits[32];
    std::snprintf(digits, sizeof digits, "%.17g", f);
    *printed = clitest::captureCli("run " + c + " --at-fos " + digits + " --out " + dir.string(), &err);
    const auto s = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
    EXPECT_DOUBLE_EQ(s["strength_reduction"]["factor"].get<double>(), f);
    EXPECT_EQ(s["strength_reduction"]["joints"], nlohmann::json::array({"sliding_plane"}));
    EXPECT_FALSE(s.contains("expectations") && !s["expectations"].empty());
    return std::hypot(s["monitors"]["wedge"]["ux"].get<double>(), s["monitors"]["wedge"]["uy"].get<double>());
  };
  std::string printed;
  const double held = displacement(stable, &printed);
  char expected[96];
  std::snprintf(expected, sizeof expected, "cohesion 25000 -> %.6g Pa, friction angle 30.0000 -> %.4f deg",
                25000 / stable, std::atan(std::tan(30 * M_PI / 180) / stable) * 180 / M_PI);
  EXPECT_NE(printed.find(expected), std::string::npos) << printed;
  EXPECT_NE(printed.find("not checked at F"), std::string::npos) << printed;
  const double slid = displacement(failing, &printed);
  EXPECT_LT(held, 0.01);
  EXPECT_GT(slid, 0.01);
  std::printf("F %.5f: %.3g m; F %.5f: %.3g m\n", stable, held, failing, slid);
  // A snapshot asked past the run's end is said, not silently dropped.
  clitest::captureCli("run " + c + " --at-fos 1.1 --duration 0.2 --snapshots 0,100 --out " + dir.string(), &err);
  EXPECT_NE(err.find("1 of the --snapshots times lie past the run's end"), std::string::npos) << err;
  EXPECT_TRUE(fs::exists(dir / "snapshot_00.png"));
  EXPECT_FALSE(fs::exists(dir / "snapshot_01.png"));
  EXPECT_EQ(clitest::runCli("run " + c + " --at-fos 1.1 --joints nope --out " + dir.string(), &err), 2);
  EXPECT_NE(err.find("no joint named \"nope\""), std::string::npos) << err;
  EXPECT_EQ(clitest::runCli("run " + c + " --joints sliding_plane --out " + dir.string(), &err), 2);
  fs::remove_all(dir);
}

// `fos --check F` answers "does the slope meet F?" without a search: it runs the trial
// the search itself runs at F. On Hoek & Bray's planar failure (closed form 1.1133, docs/validation.md
// C) F is met 2 % below that and not met 2 % above (the search's own tolerance against the closed
// form, PlanarFailureMatchesHoekAndBray). At every factor a search tried, held and settled, the
// check's trial is the search's trial: same rule, steps after and before t = 0, time and motion (the
// trial in force: a re-run's where the review made one). So it is on the Alejano & Alonso toppling
// slope (columns that topple, not a sliding block) and on the bilinear slab with its bedding reduced
// alone, at the bracket's ends. The JSON says the verdict, the joints, the runs (a settled start's
// trial at F = 1 counted), and the picture is of the check's own trial only.
TEST(StrengthReduction, CheckAtARequiredFactorIsTheSearchsTrialThere) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_check_" + std::to_string(::getpid()));
  std::string err;
  const auto check = [&](const std::string& c, double f, const std::string& options) {
    char digits[32];
    std::snprintf(digits, sizeof digits, "%.17g", f);
    const auto j = nlohmann::json::parse(clitest::captureCli(
        "fos " + c + " --check " + digits + " " + options + " --json --quiet --out " + (dir / "check").string(), &err));
    EXPECT_DOUBLE_EQ(j["check"].get<double>(), f);
    EXPECT_EQ(j["forward_runs"], j["trials"].size());
    const auto file = nlohmann::json::parse(std::ifstream(dir / "check" / "fos.json"));
    EXPECT_EQ(file["verdict"], j["verdict"]);
    const bool stable = j["verdict"] == "stable";
    EXPECT_EQ(j["meets_factor"], stable) << j.dump();
    EXPECT_EQ(fs::exists(dir / "check" / "mechanism_stable.png"), stable);
    EXPECT_EQ(fs::exists(dir / "check" / "mechanism_failed.png"), j["verdict"] == "failing");
    return j;
  };
  const std::string planar = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  EXPECT_EQ(check(planar, 0.98 * 1.1133, "")["verdict"], "stable");
  EXPECT_EQ(check(planar, 1.02 * 1.1133, "")["verdict"], "failing");
  const struct {
    std::string name, options;
    bool everyTrial;
  } searches[] = {{"planar_failure", "", true},
                  {"planar_failure", "--trial-start settled", true},
                  {"toppling_slope", "", false},
                  {"bilinear_slab", "--joints bedding", false}};
  for (const auto& search : searches) {
    SCOPED_TRACE(search.name + " " + search.options);
    const std::string c = std::string(DDASLOPE_SOURCE_DIR) + "/cases/" + search.name + ".json";
    const auto fos = nlohmann::json::parse(
        clitest::captureCli("fos " + c + " " + search.options + " --json --quiet --out " + (dir / "fos").string(), &err));
    ASSERT_TRUE(fos["found"].get<bool>());
    std::map<double, nlohmann::json> inForce;
    for (const auto& t : fos["trials"])
      if (t["rerun"].get<bool>() || !inForce.count(t["factor"].get<double>())) inForce[t["factor"].get<double>()] = t;
    int compared = 0;
    for (const auto& [f, t] : inForce) {
      if (!search.everyTrial && f != fos["bracket"][0].get<double>() && f != fos["bracket"][1].get<double>()) continue;
      const auto j = check(c, f, search.options);
      const auto& mine = j["trials"].back();
      for (const char* key : {"stable", "rule", "steps", "equilibrium_steps", "time_s", "max_displacement_m",
                              "settling_displacement_m", "run_on", "rerun"})
        EXPECT_EQ(mine[key], t[key]) << "F = " << f << ": " << key;
      EXPECT_EQ(j["verdict"], t["stable"].get<bool>() ? "stable" : "failing") << "F = " << f;
      // The search's trial at F = 1 starts held, as it must to find the rest the others start from.
      EXPECT_EQ(j["trial_start"], f == 1 ? "held" : fos["trial_start"]) << "F = " << f;
      ++compared;
    }
    EXPECT_GE(compared, search.everyTrial ? 9 : 2);
    if (search.options == "--joints bedding") {
      EXPECT_EQ(check(c, 1.2, search.options)["joints"], nlohmann::json::array({"bedding"}));
    }
  }
  // A trial that cannot converge (no Δt cut allowed, one open-close iteration) says so: exit 3, no
  // verdict on F, no picture of a mechanism it did not show.
  std::string out;
  EXPECT_EQ(clitest::runCliCapturing("fos " + planar + " --check 1.12 --set analysis.max_step_cuts=0 --set "
                                     "analysis.open_close_max_iterations=1 --json --quiet --out " + (dir / "nc").string(),
                                     &out, &err),
            3);
  const auto nc = nlohmann::json::parse(out);
  EXPECT_EQ(nc["verdict"], "not_converged");
  EXPECT_TRUE(nc["meets_factor"].is_null());
  EXPECT_FALSE(fs::exists(dir / "nc" / "mechanism_failed.png"));
  // Without --out a check writes out/fos_check, and leaves a search's out/fos alone.
  const fs::path here = fs::current_path();
  fs::create_directories(dir / "cwd");
  fs::current_path(dir / "cwd");
  clitest::captureCli("fos " + planar + " --check 1.3 --quiet", &err);
  fs::current_path(here);
  EXPECT_TRUE(fs::exists(dir / "cwd" / "out" / "fos_check" / "fos.json"));
  EXPECT_FALSE(fs::exists(dir / "cwd" / "out" / "fos"));
  fs::remove_all(dir);
}

// A check whose trial stays undecided says so: a block gliding at 1 cm/s on a
// frictionless base, against a failure displacement of 10 m, moves 4 cm in its first run and its
// three extensions (4 s), and 16 cm in the re-run four times longer (16 s), under 10 % of 10 m
// both times and never growing (SmallMotion.SteadyGlideIsUndecidedNotFailure): undecided, exit 3,
// no verdict on F, two forward runs, no picture.
TEST(StrengthReduction, ACheckThatStaysUndecidedSaysSo) {
  namespace fs = std::filesystem;
  const std::string c = clitest::writeTemp("glide.json", R"({
    "gravity": [0, -9.81],
    "materials": {"rock": {"density": 2500, "young_modulus": 1e10, "poisson_ratio": 0.25}},
    "joints": {"smooth": {"friction_angle": 0, "cohesion": 0, "tensile_strength": 0}},
    "blocks": [
      {"id": "base", "material": "rock", "fixed": true, "vertices": [[0, -2], [100, -2], [100, 0], [0, 0]]},
      {"id": "block", "material": "rock", "vertices": [[10, 0], [11, 0], [11, 1], [10, 1]], "velocity": [0.01, 0]}],
    "analysis": {"duration": 1.0, "time_step": 0.001, "failure_displacement": 10}})");
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_undecided_" + std::to_string(::getpid()));
  std::string out, err;
  EXPECT_EQ(clitest::runCliCapturing("fos " + c + " --check 1.3 --json --quiet --out " + dir.string(), &out, &err), 3)
      << err;
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["verdict"], "undecided");
  EXPECT_TRUE(j["meets_factor"].is_null());
  EXPECT_EQ(j["forward_runs"], 2);
  ASSERT_EQ(j["trials"].size(), 2u);
  EXPECT_TRUE(j["trials"][1]["rerun"].get<bool>());
  EXPECT_NEAR(j["trials"][1]["max_displacement_m"].get<double>(), 0.16, 0.01 * 0.16) << "m: 1 cm/s over 16 s";
  EXPECT_FALSE(fs::exists(dir / "mechanism_stable.png") || fs::exists(dir / "mechanism_failed.png"));
  EXPECT_EQ(clitest::runCliCapturing("fos " + c + " --check 1.3 --out " + dir.string(), &out, &err), 3);
  EXPECT_NE(out.find("F = 1.3: undecided"), std::string::npos) << out;
  fs::remove_all(dir);
}

// `fos` draws the mechanism (issue #43): on the shipped planar and toppling cases it writes the
// pictures of the trials at its bracket's ends, mechanism_stable.png and mechanism_failed.png,
// into --out and lists them in its JSON; `critical` does the same for its bracket.
TEST(StrengthReduction, FosWritesTheMechanismAtItsBracketsEnds) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_mechanism_" + std::to_string(::getpid()));
  std::string err;
  const auto isPng = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    char magic[8] = {};
    in.read(magic, 8);
    return in && std::string(magic + 1, 3) == "PNG" && fs::file_size(p) > 1000;
  };
  for (const std::string name : {"planar_failure", "toppling_slope"}) {
    fs::remove_all(dir);
    const std::string c = std::string(DDASLOPE_SOURCE_DIR) + "/cases/" + name + ".json";
    const auto fos = nlohmann::json::parse(clitest::captureCli("fos " + c + " --json --out " + dir.string(), &err));
    ASSERT_TRUE(fos["found"].get<bool>()) << name;
    ASSERT_EQ(fos["mechanism_pictures"].size(), 2u) << name;
    for (const char* f : {"mechanism_stable.png", "mechanism_failed.png"}) EXPECT_TRUE(isPng(dir / f)) << name << " " << f;
  }
  fs::remove_all(dir);
  const auto critical = nlohmann::json::parse(clitest::captureCli(
      "critical " + std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json --json --out " + dir.string(), &err));
  EXPECT_EQ(critical["mechanism_pictures"].size(), 2u);
  EXPECT_TRUE(isPng(dir / "mechanism_failed.png"));
  fs::remove_all(dir);
}

// Soft blocks settle elastically under their own weight (Hoek & Bray's wedge at E = 3 MPa: a
// strain of ρgH/E ≈ 0.1 over its height, centimetres), whatever the joints' strength: every
// factor down to 1.5^-40 "fails" while settling by the same motion. The search finds no F, and
// says that this may be the blocks' settlement, with its size against the failure displacement,
// rather than only a toppling or lifting block; only where the motion is within the blocks' own
// elastic settlement, ρgh²/E.
TEST(StrengthReduction, ASettlementOfSoftBlocksIsNamedWhenEveryFactorFails) {
  const std::string planar = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  std::string out, err;
  EXPECT_EQ(clitest::runCliCapturing("fos " + planar + " --set materials.rock.young_modulus=3e6 --json --quiet --out " +
                                         (std::filesystem::temp_directory_path() / "ddaslope_soft").string(),
                                     &out, &err),
            3);  // no answer: exit 3
  const auto soft = nlohmann::json::parse(out);
  EXPECT_TRUE(soft["factor_of_safety"].is_null());
  const std::string message = soft["message"];
  EXPECT_NE(message.find("the blocks' own settlement"), std::string::npos) << message;
  EXPECT_NE(message.find("against the failure displacement 0.025 m"), std::string::npos) << message;
  EXPECT_NE(message.find("as much as at every other factor"), std::string::npos) << message;
  // A toppling column of 5 GPa rock (cases/toppling_block.json, 25 m: ρgh²/E ≈ 3 mm) fails at
  // every factor too, by toppling 7 cm: not a settlement, and not called one.
  EXPECT_EQ(clitest::runCliCapturing("fos " + std::string(DDASLOPE_SOURCE_DIR) + "/cases/toppling_block.json --json --quiet --out " +
                                         (std::filesystem::temp_directory_path() / "ddaslope_soft").string(),
                                     &out, &err),
            3);
  const std::string topples = nlohmann::json::parse(out)["message"];
  EXPECT_NE(topples.find("a block that topples"), std::string::npos) << topples;
  EXPECT_EQ(topples.find("own settlement"), std::string::npos) << topples;
}
