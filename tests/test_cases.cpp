// Every shipped case runs and meets the expected values it carries; runs are deterministic.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/run_case.hpp"

namespace fs = std::filesystem;
using namespace ddaslope;

namespace {
std::vector<std::string> shippedCases() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::path(DDASLOPE_SOURCE_DIR) / "cases"))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Conservation law: friction, contact state changes and the γ = 1 integrator only dissipate, so
// the mechanical energy never rises. Allowed: 1e-4 of the run's energy scale (the contacts'
// geometry is linearised within a step; measured ≤ 2e-5 on the Vajont run-out) and 1e-12 of the
// total (round-off in sums of up to ~1e12 J/m; the static cases show 1e-15). A sliding contact's
// shear spring counts as stretched to its friction force (elastic-plastic), or a contact that
// sticks with force continuity would seem to create ½S²/p_s (4e-3 J/m on the toppling slope
// with its bench at the toe, before it was counted so).
void expectNoEnergyGain(const io::Trace& t) {
  EXPECT_LE(t.largestEnergyGain(), 1e-4 * t.energyScale() + 1e-12 * std::abs(t.energy.front().mechanical()))
      << "energy gained";
}
}  // namespace

class ShippedCase : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedCase, MeetsItsExpectedValues) {
  const model::Scene scene = io::readCase(GetParam());
  ASSERT_FALSE(scene.expectations.empty()) << "a shipped case must carry expected values";
  const io::RunOutcome o = io::runScene(scene, {});
  ASSERT_TRUE(o.completed) << o.failure;
  for (const auto& r : o.expectations) EXPECT_TRUE(r.passed) << r.describe();
  expectNoEnergyGain(o.trace);
}

// A run shortened below an expectation's time does not report a value there: the sliding block's
// d(1 s) = a/2 and d(2 s) = 2a are not checked in a 0.5 s run (its last sample is no answer at
// 1 s), while a time inside the run still is (Hoek & Bray's a = g(sin 30° − cos 30° tan φ)).
TEST(ShippedCaseShortened, ExpectationsPastTheRunsEndAreNotChecked) {
  model::Scene scene = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/cases/sliding_block_30deg.json");
  scene.settings.duration = 0.5;
  scene.expectations.push_back(scene.expectations.front());
  scene.expectations.back().time = 0.5;
  scene.expectations.back().value = *scene.expectations.front().value / 4;  // d = a t²/2 at t = 0.5 s
  const io::RunOutcome o = io::runScene(scene, {});
  ASSERT_TRUE(o.completed) << o.failure;
  ASSERT_EQ(o.expectations.size(), 4u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_FALSE(o.expectations[k].reached) << o.expectations[k].describe();
    EXPECT_FALSE(o.expectations[k].passed);
    EXPECT_NE(o.expectations[k].describe().find("not checked"), std::string::npos) << o.expectations[k].describe();
  }
  EXPECT_TRUE(o.expectations[3].reached);
  EXPECT_TRUE(o.expectations[3].passed) << o.expectations[3].describe();
}

// The Vajont run-out at a residual friction of 6° (calibration/vajont_runout): no energy gained,
// and the mass at rest by 45 s (quoted: the collapse lasted under 45 s, S8 p41). Before the step
// limit was held to the thinnest block, a contact found 4.5 m deep created 1e12 J/m in one step
// and threw the toe wedge kilometres.
TEST(RunOut, VajontDissipatesAndComesToRest) {
  const model::Scene scene = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/calibration/vajont_runout/case.json",
                                          {{"joints.sliding_surface.friction_angle", 6}});
  const io::RunOutcome o = io::runScene(scene, {});
  ASSERT_TRUE(o.completed) << o.failure;
  const double scale = o.trace.energyScale();
  EXPECT_GT(scale, 1e11);  // it did run out: ~3e11 J/m released
  EXPECT_LE(o.trace.largestEnergyGain(), 1e-4 * scale);
  EXPECT_LT(o.trace.energy.back().kinetic, 1e-6 * scale) << "still moving at 45 s";
}

// Rigid blocks (three unknowns, analysis.blocks = "rigid") meet the same expected values: every
// shipped case's closed form or published result holds for rigid bodies (the blocks' elastic
// strain is orders of magnitude below the displacements they check).
TEST_P(ShippedCase, MeetsItsExpectedValuesWithRigidBlocks) {
  model::Scene scene = io::readCase(GetParam());
  scene.settings.rigidBlocks = true;
  const io::RunOutcome o = io::runScene(scene, {});
  ASSERT_TRUE(o.completed) << o.failure;
  for (const auto& r : o.expectations) EXPECT_TRUE(r.passed) << r.describe();
  expectNoEnergyGain(o.trace);
}

INSTANTIATE_TEST_SUITE_P(Cases, ShippedCase, ::testing::ValuesIn(shippedCases()),
                         [](const auto& info) { return fs::path(info.param).stem().string(); });

// The same case run twice gives byte-identical history.csv (issue #2: bisection and NLopt need
// a well-defined function).
TEST(Determinism, HistoryIsByteIdentical) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/sliding_block_40deg.json";
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_det_" + std::to_string(::getpid()));
  std::string first;
  for (int k = 0; k < 2; ++k) {
    io::RunOptions opt;
    opt.outputDir = (dir / std::to_string(k)).string();
    ASSERT_TRUE(io::runScene(io::readCase(path), opt).completed);
    const std::string h = slurp(dir / std::to_string(k) / "history.csv");
    ASSERT_GT(h.size(), 1000u);
    if (k == 0) first = h; else EXPECT_EQ(first, h);
  }
  fs::remove_all(dir);
}
